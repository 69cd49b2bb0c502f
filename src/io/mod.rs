//! File formats handled by the core: OBJ (read and write, with its
//! face-varying data) and OFF (write).
//! PLY and the native `.npz` format are written and read on the Python side
//! (`topomesh.io`), through plyfile and NumPy.

pub mod obj;
mod writer;

pub use obj::{parse_obj, read_obj, write_obj, ObjAttributes, ObjData};
pub use writer::{write_text, TextFormat};

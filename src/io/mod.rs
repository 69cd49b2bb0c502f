//! File formats handled by the core: OBJ (read and write, with its
//! face-varying data) and OFF (write), and the record walk of binary PLY
//! elements of variable record length.
//! PLY headers and the native `.npz` format are written and read on the
//! Python side (`topomesh.io`), with NumPy (plyfile for ASCII and
//! big-endian PLY).

pub mod obj;
pub mod ply;
mod writer;

pub use obj::{parse_obj, read_obj, write_obj, ObjAttributes, ObjData};
pub use writer::{write_text, TextFormat};

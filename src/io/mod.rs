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

use crate::error::{MeshError, Result};
use std::path::Path;

/// The whole file at `path`, as `std::fs::read` reads it, into a buffer
/// whose pages are mapped in one call per chunk before the read
/// (`crate::mesh::populate`): a fresh buffer faulted in page by page cost
/// as much as the copy itself (a 36 MiB PLY file: 20-28 ms read by Python's
/// `f.read()`). A file larger than the memory budget is refused before the
/// allocation.
pub fn read_file(path: &Path) -> Result<Vec<u8>> {
    use std::io::Read;
    let io = |e: std::io::Error| MeshError::Io(format!("{}: cannot read ({e})", path.display()));
    let mut f = std::fs::File::open(path).map_err(io)?;
    let len = f.metadata().map_err(io)?.len();
    crate::budget::check("load", &format!("{} ({len} bytes)", path.display()), len)?;
    let mut v = Vec::with_capacity(len as usize);
    crate::mesh::populate(&mut v, len as usize);
    f.read_to_end(&mut v).map_err(io)?;
    Ok(v)
}

//! Writers for OBJ and OFF (text, polygon faces, float64 written as the
//! shortest decimal that reads back to the same bits).

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use std::io::Write;

/// Text format of [`write_text`].
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum TextFormat {
    Obj,
    Off,
}

/// Writes the exported polygons of `m` (holes left out) as OBJ or OFF.
pub fn write_text<W: Write>(m: &Mesh, format: TextFormat, out: W) -> Result<()> {
    let io = |e: std::io::Error| MeshError::Io(e.to_string());
    let mut w = std::io::BufWriter::with_capacity(1 << 20, out);
    let p = m.to_polygons();
    match format {
        TextFormat::Obj => writeln!(w, "# written by topomesh").map_err(io)?,
        TextFormat::Off => writeln!(w, "OFF\n{} {} {}", m.n_vertices(), p.sizes.len(), m.n_edges()).map_err(io)?,
    }
    let prefix = if format == TextFormat::Obj { "v " } else { "" };
    for q in m.positions() {
        // Debug on f64 prints the shortest decimal that parses back to the
        // same bits, with an exponent for very large or small magnitudes
        writeln!(w, "{prefix}{:?} {:?} {:?}", q.x, q.y, q.z).map_err(io)?;
    }
    let mut k = 0;
    for &s in &p.sizes {
        let face = &p.indices[k..k + s as usize];
        k += s as usize;
        match format {
            TextFormat::Obj => {
                w.write_all(b"f").map_err(io)?;
                for &i in face {
                    write!(w, " {}", i + 1).map_err(io)?;
                }
            }
            TextFormat::Off => {
                write!(w, "{s}").map_err(io)?;
                for &i in face {
                    write!(w, " {i}").map_err(io)?;
                }
            }
        }
        w.write_all(b"\n").map_err(io)?;
    }
    w.flush().map_err(io)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;

    #[test]
    fn obj_and_off_text() {
        let m = primitives::tetrahedron();
        let mut obj = Vec::new();
        write_text(&m, TextFormat::Obj, &mut obj).unwrap();
        let obj = String::from_utf8(obj).unwrap();
        assert_eq!(obj.lines().filter(|l| l.starts_with("v ")).count(), 4);
        assert_eq!(obj.lines().filter(|l| l.starts_with("f ")).count(), 4);
        assert!(obj.contains("v 1.0 1.0 1.0\n"));
        let mut off = Vec::new();
        write_text(&m, TextFormat::Off, &mut off).unwrap();
        let off = String::from_utf8(off).unwrap();
        assert!(off.starts_with("OFF\n4 4 6\n"));
        // values that need all 17 digits survive
        let mut m2 = m.clone();
        m2.positions_mut()[0].x = 0.1 + 0.2;
        let mut obj = Vec::new();
        write_text(&m2, TextFormat::Obj, &mut obj).unwrap();
        let first = String::from_utf8(obj).unwrap().lines().nth(1).unwrap().to_string();
        let x: f64 = first.split_whitespace().nth(1).unwrap().parse().unwrap();
        assert_eq!(x, 0.1 + 0.2);
    }
}

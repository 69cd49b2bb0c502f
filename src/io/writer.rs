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

/// Lines formatted per parallel job of [`write_text`] and `write_obj`.
pub(crate) const TEXT_CHUNK: usize = 1 << 14;

/// Writes the exported polygons of `m` (holes left out) as OBJ or OFF.
/// The lines are formatted in parallel, chunk by chunk, and written in
/// order while the next chunks are formatted: formatting floats one line
/// after another took 200 ms of an OBJ save of 1M triangles (`perf`:
/// mostly `f64`'s shortest-decimal formatting, on one thread).
pub fn write_text<W: Write + Send>(m: &Mesh, format: TextFormat, out: W) -> Result<()> {
    let io = |e: std::io::Error| MeshError::Io(e.to_string());
    let mut w = std::io::BufWriter::with_capacity(1 << 20, out);
    let p = m.to_polygons();
    match format {
        TextFormat::Obj => writeln!(w, "# written by topomesh").map_err(io)?,
        TextFormat::Off => writeln!(w, "OFF\n{} {} {}", m.n_vertices(), p.sizes.len(), m.n_edges()).map_err(io)?,
    }
    let prefix = if format == TextFormat::Obj { "v " } else { "" };
    let pos = m.positions();
    let starts = face_chunk_starts(&p.sizes);
    let (nvc, nfc) = (pos.len().div_ceil(TEXT_CHUNK), starts.len());
    // chunk j: vertex chunk j, then face chunk j - nvc; formatted into its own buffer
    let text = |j: usize| -> Vec<u8> {
        if j < nvc {
            return vertex_lines(pos, j, prefix);
        }
        let mut b = Vec::with_capacity(64 * TEXT_CHUNK);
        let c = j - nvc;
        let mut k = starts[c];
        for &s in &p.sizes[c * TEXT_CHUNK..((c + 1) * TEXT_CHUNK).min(p.sizes.len())] {
            let face = &p.indices[k..k + s as usize];
            k += s as usize;
            // writes to a Vec cannot fail
            let _ = match format {
                TextFormat::Obj => {
                    b.push(b'f');
                    face.iter().try_for_each(|&i| write!(b, " {}", i + 1))
                }
                TextFormat::Off => write!(b, "{s}").and_then(|()| face.iter().try_for_each(|&i| write!(b, " {i}"))),
            };
            b.push(b'\n');
        }
        b
    };
    write_pieces(&mut w, nvc + nfc, text)?;
    w.flush().map_err(io)
}

/// Writes `piece(0)`, `piece(1)`, … `piece(n - 1)` to `w` in order: the
/// pieces are formatted in parallel, a wave of a few per thread at a time,
/// and each wave is written while the next one is formatted.
pub(crate) fn write_pieces<W: Write + Send>(w: &mut W, n: usize, piece: impl Fn(usize) -> Vec<u8> + Sync) -> Result<()> {
    use rayon::prelude::*;
    let wave = 4 * rayon::current_num_threads().max(1);
    let mut done: Vec<Vec<u8>> = Vec::new();
    let mut next = 0;
    while next < n || !done.is_empty() {
        crate::cancel::check()?;
        let range = next..(next + wave).min(n);
        next = range.end;
        let (written, formatted) = rayon::join(
            || done.iter().try_for_each(|b| w.write_all(b)),
            || range.into_par_iter().map(&piece).collect::<Vec<_>>(),
        );
        written.map_err(|e| MeshError::Io(e.to_string()))?;
        done = formatted;
    }
    Ok(())
}

/// The first corner of every chunk of [`TEXT_CHUNK`] faces of `sizes`.
pub(crate) fn face_chunk_starts(sizes: &[u32]) -> Vec<usize> {
    sizes
        .chunks(TEXT_CHUNK)
        .scan(0usize, |k, c| {
            let first = *k;
            *k += c.iter().map(|&s| s as usize).sum::<usize>();
            Some(first)
        })
        .collect()
}

/// `v x y z` lines (`prefix` before each) of the positions of chunk `j` of
/// [`TEXT_CHUNK`] vertices, floats as the shortest decimal that reads back
/// to the same bits (`f64`'s Debug), with an exponent for very large or
/// small magnitudes.
pub(crate) fn vertex_lines(pos: &[glam::DVec3], j: usize, prefix: &str) -> Vec<u8> {
    let mut b = Vec::with_capacity(64 * TEXT_CHUNK);
    for q in &pos[j * TEXT_CHUNK..((j + 1) * TEXT_CHUNK).min(pos.len())] {
        let _ = writeln!(b, "{prefix}{:?} {:?} {:?}", q.x, q.y, q.z); // a Vec takes every write
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;

    /// The lines as the writer wrote them one after another before it ran in parallel.
    fn sequential(m: &Mesh, format: TextFormat) -> Vec<u8> {
        let mut w = Vec::new();
        let p = m.to_polygons();
        match format {
            TextFormat::Obj => writeln!(w, "# written by topomesh").unwrap(),
            TextFormat::Off => writeln!(w, "OFF\n{} {} {}", m.n_vertices(), p.sizes.len(), m.n_edges()).unwrap(),
        }
        let prefix = if format == TextFormat::Obj { "v " } else { "" };
        for q in m.positions() {
            writeln!(w, "{prefix}{:?} {:?} {:?}", q.x, q.y, q.z).unwrap();
        }
        let mut k = 0;
        for &s in &p.sizes {
            let face = &p.indices[k..k + s as usize];
            k += s as usize;
            match format {
                TextFormat::Obj => {
                    w.extend_from_slice(b"f");
                    face.iter().for_each(|&i| write!(w, " {}", i + 1).unwrap());
                }
                TextFormat::Off => {
                    write!(w, "{s}").unwrap();
                    face.iter().for_each(|&i| write!(w, " {i}").unwrap());
                }
            }
            w.extend_from_slice(b"\n");
        }
        w
    }

    #[test]
    fn parallel_text_is_the_sequential_text() {
        // several chunks of vertices and of faces, triangles and quads interleaved, odd coordinates
        let t = primitives::torus(300, 200, 3.0, 1.0).unwrap();
        let p = t.to_polygons();
        let (mut sizes, mut idx) = (Vec::new(), Vec::new());
        for (f, q) in p.indices.chunks(4).enumerate() {
            let q: Vec<i64> = q.iter().map(|&i| i as i64).collect();
            if f % 2 == 0 {
                sizes.extend([3, 3]);
                idx.extend([q[0], q[1], q[2], q[0], q[2], q[3]]);
            } else {
                sizes.push(4);
                idx.extend(q);
            }
        }
        let mut pos = t.positions().to_vec();
        pos[7].x = 0.1 + 0.2;
        pos[8].y = 1e-300;
        pos[9].z = -2.5e17;
        let m = Mesh::from_polygons(pos, &sizes, &idx, crate::mesh::BuildOptions::default()).unwrap();
        assert!(m.n_vertices() > 2 * TEXT_CHUNK && m.n_faces() > 4 * TEXT_CHUNK);
        for format in [TextFormat::Obj, TextFormat::Off] {
            let mut out = Vec::new();
            write_text(&m, format, &mut out).unwrap();
            assert!(out == sequential(&m, format), "{format:?}");
        }
    }

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

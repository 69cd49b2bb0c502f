//! Exports: polygons (lossless), pyvista's padded layout, and triangles for
//! rendering and for the validation peers.

use super::{Mesh, PolygonFaces, POINT};
use rayon::prelude::*;

/// Faces per parallel task of the flat exports.
const BLOCK: usize = 4096;

impl Mesh {
    /// Every non-hole face as its vertex cycle from its first corner, repeats
    /// kept (a self-loop shows as a vertex twice in a row; a one-gon or a
    /// point-sphere as a face of size 1).
    pub fn to_polygons(&self) -> PolygonFaces {
        let mut out = PolygonFaces {
            sizes: Vec::with_capacity(self.n_faces()),
            indices: Vec::with_capacity(self.n_halfedges() + self.n_faces()),
        };
        for f in self.faces() {
            if self.is_hole(f) {
                continue;
            }
            let before = out.indices.len();
            out.indices.extend(self.face_vertices(f).map(|v| v.0));
            out.sizes.push((out.indices.len() - before) as u32);
        }
        out
    }

    /// First exported corner of every face (`n_faces() + 1` entries): a hole
    /// face exports none, a point-sphere one. In parallel (a walk per face),
    /// then one prefix sum.
    pub(crate) fn export_offsets(&self) -> Vec<u32> {
        let next = &self.he_next;
        let deg: Vec<u32> = self
            .f_start
            .par_iter()
            .zip(&self.f_hole)
            .with_min_len(BLOCK)
            .map(|(&s, &hole)| {
                if hole {
                    0
                } else if s & POINT != 0 {
                    1
                } else {
                    let (mut h, mut k) = (next[s as usize], 1u32);
                    while h != s {
                        h = next[h as usize];
                        k += 1;
                    }
                    k
                }
            })
            .collect();
        let mut off = Vec::with_capacity(deg.len() + 1);
        let mut acc = 0u32;
        off.push(0);
        for d in deg {
            acc += d;
            off.push(acc);
        }
        off
    }

    /// [`Mesh::to_polygons`] as the `int64` arrays Python exports, written
    /// in parallel straight into their final buffers (no `u32` copy first):
    /// `(face sizes, flat indices)`, the same values.
    pub fn polygons_i64(&self) -> (Vec<i64>, Vec<i64>) {
        let off = self.export_offsets();
        let nf = self.n_faces();
        let sizes: Vec<i64> = if self.f_hole.iter().any(|&h| h) {
            (0..nf).filter(|&f| !self.f_hole[f]).map(|f| (off[f + 1] - off[f]) as i64).collect()
        } else {
            off.par_windows(2).with_min_len(BLOCK).map(|w| (w[1] - w[0]) as i64).collect()
        };
        let mut idx = vec![0i64; off[nf] as usize];
        let (next, vert) = (&self.he_next, &self.he_vert);
        for_face_blocks(&off, &mut idx, |f, out| {
            let s = self.f_start[f];
            if s & POINT != 0 {
                out[0] = (s & !POINT) as i64;
                return;
            }
            let mut h = s;
            for o in out.iter_mut() {
                *o = vert[h as usize] as i64;
                h = next[h as usize];
            }
        });
        (sizes, idx)
    }

    /// pyvista/VTK cell layout: `[n, i0, .., i(n-1), n, ...]`, holes left out.
    pub fn to_padded_faces(&self) -> Vec<u32> {
        let p = self.to_polygons();
        let mut out = Vec::with_capacity(p.sizes.len() + p.indices.len());
        let mut k = 0;
        for &s in &p.sizes {
            out.push(s);
            out.extend_from_slice(&p.indices[k..k + s as usize]);
            k += s as usize;
        }
        out
    }

    /// Triangles of every non-hole face and the face each came from: the
    /// `tris` and `tri_face` of [`Mesh::triangulate`]. Indices at or above
    /// `n_vertices()` are the points it adds (`Triangulation::points`).
    pub fn triangles(&self) -> (Vec<[u32; 3]>, Vec<u32>) {
        let t = self.triangulate();
        (t.tris, t.tri_face)
    }
}

/// Calls `fill(f, corners of f)` for every face with exported corners
/// (`off` from [`Mesh::export_offsets`]), over blocks of faces in parallel;
/// `out` holds every exported corner.
pub(crate) fn for_face_blocks<T: Send>(off: &[u32], out: &mut [T], fill: impl Fn(usize, &mut [T]) + Sync) {
    let nf = off.len() - 1;
    let mut parts = Vec::with_capacity(nf.div_ceil(BLOCK));
    let mut rest = out;
    for b in (0..nf).step_by(BLOCK) {
        let e = (b + BLOCK).min(nf);
        let (head, tail) = std::mem::take(&mut rest).split_at_mut((off[e] - off[b]) as usize);
        parts.push((b, e, head));
        rest = tail;
    }
    parts.into_par_iter().for_each(|(b, e, part)| {
        let base = off[b] as usize;
        for f in b..e {
            let (s, t) = (off[f] as usize - base, off[f + 1] as usize - base);
            if t > s {
                fill(f, &mut part[s..t]);
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use crate::schemes::hosts::test_meshes as tm;

    /// The parallel exports equal the sequential ones on the corpus (point-spheres,
    /// self-loops, one- and two-gons) and the open meshes (hole faces left out).
    #[test]
    fn flat_exports_equal_the_sequential_ones() {
        let mut meshes = tm::corpus();
        meshes.extend(tm::open_meshes());
        meshes.push(("empty", crate::Mesh::new()));
        for (name, m) in meshes {
            let p = m.to_polygons();
            let (s, i) = m.polygons_i64();
            assert_eq!(s, p.sizes.iter().map(|&x| x as i64).collect::<Vec<_>>(), "{name}");
            assert_eq!(i, p.indices.iter().map(|&x| x as i64).collect::<Vec<_>>(), "{name}");
            assert_eq!(m.corner_twins(), m.corner_twins_sequential(), "{name}");
        }
    }
}

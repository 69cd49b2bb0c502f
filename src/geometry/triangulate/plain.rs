//! The fast path of `Mesh.triangles()` (issue 19): on a mesh whose faces are
//! all triangles of three distinct vertices, without holes or multi-edges,
//! [`triangulate`](super::triangulate) returns the faces themselves, each
//! from its first corner, and adds no point. Checking that and writing the
//! faces straight into the caller's buffer skips the per-block vectors, the
//! source-face column and the conversion copy.

use super::multi_edge_copies;
use crate::mesh::{Mesh, POINT};
use rayon::prelude::*;

/// Faces per parallel task.
const BLOCK: usize = 4096;

impl Mesh {
    /// Whether [`Mesh::triangulate`] of this mesh is exactly its faces (see
    /// the module docs): every face a triangle of distinct vertices, no hole
    /// face, no multi-edge.
    pub fn triangles_are_faces(&self) -> bool {
        let (next, vert) = (&self.he_next, &self.he_vert);
        !self.f_hole.iter().any(|&h| h)
            && self.f_start.par_iter().with_min_len(BLOCK).all(|&s| {
                if s & POINT != 0 {
                    return false;
                }
                let a = next[s as usize];
                let b = next[a as usize];
                let (x, y, z) = (vert[s as usize], vert[a as usize], vert[b as usize]);
                a != s && b != s && next[b as usize] == s && x != y && y != z && x != z
            })
            && multi_edge_copies(self).is_empty()
    }

    /// Writes every face's three vertices, from its first corner, into
    /// `out` (`3·n_faces()` entries). Only meaningful where
    /// [`Mesh::triangles_are_faces`] holds.
    pub fn write_triangle_faces(&self, out: &mut [i64]) {
        assert_eq!(out.len(), 3 * self.n_faces(), "write_triangle_faces: buffer size");
        let (next, vert) = (&self.he_next, &self.he_vert);
        out.par_chunks_mut(3 * BLOCK).enumerate().for_each(|(k, chunk)| {
            for (i, row) in chunk.chunks_exact_mut(3).enumerate() {
                let s = self.f_start[k * BLOCK + i] as usize;
                let a = next[s] as usize;
                row[0] = vert[s] as i64;
                row[1] = vert[a] as i64;
                row[2] = vert[next[a] as usize] as i64;
            }
        });
    }
}

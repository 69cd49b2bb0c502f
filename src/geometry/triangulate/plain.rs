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

    /// Necessary for [`Mesh::triangles_are_faces`], in constant time: three
    /// half-edges per face (so a mesh with other faces is not walked, nor its
    /// edges sorted for multi-edges) and no hole face.
    pub fn may_be_plain_triangles(&self) -> bool {
        self.n_halfedges() == 3 * self.n_faces() && self.n_holes() == 0
    }

    /// [`Mesh::triangles_are_faces`] and [`Mesh::write_triangle_faces`] in
    /// one walk over the faces, with the multi-edge search running beside
    /// it (`rayon::join`): on an all-triangle mesh the check and the write
    /// had been two walks and a sequential sort one after the other. Returns
    /// whether the faces are the triangles; when not, `out` holds garbage.
    pub fn write_triangle_faces_if_plain(&self, out: &mut [i64]) -> bool {
        assert_eq!(out.len(), 3 * self.n_faces(), "write_triangle_faces_if_plain: buffer size");
        if !self.may_be_plain_triangles() {
            return false;
        }
        let (next, vert) = (&self.he_next, &self.he_vert);
        let (plain, no_multi) = rayon::join(
            || {
                out.par_chunks_mut(3 * BLOCK).enumerate().all(|(k, chunk)| {
                    chunk.chunks_exact_mut(3).enumerate().all(|(i, row)| {
                        let s = self.f_start[k * BLOCK + i];
                        if s & POINT != 0 {
                            return false;
                        }
                        let a = next[s as usize];
                        let b = next[a as usize];
                        let (x, y, z) = (vert[s as usize], vert[a as usize], vert[b as usize]);
                        (row[0], row[1], row[2]) = (x as i64, y as i64, z as i64);
                        a != s && b != s && next[b as usize] == s && x != y && y != z && x != z
                    })
                })
            },
            || multi_edge_copies(self).is_empty(),
        );
        plain && no_multi
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

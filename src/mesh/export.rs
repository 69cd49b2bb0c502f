//! Exports: polygons (lossless), pyvista's padded layout, and triangles for
//! rendering and for the validation peers.

use super::{Mesh, PolygonFaces};

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

//! Step 5 (VII.3 step 5, CreatePipe): the window corners, where each pipe
//! leaves its face. A pipe joins a face's remeshing face to its offset face
//! with one quad per side; a window corner is its offset corner projected
//! back onto the face plane, so every pipe wall is a planar quad
//! perpendicular to its face (module docs of [`super`], step 2).

use super::connect::Inner;
use super::inset::{corner_sides, inside_corner};
use super::offset::Plan;
use crate::mesh::Mesh;
use glam::DVec3;

/// The window corner of every half-edge (its tail's corner in its face),
/// in half-edge order.
pub(super) fn window_corners(m: &Mesh, pl: &Plan, inner: &Inner) -> Vec<DVec3> {
    let pos = m.positions();
    let mut out_pos = Vec::with_capacity(m.n_halfedges());
    // window corners: the offset corners (after merging and welding)
    // projected back onto the face plane, so every pipe wall is a planar
    // quad perpendicular to its face (module docs); the inset corner
    // where the projection would leave less than D/2 of frame (depth
    // below the face, distance from the corner's two sides) or the
    // corner is not convex
    if pl.per_face {
        // per-face corners lie straight below their inset corners: every
        // pipe is a right prism over its window (module docs, "Per-face
        // corners")
        return pl.q.clone();
    }
    for h in m.halfedges() {
        let f = m.face(h).idx();
        let (n, d, dd) = (pl.face_n[f], pl.face_d[f], pl.face_depth[f]);
        let pv = pos[m.vertex(h).idx()];
        let r = inner.pos[inner.rep[pl.group[h.idx()] as usize] as usize];
        let depth = (pv - r).dot(n);
        let x = r + depth * n;
        let (w1, w2, convex) = corner_sides(m, n, h);
        let ok = convex && depth >= 0.5 * dd && inside_corner(x, pv, (w1, w2), 0.5 * d);
        out_pos.push(if ok { x } else { pl.q[h.idx()] });
    }
    out_pos
}

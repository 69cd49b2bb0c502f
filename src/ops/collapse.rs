//! CollapseEdge (dissertation ch. III.6).

use super::{check_edge, follow_vertex};
use crate::error::{MeshError, Result};
use crate::mesh::{Corner, EdgeId, HalfedgeId, Mesh, VertexId};

/// What [`Mesh::collapse_edge`] did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Collapse {
    /// The merged vertex (at the edge's midpoint), under its id after the call.
    pub vertex: VertexId,
    /// The vertex that was merged into it (its id before the call); the last
    /// vertex took this id.
    pub removed: VertexId,
    /// Edges inserted from v1 to v2's neighbours (step 4).
    pub inserted: usize,
    /// Edges of v2 deleted (step 5), `e` included.
    pub deleted: usize,
}

impl Mesh {
    /// **CollapseEdge(e)** (ch. III.6): merges the ends v1, v2 of `e` into v1
    /// at the midpoint. For each corner of v2 whose following corner is not
    /// at v1, InsertEdge(that following corner, c1) with c1 the corner where
    /// `e` starts; then DeleteEdgeWithCleanup on every edge of v2 (which
    /// removes v2). The corners of v2 are visited clockwise from the one after
    /// `e`, so the new edges take v2's place in v1's rotation in order.
    ///
    /// v1 is the tail of `2e`, unless v2 has a self-loop and v1 has none, in
    /// which case the roles swap.
    ///
    /// Contract, with s ≥ 1 the number of corners of v2 followed by a corner
    /// at v1 (1 for an edge with no parallel edge; each two-gon on `e` adds
    /// one): V−1, E−s, F−(s−1), components and genus unchanged — provided
    /// every edge parallel to `e` bounds a chain of two-gons with it (the
    /// algorithm deletes parallel edges; a parallel edge around a handle
    /// would cut it). A component whose only vertices are v1 and v2 becomes
    /// a point-sphere. Preconditions: `e` is not a self-loop, and not both
    /// ends carry self-loops.
    pub fn collapse_edge(&mut self, e: EdgeId) -> Result<Collapse> {
        check_edge(self, e)?;
        if self.is_self_loop(e) {
            return Err(MeshError::Precondition(format!("collapse_edge: edge {} is a self-loop", e.0)));
        }
        let has_loop = |m: &Mesh, v: VertexId| m.vertex_halfedges(v).any(|h| m.head(h) == v);
        let mut h: HalfedgeId = e.halfedge();
        if has_loop(self, self.head(h)) {
            if has_loop(self, self.vertex(h)) {
                return Err(MeshError::Precondition(format!(
                    "collapse_edge: both ends of edge {} ({} and {}) carry self-loops",
                    e.0,
                    self.vertex(h).0,
                    self.head(h).0
                )));
            }
            h = h.twin();
        }
        let (v1, v2) = (self.vertex(h), self.head(h));
        let (a, b) = (self.position(v1), self.position(v2));
        let mut mid = (a + b) * 0.5;
        if !mid.is_finite() {
            mid = a * 0.5 + b * 0.5; // the sum overflowed (coordinates near f64's limit)
        }
        // v2's corners clockwise from the one after e: x, next(twin(x)), ...
        let mut targets = Vec::new();
        let mut x = self.next(h);
        while x != h.twin() {
            let c = self.next(x);
            if self.vertex(c) != v1 {
                targets.push(c);
            }
            x = self.next(x.twin());
        }
        for &c in &targets {
            self.insert_edge(Corner::Halfedge(c), Corner::Halfedge(h))?;
        }
        let deg = self.valence(v2);
        let (mut v1_now, mut v2_now) = (Some(v1), Some(v2));
        for _ in 0..deg {
            let Some(out) = v2_now.and_then(|v| self.vertex_halfedge(v)) else { break };
            let nv = self.n_vertices();
            let removed = self.delete_edge_with_cleanup(out.edge())?;
            v1_now = v1_now.and_then(|v| follow_vertex(v, nv, &removed));
            v2_now = v2_now.and_then(|v| follow_vertex(v, nv, &removed));
        }
        // v1 goes too only when every edge of the component ran between v1
        // and v2: what is left of it is a point-sphere
        let v1_now = match v1_now {
            Some(v) => {
                self.set_position(v, mid);
                v
            }
            None => self.create_vertex(mid)?.0,
        };
        Ok(Collapse { vertex: v1_now, removed: v2, inserted: targets.len(), deleted: deg })
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use crate::mesh::{Corner, EdgeId, FaceId};
    use crate::primitives;

    #[test]
    fn triangle_and_quad_meshes() {
        for m0 in [primitives::icosahedron(), primitives::cube(), primitives::torus(6, 4, 1.0, 0.4).unwrap()] {
            for e in [0u32, 3, 7] {
                let mut m = m0.clone();
                let (v, ed, f, c, g) = counts(&m);
                let h = EdgeId(e).halfedge();
                let mid = (m.position(m.vertex(h)) + m.position(m.head(h))) * 0.5;
                let tri_sides = [m.face(h), m.face(h.twin())].iter().filter(|&&f| m.face_degree(f) == 3).count();
                let r = m.collapse_edge(EdgeId(e)).unwrap();
                assert_eq!(counts(&m), (v - 1, ed - 1, f, c, g));
                assert!(r.removed == m0.vertex(h) || r.removed == m0.head(h));
                assert_eq!(r.inserted + 1, r.deleted);
                assert!((m.position(r.vertex) - mid).length() < 1e-12);
                // each triangle beside e became a two-gon
                assert_eq!(m.face_size_histogram().get(&2).copied().unwrap_or(0), tri_sides);
            }
        }
    }

    #[test]
    fn two_gon_collapses_away() {
        // a cube with a doubled edge (two-gon between edge 0 and its copy)
        let mut m = primitives::cube();
        let h = EdgeId(0).halfedge();
        let c1 = Corner::Halfedge(h);
        let c2 = Corner::Halfedge(m.next(h));
        m.insert_edge(c1, c2).unwrap();
        let (v, e, f, c, g) = counts(&m);
        assert_eq!(m.face_size_histogram().get(&2), Some(&1));
        m.collapse_edge(EdgeId(0)).unwrap();
        // s = 2: the parallel edge goes too, and the two-gon with it
        assert_eq!(counts(&m), (v - 1, e - 2, f - 1, c, g));
        assert_eq!(m.face_size_histogram().get(&2), None);
    }

    #[test]
    fn lone_dipole_becomes_a_point_sphere() {
        let mut m = digon_sphere();
        let r = m.collapse_edge(EdgeId(0)).unwrap();
        assert_eq!(counts(&m), (1, 0, 1, 1, 0));
        assert_eq!(m.point_sphere_face(r.vertex), Some(FaceId(0)));
    }

    #[test]
    fn self_loops() {
        let mut m = loop_sphere();
        assert!(m.collapse_edge(EdgeId(0)).is_err());
        // an edge whose head carries a self-loop: the roles swap
        let mut m = primitives::cube();
        let h = m.face_halfedge(FaceId(0)).unwrap();
        let v2 = m.head(h);
        let c = Corner::Halfedge(m.next(h));
        m.insert_edge(c, c).unwrap();
        let (v, e, f, cc, g) = counts(&m);
        let r = m.collapse_edge(h.edge()).unwrap();
        assert_eq!(counts(&m), (v - 1, e - 1, f, cc, g));
        assert_eq!(m.n_self_loops(), 1);
        assert_ne!(r.removed, v2);
    }
}

//! SubdivideEdge (dissertation ch. III.2).

use super::check_edge;
use crate::error::{MeshError, Result};
use crate::mesh::{Corner, EdgeId, HalfedgeId, Mesh, VertexId};

/// What [`Mesh::subdivide_edge`] made of edge `e` = (v1 → v2, its half-edge `2e`).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct EdgeSplit {
    /// The new vertex vm.
    pub vertex: VertexId,
    /// v1 → vm, in the face that held `2e` (its corner at v1).
    pub first: HalfedgeId,
    /// vm → v2, in the face that held `2e` (its corner at vm). Its twin
    /// v2 → vm is the corner at v2 of the face that held `2e + 1`.
    pub second: HalfedgeId,
}

impl EdgeSplit {
    /// The corner a half-edge of the split edge stood for, after the split:
    /// `2e` (corner at v1) → `first`, `2e + 1` (corner at v2) → twin of
    /// `second`; any other half-edge is unchanged.
    pub fn remap(&self, e: EdgeId, h: HalfedgeId) -> HalfedgeId {
        if h == e.halfedge() {
            self.first
        } else if h == e.halfedge().twin() {
            self.second.twin()
        } else {
            h
        }
    }
}

impl Mesh {
    /// **SubdivideEdge(e)** (ch. III.2): a new vertex at `(1 − t)·v1 + t·v2`
    /// on edge `e` (v1 = tail of `2e`), by CreateVertex(pm), InsertEdge(c1, cm),
    /// InsertEdge(c2, cm), DeleteEdge(e). Self-loops (v1 = v2) are split too:
    /// a one-gon becomes a two-gon.
    ///
    /// Contract: V+1, E+1, F, components and genus unchanged; each of the two
    /// faces beside `e` gains one corner. Ids: every vertex, face and every
    /// half-edge of another edge keeps its id; edge `e` now is vm–v2 (its
    /// `2e + 1` = [`EdgeSplit::second`]) and the new last edge is v1–vm
    /// (its `2e'` = [`EdgeSplit::first`]). `t` must lie in [0, 1].
    pub fn subdivide_edge(&mut self, e: EdgeId, t: f64) -> Result<EdgeSplit> {
        check_edge(self, e)?;
        if !(0.0..=1.0).contains(&t) {
            return Err(MeshError::InvalidArgument(format!("subdivide_edge: t = {} is not in [0, 1]", crate::error::num(t))));
        }
        let h = e.halfedge();
        let (v1, v2) = (self.vertex(h), self.head(h));
        let pm = self.position(v1).lerp(self.position(v2), t);
        let (vm, _) = self.create_vertex(pm)?;
        let e1 = self.insert_edge(Corner::Halfedge(h), Corner::Point(vm))?;
        // vm's only corner is now the side of e1 leaving it; the corner at v2
        // follows h (for a one-gon that is the spike just inserted)
        let cm = e1.halfedge().twin();
        let c2 = self.next(h);
        let e2 = self.insert_edge(Corner::Halfedge(c2), Corner::Halfedge(cm))?;
        debug_assert_eq!(e2.idx(), self.n_edges() - 1);
        self.delete_edge(e)?;
        // DeleteEdge moved the last edge, e2, into e's id
        Ok(EdgeSplit { vertex: vm, first: e1.halfedge(), second: e.halfedge().twin() })
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use crate::mesh::{EdgeId, FaceId};
    use crate::primitives;

    #[test]
    fn contract_on_cube_edges() {
        let mut m = primitives::cube();
        for e in 0..12 {
            let (v, ed, f, c, g) = counts(&m);
            let h = EdgeId(e).halfedge();
            let (fa, fb) = (m.face(h), m.face(h.twin()));
            let (da, db) = (m.face_degree(fa), m.face_degree(fb));
            let (p1, p2) = (m.position(m.vertex(h)), m.position(m.head(h)));
            let s = m.subdivide_edge(EdgeId(e), 0.25).unwrap();
            assert_eq!(counts(&m), (v + 1, ed + 1, f, c, g));
            assert_eq!(m.face_degree(fa), da + 1);
            assert_eq!(m.face_degree(fb), db + 1);
            assert_eq!(m.face(s.first), fa);
            assert_eq!(m.face(s.second), fa);
            assert_eq!(m.face(s.second.twin()), fb);
            assert_eq!(m.next(s.first), s.second);
            assert_eq!(m.head(s.first), s.vertex);
            assert!((m.position(s.vertex) - (p1 * 0.75 + p2 * 0.25)).length() < 1e-12);
        }
        assert_eq!(m.face_size_histogram().get(&8), Some(&6));
    }

    #[test]
    fn self_loop_one_gon_becomes_two_gon() {
        let mut m = loop_sphere();
        let s = m.subdivide_edge(EdgeId(0), 0.5).unwrap();
        assert_eq!(counts(&m), (2, 2, 2, 1, 0));
        assert_eq!(m.n_self_loops(), 0);
        assert_eq!(m.face_size_histogram().get(&2), Some(&2));
        assert_eq!(m.face_degree(m.face(s.first)), 2);
    }

    #[test]
    fn two_gon_becomes_triangle() {
        let mut m = digon_sphere();
        m.subdivide_edge(EdgeId(1), 0.5).unwrap();
        assert_eq!(counts(&m), (3, 3, 2, 1, 0));
        assert_eq!(m.face_degree(FaceId(0)), 3);
        assert_eq!(m.face_degree(FaceId(1)), 3);
    }

    #[test]
    fn bad_arguments() {
        let mut m = primitives::cube();
        assert!(m.subdivide_edge(EdgeId(12), 0.5).is_err());
        assert!(m.subdivide_edge(EdgeId(0), 1.5).is_err());
        assert!(m.subdivide_edge(EdgeId(0), f64::NAN).is_err());
        assert_eq!(m, primitives::cube());
    }
}

//! ConnectEdges (dissertation ch. III.5).

use super::check_halfedge;
use crate::error::{MeshError, Result};
use crate::mesh::{Corner, EdgeId, FaceId, HalfedgeId, Mesh};

impl Mesh {
    /// **ConnectEdges({e1, f1}, {e2, f2})** (ch. III.5) on two half-edges
    /// `h1`, `h2`: InsertEdge from the corner where `h1` starts to the corner
    /// where `h2` ends, then InsertEdge from the corner where `h1` ends to the
    /// corner where `h2` starts. Returns the two edges and the new face,
    /// bounded by `h1`, `h2` and the two edges.
    ///
    /// Contract: E+2. Same face: it splits in three, F+2, genus unchanged.
    /// Two faces: the first edge merges them (a handle, or a bridge between
    /// components) and the second splits the result: F unchanged, and genus
    /// +1 (one component) or components −1 (two). Existing ids are all kept.
    /// Precondition: `h1 ≠ h2`.
    pub fn connect_edges(&mut self, h1: HalfedgeId, h2: HalfedgeId) -> Result<(EdgeId, EdgeId, FaceId)> {
        check_halfedge(self, h1)?;
        check_halfedge(self, h2)?;
        if h1 == h2 {
            return Err(MeshError::Precondition(format!("connect_edges: both half-edges are {}", h1.0)));
        }
        let end2 = self.next(h2);
        let ea = self.insert_edge(Corner::Halfedge(h1), Corner::Halfedge(end2))?;
        let end1 = self.next(h1);
        let eb = self.insert_edge(Corner::Halfedge(end1), Corner::Halfedge(h2))?;
        Ok((ea, eb, self.face(h1)))
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use crate::mesh::{EdgeId, FaceId, HalfedgeId};
    use crate::primitives;

    #[test]
    fn same_face_splits_in_three() {
        let mut m = primitives::cube();
        let h: Vec<HalfedgeId> = m.face_halfedges(FaceId(0)).collect();
        let (v, e, f, c, g) = counts(&m);
        let (_, _, nf) = m.connect_edges(h[0], h[2]).unwrap();
        assert_eq!(counts(&m), (v, e + 2, f + 2, c, g));
        // the new face is the quad h0, edge, h2, edge
        assert_eq!(m.face_degree(nf), 4);
        assert_eq!(m.face(h[2]), nf);
        // adjacent half-edges: the second edge is a self-loop at their shared vertex
        let mut m = primitives::cube();
        let h: Vec<HalfedgeId> = m.face_halfedges(FaceId(0)).collect();
        m.connect_edges(h[0], h[1]).unwrap();
        assert_eq!(counts(&m), (v, e + 2, f + 2, c, g));
        assert_eq!(m.n_self_loops(), 1);
    }

    #[test]
    fn two_faces_make_a_handle() {
        let mut m = primitives::cube();
        let a = m.face_halfedge(FaceId(0)).unwrap();
        let b = m.face_halfedge(FaceId(1)).unwrap();
        let (v, e, f, c, g) = counts(&m);
        let (_, _, nf) = m.connect_edges(a, b).unwrap();
        assert_eq!(counts(&m), (v, e + 2, f, c, g + 1));
        assert_eq!(m.face_degree(nf), 4);
    }

    #[test]
    fn degenerate_inputs() {
        // the two sides of one edge of a two-gon sphere
        let mut m = digon_sphere();
        let h = EdgeId(0).halfedge();
        m.connect_edges(h, h.twin()).unwrap();
        let (v, e, _, c, _) = counts(&m);
        assert_eq!((v, e, c), (2, 4, 1));
        // a self-loop with itself across: the loop sphere's two one-gons
        let mut m = loop_sphere();
        let h = EdgeId(0).halfedge();
        m.connect_edges(h, h.twin()).unwrap();
        assert_eq!(counts(&m), (1, 3, 2, 1, 1));
        assert!(m.connect_edges(h, h).is_err());
    }
}

//! DeleteEdgeWithCleanup (dissertation ch. III.1).

use super::check_edge;
use crate::error::Result;
use crate::mesh::{EdgeId, Mesh, VertexId};

impl Mesh {
    /// **DeleteEdgeWithCleanup(e)** (ch. III.1): DeleteEdge(e), then
    /// DeleteVertex on each end vertex the deletion left as a point-sphere.
    ///
    /// Returns the removed vertices in removal order; each removal moved the
    /// then-last vertex into the removed id (see `ops::follow_vertex`).
    ///
    /// Contract: E−1 and the effect of DeleteEdge (different faces merge: F−1;
    /// the same face on both sides separates: F+1 and genus −1 or components
    /// +1); then for each of the k ∈ {0, 1, 2} end vertices left without edges:
    /// V−k, F−k, components −k. Edge ids as DeleteEdge (the last edge takes `e`).
    pub fn delete_edge_with_cleanup(&mut self, e: EdgeId) -> Result<Vec<VertexId>> {
        check_edge(self, e)?;
        let h = e.halfedge();
        let (va, vb) = (self.vertex(h), self.head(h));
        self.delete_edge(e)?;
        let mut ends = vec![va];
        if vb != va {
            ends.push(vb);
        }
        let mut removed = Vec::new();
        for i in 0..ends.len() {
            let v = ends[i];
            if self.point_sphere_face(v).is_some() {
                let last = VertexId::new(self.n_vertices() - 1);
                self.delete_vertex(v)?;
                removed.push(v);
                for w in ends[i + 1..].iter_mut() {
                    if *w == last {
                        *w = v;
                    }
                }
            }
        }
        Ok(removed)
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use crate::mesh::{Corner, EdgeId, Mesh};
    use crate::primitives;
    use glam::DVec3;

    #[test]
    fn ordinary_edge_merges_two_faces() {
        let mut m = primitives::cube();
        let (v, e, f, c, g) = counts(&m);
        let removed = m.delete_edge_with_cleanup(EdgeId(0)).unwrap();
        assert!(removed.is_empty());
        assert_eq!(counts(&m), (v, e - 1, f - 1, c, g));
    }

    #[test]
    fn dangling_edge_removes_its_point_sphere() {
        // a cube with a dangling edge to a new vertex inside face 0
        let mut m = primitives::cube();
        let (v0, _) = m.create_vertex(DVec3::new(0., 0., -1.)).unwrap();
        let c = m.corner(crate::FaceId(0), 0).unwrap();
        let e = m.insert_edge(c, Corner::Point(v0)).unwrap();
        let before = counts(&m);
        let removed = m.delete_edge_with_cleanup(e).unwrap();
        assert_eq!(removed, vec![v0]);
        assert_eq!(counts(&m), (before.0 - 1, before.1 - 1, before.2, before.3, before.4));
        assert_eq!(counts(&m), counts(&primitives::cube()));
    }

    #[test]
    fn lone_edge_component_disappears() {
        // two point-spheres joined by an edge: deleting it removes both
        let mut m = primitives::cube();
        let (a, _) = m.create_vertex(DVec3::X * 5.).unwrap();
        let (b, _) = m.create_vertex(DVec3::X * 6.).unwrap();
        let e = m.insert_edge(Corner::Point(a), Corner::Point(b)).unwrap();
        assert_eq!(m.n_components(), 2);
        let removed = m.delete_edge_with_cleanup(e).unwrap();
        assert_eq!(removed.len(), 2);
        assert_eq!(counts(&m), counts(&primitives::cube()));
    }

    #[test]
    fn self_loop_and_two_gon() {
        // self-loop sphere: deleting the loop leaves a point-sphere, cleaned up
        let mut m = loop_sphere();
        assert_eq!(counts(&m), (1, 1, 2, 1, 0));
        let removed = m.delete_edge_with_cleanup(EdgeId(0)).unwrap();
        assert_eq!(removed.len(), 1);
        assert_eq!(m, Mesh::new());
        // two-gon sphere: deleting one edge of the double edge leaves a dangling-free edge
        let mut m = digon_sphere();
        assert_eq!(counts(&m), (2, 2, 2, 1, 0));
        assert!(m.delete_edge_with_cleanup(EdgeId(0)).unwrap().is_empty());
        assert_eq!(counts(&m), (2, 1, 1, 1, 0));
        // the last edge: both ends become point-spheres and go
        assert_eq!(m.delete_edge_with_cleanup(EdgeId(0)).unwrap().len(), 2);
        assert_eq!(counts(&m), (0, 0, 0, 0, 0));
    }
}

//! CreateFaceManifold (dissertation ch. III.4).

use crate::error::{MeshError, Result};
use crate::mesh::{Corner, FaceId, Mesh, VertexId};
use glam::DVec3;

/// What [`Mesh::create_face_manifold`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FaceManifold {
    /// The new vertices, one per point, in input order.
    pub vertices: Vec<VertexId>,
    /// The face running through the points in the given order.
    pub front: FaceId,
    /// The face running through them in reverse order (`front` itself for one point).
    pub back: FaceId,
    /// The corner of the first point in the front face.
    pub front_corner: Corner,
    /// The corner of the first point in the back face.
    pub back_corner: Corner,
}

impl Mesh {
    /// **CreateFaceManifold(p0, …, pN−1)** (ch. III.4): a new sphere of two
    /// faces sharing N vertices, by N × CreateVertex and N × InsertEdge
    /// (c_i, c_(i+1) mod N). One point gives a point-sphere (front = back).
    ///
    /// Contract: V+N, E+N (E+0 for N = 1), F+2 (F+1 for N = 1),
    /// components +1, genus unchanged. Existing ids are all kept.
    pub fn create_face_manifold(&mut self, points: &[DVec3]) -> Result<FaceManifold> {
        let n = points.len();
        if n == 0 {
            return Err(MeshError::InvalidArgument("create_face_manifold: no points".into()));
        }
        if let Some(i) = points.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::InvalidArgument(format!("create_face_manifold: point {i} is not finite")));
        }
        let mut vertices = Vec::with_capacity(n);
        for &p in points {
            vertices.push(self.create_vertex(p)?.0);
        }
        if n == 1 {
            let c = Corner::Point(vertices[0]);
            let f = self.corner_face(c);
            return Ok(FaceManifold { vertices, front: f, back: f, front_corner: c, back_corner: c });
        }
        // a chain v0 - v1 - ... - vN-1: c_i is the corner of v_i in the one face
        let mut corners: Vec<Corner> = vertices.iter().map(|&v| Corner::Point(v)).collect();
        for i in 1..n {
            let e = self.insert_edge(corners[i - 1], corners[i])?;
            if i == 1 {
                corners[0] = Corner::Halfedge(e.halfedge());
            }
            corners[i] = Corner::Halfedge(e.halfedge().twin());
        }
        // closing the chain splits its face into the front and back faces
        let e = self.insert_edge(corners[n - 1], corners[0])?;
        let (front_corner, back_corner) = (corners[0], Corner::Halfedge(e.halfedge().twin()));
        Ok(FaceManifold {
            vertices,
            front: self.corner_face(front_corner),
            back: self.corner_face(back_corner),
            front_corner,
            back_corner,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use crate::mesh::{Corner, Mesh};
    use crate::primitives;
    use glam::DVec3;

    #[test]
    fn contract_and_orientation() {
        for n in 1..7usize {
            let mut m = primitives::cube();
            let (v, e, f, c, g) = counts(&m);
            let pts: Vec<DVec3> = (0..n).map(|i| {
                let a = i as f64 / n as f64 * std::f64::consts::TAU;
                DVec3::new(a.cos(), a.sin(), 5.0)
            }).collect();
            let fm = m.create_face_manifold(&pts).unwrap();
            let n = n as i64;
            let (de, df) = if n == 1 { (0, 1) } else { (n, 2) };
            assert_eq!(counts(&m), (v + n, e + de, f + df, c + 1, g));
            let front: Vec<_> = m.face_vertices(fm.front).collect();
            assert_eq!(front.len(), n as usize);
            // the front face runs through the points in order, from the first
            let k = front.iter().position(|&x| x == fm.vertices[0]).unwrap();
            for i in 0..n as usize {
                assert_eq!(front[(k + i) % n as usize], fm.vertices[i]);
            }
            assert_eq!(m.corner_face(fm.front_corner), fm.front);
            assert_eq!(m.corner_vertex(fm.front_corner), fm.vertices[0]);
            assert_eq!(m.corner_vertex(fm.back_corner), fm.vertices[0]);
            if n >= 3 {
                assert!(m.face_newell(fm.front).z > 0.0 && m.face_newell(fm.back).z < 0.0);
            }
            if let (Corner::Halfedge(a), Corner::Halfedge(b)) = (fm.front_corner, fm.back_corner) {
                // the back face runs the other way round
                assert_eq!(m.head(a), fm.vertices[1]);
                assert_eq!(m.head(b), fm.vertices[n as usize - 1]);
            }
        }
        assert!(Mesh::new().create_face_manifold(&[]).is_err());
    }
}

//! CreatePipe (dissertation ch. III.3), with the face-size equalization its
//! text leaves to a pre-processing step.

use super::check_halfedge;
use crate::error::{MeshError, Result};
use crate::mesh::{Corner, EdgeId, FaceId, HalfedgeId, Mesh};

/// What [`Mesh::create_pipe`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Pipe {
    /// Edges added to the smaller face by SubdivideEdge before piping.
    pub subdivisions: usize,
    /// The pipe's edges: edge i joins corner i of the first face with
    /// corner −i (mod N) of the second.
    pub edges: Vec<EdgeId>,
    /// The pipe's quads, one per corner of the first face: quad i holds the
    /// first face's side from corner i to corner i + 1 (this half-edge).
    pub sides: Vec<HalfedgeId>,
}

impl Mesh {
    /// Corners a, b of two distinct faces, checked.
    fn pipe_faces(&self, c1: Corner, c2: Corner, what: &str) -> Result<(FaceId, FaceId)> {
        for c in [c1, c2] {
            match c {
                Corner::Halfedge(h) => check_halfedge(self, h)?,
                Corner::Point(v) if v.idx() < self.n_vertices() && self.point_sphere_face(v).is_some() => {}
                Corner::Point(v) => {
                    return Err(MeshError::InvalidArgument(format!("{what}: vertex {} is not a point-sphere", v.0)))
                }
            }
        }
        let (f1, f2) = (self.corner_face(c1), self.corner_face(c2));
        if f1 == f2 {
            return Err(MeshError::Precondition(format!("{what}: both corners are in face {}; a pipe needs two faces", f1.0)));
        }
        Ok((f1, f2))
    }

    /// Subdivides edges of the smaller of the two faces (the longest first,
    /// at its midpoint) until both have as many corners; updates the two
    /// corners to what they stand for after each split. Returns the number
    /// of splits. Sides shared with the larger face are never split (that
    /// would grow both); a side with the smaller face on both of its sides
    /// grows it by two. When that leaves no way to equalize, it is an error
    /// and nothing changes.
    pub(crate) fn equalize_faces(&mut self, c1: &mut Corner, c2: &mut Corner, what: &str) -> Result<usize> {
        let (f1, f2) = self.pipe_faces(*c1, *c2, what)?;
        let (n1, n2) = (self.face_degree(f1), self.face_degree(f2));
        if n1 == n2 {
            return Ok(0);
        }
        let first_small = n1 < n2;
        let (small, large) = if first_small { (f1, f2) } else { (f2, f1) };
        let Some(start) = self.face_halfedge(small) else {
            return Err(MeshError::Precondition(format!(
                "{what}: face {} is a point-sphere; it cannot be matched with the {}-gon face {}",
                small.0,
                n1.max(n2),
                large.0
            )));
        };
        // which sides can grow the smaller face alone?
        let free = |m: &Mesh, h: HalfedgeId| {
            let t = m.face(h.twin());
            t != m.face(h) && t != large
        };
        let diff = n1.abs_diff(n2);
        let has_free = self.face_halfedges_from(start).any(|h| free(self, h));
        let has_self = self.face_halfedges_from(start).any(|h| self.face(h.twin()) == small);
        let feasible = has_free || (has_self && diff % 2 == 0);
        if !feasible {
            return Err(MeshError::Precondition(format!(
                "{what}: face {} ({n} corners) cannot be subdivided to match face {} ({m} corners): its sides are shared with that face",
                small.0,
                large.0,
                n = n1.min(n2),
                m = n1.max(n2)
            )));
        }
        let length = |m: &Mesh, h: HalfedgeId| (m.position(m.head(h)) - m.position(m.vertex(h))).length_squared();
        let mut splits = 0;
        loop {
            let s = if first_small { *c1 } else { *c2 };
            let Corner::Halfedge(start) = s else { unreachable!() };
            let grown = self.face_degree(self.face(start));
            let target = n1.max(n2);
            if grown >= target {
                debug_assert_eq!(grown, target);
                break;
            }
            let pick = |want_free: bool| {
                self.face_halfedges_from(start)
                    .filter(|&h| if want_free { free(self, h) } else { self.face(h.twin()) == self.face(h) })
                    .max_by(|&x, &y| {
                        length(self, x).partial_cmp(&length(self, y)).unwrap_or(std::cmp::Ordering::Equal).then(y.0.cmp(&x.0))
                    })
            };
            let h = pick(true).or_else(|| pick(false)).expect("checked above");
            let e = h.edge();
            let split = self.subdivide_edge(e, 0.5)?;
            for c in [&mut *c1, &mut *c2] {
                if let Corner::Halfedge(h) = *c {
                    *c = Corner::Halfedge(split.remap(e, h));
                }
            }
            splits += 1;
        }
        Ok(splits)
    }

    /// **CreatePipe(c1, c2)** (ch. III.3): connects every pair of matching
    /// corners of the faces of `c1` and `c2` — corner i of the first (counted
    /// from `c1` along the face) with corner −i of the second (counted from
    /// `c2`), the pairing of two faces that look at each other — giving a
    /// pipe of N quads. If the faces differ in size, the smaller one's edges
    /// are first subdivided (longest first, at midpoints) until both have N
    /// corners; this also adds a corner to each neighbour across a split edge.
    ///
    /// Contract, with d splits (|N1 − N2| unless a side of the smaller face
    /// has it on both sides: such a split adds two corners) and
    /// N = max(N1, N2):
    /// V+d, E+d+N, F+N−2; one component: genus +1; two components:
    /// components −1 and the total genus unchanged. Precondition: two
    /// different faces, and a smaller face that can be grown to the larger's
    /// size without splitting sides they share. Existing half-edges keep their ids unless their edge
    /// was split (see [`crate::ops::EdgeSplit::remap`]); the two faces are
    /// replaced by the quads (face ids as InsertEdge leaves them).
    pub fn create_pipe(&mut self, c1: Corner, c2: Corner) -> Result<Pipe> {
        let (mut c1, mut c2) = (c1, c2);
        let subdivisions = self.equalize_faces(&mut c1, &mut c2, "create_pipe")?;
        let (a, b) = match (c1, c2) {
            (Corner::Halfedge(a), Corner::Halfedge(b)) => (a, b),
            _ => {
                // one corner each (point-spheres or one-gons): a single edge
                let e = self.insert_edge(c1, c2)?;
                return Ok(Pipe { subdivisions, edges: vec![e], sides: vec![] });
            }
        };
        let ca: Vec<HalfedgeId> = self.face_halfedges_from(a).collect();
        let cb: Vec<HalfedgeId> = self.face_halfedges_from(b).collect();
        let n = ca.len();
        debug_assert_eq!(n, cb.len());
        let mut edges = Vec::with_capacity(n);
        // the first edge merges the faces, each next one splits a quad off
        edges.push(self.insert_edge(Corner::Halfedge(ca[0]), Corner::Halfedge(cb[0]))?);
        for i in 1..n {
            edges.push(self.insert_edge(Corner::Halfedge(ca[i]), Corner::Halfedge(cb[n - i]))?);
        }
        Ok(Pipe { subdivisions, edges, sides: ca })
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use crate::mesh::{Corner, FaceId, Mesh};
    use crate::primitives;
    use glam::DVec3;

    fn corner(m: &Mesh, f: u32, i: usize) -> Corner {
        m.corner(FaceId(f), i).unwrap()
    }

    #[test]
    fn pipe_on_one_component_adds_a_handle() {
        let mut m = primitives::cube();
        let (v, e, f, c, g) = counts(&m);
        let p = m.create_pipe(corner(&m, 0, 0), corner(&m, 1, 0)).unwrap();
        assert_eq!(p.subdivisions, 0);
        assert_eq!(counts(&m), (v, e + 4, f + 2, c, g + 1));
        assert_eq!(m.face_size_histogram().get(&4), Some(&8));
        for &s in &p.sides {
            assert_eq!(m.face_degree(m.face(s)), 4);
        }
    }

    #[test]
    fn pipe_between_components_joins_them() {
        let mut m = primitives::cube();
        // a second component: a triangle sphere from CreateFaceManifold
        let fm = m.create_face_manifold(&[DVec3::new(0., 0., 5.), DVec3::new(1., 0., 5.), DVec3::new(0., 1., 5.)]).unwrap();
        let (v, e, f, c, g) = counts(&m);
        assert_eq!(c, 2);
        let p = m.create_pipe(corner(&m, 1, 0), fm.back_corner).unwrap();
        // the triangle's edges were split once: d = 1, N = 4
        assert_eq!(p.subdivisions, 1);
        assert_eq!(counts(&m), (v + 1, e + 1 + 4, f + 2, c - 1, g));
    }

    #[test]
    fn size_mismatch_subdivides_the_smaller_face() {
        // triangle (tetrahedron face) to a six-gon: three splits
        let mut m = primitives::cube();
        let fm = m.create_face_manifold(&(0..6).map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 6.0;
            DVec3::new(a.cos(), a.sin(), 4.0)
        }).collect::<Vec<_>>()).unwrap();
        let _ = fm;
        let tri = m.create_face_manifold(&[DVec3::new(0., 0., 8.), DVec3::new(1., 0., 8.), DVec3::new(0., 1., 8.)]).unwrap();
        let (v, e, f, c, g) = counts(&m);
        let p = m.create_pipe(tri.front_corner, fm.back_corner).unwrap();
        assert_eq!(p.subdivisions, 3);
        assert_eq!(counts(&m), (v + 3, e + 3 + 6, f + 4, c - 1, g));
    }

    #[test]
    fn degenerate_faces() {
        // one-gon to one-gon on two loop spheres: one edge, F−1
        let mut m = loop_sphere();
        let (v0, _) = m.create_vertex(DVec3::X).unwrap();
        m.insert_edge(Corner::Point(v0), Corner::Point(v0)).unwrap();
        let (v, e, f, c, g) = counts(&m);
        assert_eq!(c, 2);
        m.create_pipe(corner(&m, 0, 0), corner(&m, 2, 0)).unwrap();
        assert_eq!(counts(&m), (v, e + 1, f - 1, c - 1, g));
        // pipe between the two one-gons of one loop sphere: a handle
        let mut m = loop_sphere();
        m.create_pipe(corner(&m, 0, 0), corner(&m, 1, 0)).unwrap();
        assert_eq!(counts(&m), (1, 2, 1, 1, 1));
        // two-gons of one two-gon sphere: N = 2, genus +1
        let mut m = digon_sphere();
        m.create_pipe(corner(&m, 0, 0), corner(&m, 1, 0)).unwrap();
        assert_eq!(counts(&m), (2, 4, 2, 1, 1));
        // a one-gon against a quad: the loop is split three times
        let mut m = primitives::cube();
        let (p, _) = m.create_vertex(DVec3::Z * 4.).unwrap();
        m.insert_edge(Corner::Point(p), Corner::Point(p)).unwrap();
        let (v, e, f, c, g) = counts(&m);
        let pipe = m.create_pipe(corner(&m, 0, 0), corner(&m, 6, 0)).unwrap();
        assert_eq!(pipe.subdivisions, 3);
        assert_eq!(counts(&m), (v + 3, e + 3 + 4, f + 2, c - 1, g));
    }

    #[test]
    fn adjacent_faces_and_impossible_equalization() {
        // faces sharing an edge: a pipe is still a handle topologically
        let mut m = primitives::cube();
        let h = m.face_halfedge(FaceId(0)).unwrap();
        let (v, e, f, c, g) = counts(&m);
        m.create_pipe(Corner::Halfedge(h), Corner::Halfedge(h.twin())).unwrap();
        assert_eq!(counts(&m), (v, e + 4, f + 2, c, g + 1));
        // a one-gon whose only side it shares with the five-gon around it
        let mut m = primitives::cube();
        let c0 = corner(&m, 0, 0);
        let l = m.insert_edge(c0, c0).unwrap();
        let one_gon = m.face(l.halfedge());
        assert_eq!(m.face_degree(one_gon), 1);
        let before = m.clone();
        let err = m.create_pipe(Corner::Halfedge(l.halfedge()), Corner::Halfedge(l.halfedge().twin())).unwrap_err();
        assert!(err.to_string().contains("its sides are shared with that face"), "{err}");
        assert_eq!(m, before);
    }

    #[test]
    fn same_face_and_point_sphere_are_errors() {
        let mut m = primitives::cube();
        assert!(m.create_pipe(corner(&m, 0, 0), corner(&m, 0, 2)).is_err());
        let (p, _) = m.create_vertex(DVec3::Z * 4.).unwrap();
        let before = m.clone();
        assert!(m.create_pipe(corner(&m, 0, 0), Corner::Point(p)).is_err());
        assert_eq!(m, before);
    }
}

//! The high-level modeling operators of the high-genus dissertation
//! (Srinivasan, "Modeling High-Genus Surfaces"): the operators of ch. III,
//! multi-segment curved handles (ch. IV) and rind modeling (ch. V.3).
//!
//! Every operator here is a sequence of the four fundamental operators of
//! `crate::mesh` (CreateVertex, DeleteVertex, InsertEdge, DeleteEdge) in the
//! order the dissertation writes it, plus geometry; none touches the half-edge
//! columns directly, so each keeps the mesh a valid orientable 2-manifold at
//! every step. Each documents its contract: what it returns, how V, E, F,
//! components and genus change, and which ids survive.
//!
//! Id stability, inherited from the fundamental operators: InsertEdge and
//! CreateVertex only append, so half-edges (corners) and vertices keep their
//! ids; DeleteEdge / DeleteVertex swap-remove (the last element takes the
//! removed id). Operators that delete report what moved.

mod cleanup;
mod collapse;
mod connect;
mod face_manifold;
pub mod handle;
mod pipe;
pub mod rind;
mod subdivide;
pub mod tools;

pub use collapse::Collapse;
pub use face_manifold::FaceManifold;
pub use handle::{Handle, HandleShape};
pub use pipe::Pipe;
pub use rind::Rind;
pub use subdivide::EdgeSplit;

use crate::error::{MeshError, Result};
use crate::mesh::{EdgeId, HalfedgeId, Mesh, VertexId};

/// After DeleteEdge(`e`) with `last` the last edge before the call: half-edges
/// of `e` are gone (`None`), those of `last` now carry `e`'s ids.
pub(crate) fn remap_deleted_edge(e: EdgeId, last: EdgeId, tracked: &mut [Option<HalfedgeId>]) {
    for t in tracked.iter_mut() {
        if let Some(h) = *t {
            if h.edge() == e {
                *t = None;
            } else if h.edge() == last {
                *t = Some(HalfedgeId(2 * e.0 + (h.0 & 1)));
            }
        }
    }
}

/// The id a vertex has after DeleteVertex removed `removed` (in order), the
/// mesh having `n_before` vertices before the first removal; `None` if it was
/// itself removed.
pub(crate) fn follow_vertex(mut v: VertexId, n_before: usize, removed: &[VertexId]) -> Option<VertexId> {
    let mut last = n_before;
    for &r in removed {
        last -= 1;
        if v == r {
            return None;
        }
        if v.idx() == last {
            v = r;
        }
    }
    Some(v)
}

pub(crate) fn check_edge(m: &Mesh, e: EdgeId) -> Result<()> {
    if e.idx() >= m.n_edges() {
        return Err(MeshError::InvalidArgument(format!("edge {} out of range (mesh has {} edges)", e.0, m.n_edges())));
    }
    Ok(())
}

pub(crate) fn check_halfedge(m: &Mesh, h: HalfedgeId) -> Result<()> {
    if h.idx() >= m.n_halfedges() {
        return Err(MeshError::InvalidArgument(format!(
            "half-edge {} out of range (mesh has {})",
            h.0,
            m.n_halfedges()
        )));
    }
    Ok(())
}

#[cfg(test)]
pub(crate) mod testing {
    use crate::mesh::{BuildOptions, Mesh};
    use glam::DVec3;

    /// (V, E, F, components, genus)
    pub fn counts(m: &Mesh) -> (i64, i64, i64, i64, i64) {
        m.validate().expect("valid mesh");
        (m.n_vertices() as i64, m.n_edges() as i64, m.n_faces() as i64, m.n_components() as i64, m.genus())
    }

    /// A sphere of two one-gons: one vertex, one self-loop.
    pub fn loop_sphere() -> Mesh {
        let mut m = Mesh::new();
        let (v, _) = m.create_vertex(DVec3::ZERO).unwrap();
        m.insert_edge(crate::Corner::Point(v), crate::Corner::Point(v)).unwrap();
        m
    }

    /// A sphere of two two-gons (two vertices, a double edge), by CreateFaceManifold.
    pub fn digon_sphere() -> Mesh {
        let mut m = Mesh::new();
        m.create_face_manifold(&[DVec3::new(-1., 0., 0.), DVec3::new(1., 0., 0.)]).unwrap();
        m
    }

    /// The cube [-1, 1]³ with each face cut into an n × n grid of quads.
    pub fn grid_cube(n: usize) -> Mesh {
        let mut pos: Vec<DVec3> = Vec::new();
        let mut index = std::collections::HashMap::new();
        let mut id = |p: [i64; 3], pos: &mut Vec<DVec3>| -> i64 {
            *index.entry(p).or_insert_with(|| {
                pos.push(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) * (2.0 / n as f64) - DVec3::ONE);
                pos.len() as i64 - 1
            })
        };
        let n = n as i64;
        let mut sizes = Vec::new();
        let mut idx = Vec::new();
        for axis in 0..3 {
            for side in [0, n] {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                for i in 0..n {
                    for j in 0..n {
                        let mut quad = [[0i64; 3]; 4];
                        for (k, (di, dj)) in [(0, 0), (1, 0), (1, 1), (0, 1)].into_iter().enumerate() {
                            quad[k][axis] = side;
                            quad[k][u] = i + di;
                            quad[k][v] = j + dj;
                        }
                        let mut f: Vec<i64> = quad.iter().map(|&p| id(p, &mut pos)).collect();
                        if side == 0 {
                            f.reverse();
                        }
                        sizes.push(4);
                        idx.extend(f);
                    }
                }
            }
        }
        Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap()
    }
}

/// Random sequences of every operator from several start meshes (degenerate
/// ones included), checking `validate()` and each contract at every step.
#[cfg(test)]
mod random_sequences {
    use super::testing::*;
    use crate::mesh::{Corner, EdgeId, FaceId, HalfedgeId, Mesh};
    use crate::primitives;
    use glam::DVec3;

    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }
        fn below(&mut self, n: usize) -> usize {
            (self.next() % n as u64) as usize
        }
        fn unit(&mut self) -> f64 {
            (self.next() >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    fn random_corner(m: &Mesh, r: &mut Rng) -> Corner {
        let f = FaceId::new(r.below(m.n_faces()));
        let d = m.face_degree(f);
        m.corner(f, r.below(d)).unwrap()
    }

    fn same_component(m: &Mesh, a: Corner, b: Corner) -> bool {
        let (label, _) = m.vertex_components();
        label[m.corner_vertex(a).idx()] == label[m.corner_vertex(b).idx()]
    }

    fn run(start: Mesh, seed: u64, steps: usize) {
        let mut m = start;
        let mut r = Rng(seed);
        for _ in 0..steps {
            let before = m.clone();
            let (v, e, f, c, g) = counts(&m);
            let big = m.n_edges() > 400;
            match r.below(8) {
                0 if m.n_edges() > 0 => {
                    let ed = EdgeId::new(r.below(m.n_edges()));
                    m.subdivide_edge(ed, r.unit()).unwrap();
                    assert_eq!(counts(&m), (v + 1, e + 1, f, c, g));
                }
                1 if m.n_edges() > 0 => {
                    let ed = EdgeId::new(r.below(m.n_edges()));
                    let h = ed.halfedge();
                    let split = m.face(h) == m.face(h.twin());
                    let k = m.delete_edge_with_cleanup(ed).unwrap().len() as i64;
                    let (v2, e2, f2, c2, g2) = counts(&m);
                    assert_eq!((v2, e2), (v - k, e - 1));
                    if split {
                        assert_eq!(f2, f + 1 - k);
                        assert!((c2, g2) == (c + 1 - k, g) || (c2, g2) == (c - k, g - 1));
                    } else {
                        // a lone self-loop's vertex is left bare: cleaned up
                        assert_eq!((f2, c2, g2), (f - 1 - k, c - k, g));
                    }
                }
                2 if !big && m.n_faces() > 0 => {
                    let (a, b) = (random_corner(&m, &mut r), random_corner(&m, &mut r));
                    let one = same_component(&m, a, b);
                    let (n1, n2) = (m.face_degree(m.corner_face(a)), m.face_degree(m.corner_face(b)));
                    match m.create_pipe(a, b) {
                        Ok(p) => {
                            let (d, n) = (p.subdivisions as i64, n1.max(n2) as i64);
                            assert!(d <= n1.abs_diff(n2) as i64);
                            let (c2, g2) = if one { (c, g + 1) } else { (c - 1, g) };
                            assert_eq!(counts(&m), (v + d, e + d + n, f + n - 2, c2, g2));
                        }
                        Err(_) => assert_eq!(m, before),
                    }
                }
                3 if !big && m.n_halfedges() > 0 => {
                    let h1 = HalfedgeId::new(r.below(m.n_halfedges()));
                    let h2 = HalfedgeId::new(r.below(m.n_halfedges()));
                    let same = m.face(h1) == m.face(h2);
                    let one = same_component(&m, Corner::Halfedge(h1), Corner::Halfedge(h2));
                    match m.connect_edges(h1, h2) {
                        Ok(_) if same => assert_eq!(counts(&m), (v, e + 2, f + 2, c, g)),
                        Ok(_) if one => assert_eq!(counts(&m), (v, e + 2, f, c, g + 1)),
                        Ok(_) => assert_eq!(counts(&m), (v, e + 2, f, c - 1, g)),
                        Err(_) => assert_eq!((h1, &m), (h2, &before)),
                    }
                }
                4 if m.n_edges() > 0 => {
                    let ed = EdgeId::new(r.below(m.n_edges()));
                    match m.collapse_edge(ed) {
                        Ok(col) => {
                            let (v2, e2, _, _, _) = counts(&m);
                            assert_eq!(v2, v - 1);
                            assert_eq!(e2, e + col.inserted as i64 - col.deleted as i64);
                        }
                        Err(_) => assert_eq!(m, before),
                    }
                }
                5 if !big => {
                    let n = 1 + r.below(5);
                    let pts: Vec<DVec3> = (0..n).map(|i| DVec3::new(i as f64, r.unit(), 3.0)).collect();
                    m.create_face_manifold(&pts).unwrap();
                    let (de, df) = if n == 1 { (0, 1) } else { (n as i64, 2) };
                    assert_eq!(counts(&m), (v + n as i64, e + de, f + df, c + 1, g));
                }
                6 | 7 if !big && m.n_faces() > 0 => {
                    // fundamental InsertEdge: self-loops, multi-edges, two-gons
                    let (a, b) = (random_corner(&m, &mut r), random_corner(&m, &mut r));
                    m.insert_edge(a, b).unwrap();
                    m.validate().unwrap();
                }
                _ => {}
            }
        }
    }

    #[test]
    fn operators_keep_their_contracts() {
        let starts = [primitives::cube(), primitives::torus(4, 3, 1.0, 0.4).unwrap(), loop_sphere(), digon_sphere(), grid_cube(2)];
        for (i, s) in starts.into_iter().enumerate() {
            for seed in 1..6u64 {
                run(s.clone(), seed * 7919 + i as u64, 300);
            }
        }
    }
}

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

pub use collapse::Collapse;
pub use face_manifold::FaceManifold;
pub use handle::Handle;
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

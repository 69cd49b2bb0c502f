//! One generalized Menger iteration as a [`Level`]: the correspondence of
//! its output with the input, and the linear *attribute transfer* that
//! carries vertex data through it.
//!
//! The offset construction (dissertation ch. VII.3–VII.5, [`super::menger`])
//! places points by plane intersections and least squares, so positions are
//! not linear in the input's and there is no subdivision matrix. Data still
//! has a natural home in every output element:
//!
//! - **faces**: every remeshing quad (corner, edge, window) and pipe wall of
//!   input face `f` → `(FACE, f)`; every strip or miter quad of edge `e` →
//!   `(EDGE, e)`; the vertex face of `v` → `(VERTEX, v)`;
//! - **vertices**: input vertices → themselves; the two trisection points of
//!   edge `e` → `(EDGE, e)`; every inset, window and inner point (offset
//!   corners, miter vertices, cone apices) → the input vertex whose local
//!   rule placed it;
//! - **edges**: the origin its two faces share; between regions of
//!   different kinds the lower-dimensional one (a strip's side lies on its
//!   edge, a vertex face's side at its vertex); between the regions of two
//!   faces, the input edge they share.
//!
//! The transfer (returned as the level's `stencils`, which here are *not*
//! a position matrix) copies a vertex's value to everything its rule
//! placed, and interpolates a trisection point linearly along its edge by
//! where it lies (`a + t (b − a)`).

use super::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use super::menger::{checked_build, MengerOptions, MengerReport};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::Mesh;

/// One iteration with what `req` asks for (see the module docs) and what
/// its thickness reduction did ([`super::menger::menger_reported`]).
/// `req.stencils` asks for the attribute transfer.
pub fn menger_level(m: &Mesh, o: &MengerOptions, req: &Request) -> Result<(Level, MengerReport)> {
    let ((built, mesh), crossing) = checked_build(m, o)?;
    let (nv, ne) = (m.n_vertices(), m.n_edges());
    let t_end = nv + 2 * ne;
    let vertex_origin = |i: usize| -> (u8, u32) {
        if i < nv {
            (VERTEX, i as u32)
        } else if i < t_end {
            (EDGE, ((i - nv) / 2) as u32)
        } else {
            let v = built.owner[i];
            debug_assert!((v as usize) < nv, "output vertex {i} has no owner");
            (VERTEX, v.min(nv as u32 - 1))
        }
    };
    let stencils = if req.stencils {
        let (_, vert, _) = m.halfedge_columns();
        let (p, q) = (&m.pos, &mesh.pos);
        Some(Stencils::build(mesh.n_vertices(), nv, |i, row| match vertex_origin(i) {
            (EDGE, e) => {
                let (a, b) = (vert[2 * e as usize], vert[2 * e as usize + 1]);
                let d = p[b as usize] - p[a as usize];
                let t = ((q[i] - p[a as usize]).dot(d) / d.length_squared()).clamp(0.0, 1.0);
                row.add(a, 1.0 - t);
                row.add(b, t);
            }
            (_, v) => row.add(v, 1.0),
        })?)
    } else {
        None
    };
    let origins = if req.origins {
        let n = mesh.n_vertices();
        let mut o = Origins::with_capacity(n, mesh.n_edges(), mesh.n_faces());
        for i in 0..n {
            let (k, x) = vertex_origin(i);
            o.vertex_kind.push(k);
            o.vertex.push(x);
        }
        debug_assert_eq!(built.face_origin.len(), mesh.n_faces());
        (o.face_kind, o.face) = built.face_origin.iter().copied().unzip();
        let (_, overt, oface) = mesh.halfedge_columns();
        let (_, _, iface) = m.halfedge_columns();
        for e in 0..mesh.n_edges() {
            crate::cancel::poll(e)?;
            let a = built.face_origin[oface[2 * e] as usize];
            let b = built.face_origin[oface[2 * e + 1] as usize];
            let pick = if a == b {
                a
            } else if a.0 != b.0 {
                a.min(b) // the lower-dimensional region
            } else if a.0 == FACE {
                // two faces' regions meet along an edge they share
                let shared = m
                    .face_halfedges(crate::mesh::FaceId(a.1))
                    .find(|h| iface[(h.0 ^ 1) as usize] == b.1)
                    .map(|h| (EDGE, h.0 >> 1));
                shared.unwrap_or_else(|| vertex_origin(overt[2 * e] as usize))
            } else {
                // two edges' strips (or two vertex faces) touch at a vertex
                vertex_origin(overt[2 * e] as usize)
            };
            o.edge_kind.push(pick.0);
            o.edge.push(pick.1);
        }
        Some(o)
    } else {
        None
    };
    Ok((Level { mesh, stencils, origins, creases: None }, crossing))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn origins_and_transfer_on_platonic_and_torus() {
        use crate::schemes::menger::Offset;
        for (o, (name, m)) in [Offset::PerFace, Offset::Merged].into_iter().flat_map(|offset| {
            let o = MengerOptions { offset, ..Default::default() };
            [("cube", crate::primitives::cube()), ("tetrahedron", crate::primitives::tetrahedron()), ("dodecahedron", crate::primitives::dodecahedron()), ("torus", crate::primitives::torus(6, 4, 1.0, 0.4).unwrap())].map(|c| (o, c))
        }) {
            let name = format!("{name} {:?}", o.offset);
            let name = name.as_str();
            let (lv, _) = menger_level(&m, &o, &full_request()).unwrap();
            let plain = super::super::menger::menger(&m, &o).unwrap();
            assert_eq!(lv.mesh.to_polygons(), plain.to_polygons(), "{name}");
            let org = lv.origins.as_ref().unwrap();
            org.check(&m, &lv.mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
            // every input face owns its 3n remeshing and pipe quads (n corners), at least
            let fo = origin_counts(&org.face_kind, &org.face, FACE, m.n_faces());
            for f in 0..m.n_faces() {
                assert!(fo[f] >= 3 * m.face_degree(crate::mesh::FaceId(f as u32)), "{name} face {f}: {}", fo[f]);
            }
            // two trisection points per edge
            let ev = origin_counts(&org.vertex_kind, &org.vertex, EDGE, m.n_edges());
            assert!(ev.iter().all(|&c| c == 2), "{name}");
            // the transfer reproduces the input positions at the input vertices
            // and puts trisection points where they are
            let s = lv.stencils.as_ref().unwrap();
            let p = s.apply_points(m.positions()).unwrap();
            for i in 0..m.n_vertices() + 2 * m.n_edges() {
                assert!((p[i] - lv.mesh.pos[i]).length() < 1e-12, "{name} vertex {i}");
            }
            // rows sum to one (constants are carried exactly)
            let ones = s.apply(&vec![1.0; m.n_vertices()], 1).unwrap();
            assert!(ones.iter().all(|&x| (x - 1.0).abs() < 1e-12), "{name}");
        }
    }

    /// The per-face construction (`Offset::PerFace`, the default) on every
    /// mesh of the corpus the merged one accepts (it refuses the same ones): a valid
    /// manifold with the genus formula and positive volume, its origins
    /// consistent, and the mesh the plain call gives.
    #[test]
    fn per_face_on_the_corpus() {
        let pf = MengerOptions { offset: crate::schemes::menger::Offset::PerFace, ..Default::default() };
        let mut built = 0;
        for (name, m) in corpus() {
            let merged = super::super::menger::menger(&m, &MengerOptions { offset: crate::schemes::menger::Offset::Merged, ..Default::default() });
            let (lv, r) = match menger_level(&m, &pf, &full_request()) {
                Ok(x) => x,
                Err(e) => {
                    assert!(merged.is_err(), "{name}: per-face refused what merged accepts: {e}");
                    continue;
                }
            };
            assert!(merged.is_ok(), "{name}: per-face accepted what merged refuses");
            lv.mesh.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(lv.mesh.genus(), 2 * m.genus() + m.n_faces() as i64 - 1, "{name}");
            assert!(lv.mesh.signed_volume() > 0.0, "{name}");
            assert_eq!(r.crossing_pairs, Some(0), "{name}");
            lv.origins.as_ref().unwrap().check(&m, &lv.mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(lv.mesh.to_polygons(), super::super::menger::menger(&m, &pf).unwrap().to_polygons(), "{name}");
            built += 1;
        }
        assert!(built >= 7, "{built}");
    }

    #[test]
    fn plain_request_gives_only_the_mesh() {
        let (lv, _) = menger_level(&crate::primitives::cube(), &MengerOptions::default(), &Request::plain()).unwrap();
        assert!(lv.stencils.is_none() && lv.origins.is_none());
    }
}

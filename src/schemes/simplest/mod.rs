//! The simplest subdivision scheme (J. Peters & U. Reif, "The simplest
//! subdivision scheme for smoothing polyhedra", ACM TOG 16(4), 1997), one
//! level: mid-edge subdivision.
//!
//! What is implemented, exactly: every new vertex is the midpoint of an old
//! edge (a self-loop's midpoint is its vertex); every new vertex is joined to
//! the midpoints of the four edges that follow and precede its edge in the two
//! faces beside it. Each old n-gon becomes the n-gon of its edge midpoints
//! (F-face) and each old valence-k vertex the k-gon of the midpoints around
//! it (V-face), which cuts every vertex off at the edge midpoints ("connect
//! every edge midpoint to its four neighbouring edge midpoints", the paper's
//! abstract). On a regular quad mesh two steps are one binary refinement of
//! the four-direction (Zwart–Powell) box spline. The paper's improved weights for the
//! extraordinary (non-4-sided) faces are *not* applied: every new point is a
//! plain midpoint, so one step is exactly the rectification (medial
//! polyhedron) of the input.
//!
//! Counts (H = 2E): V' = E, E' = H = 2E, F' = F + V; every new vertex is
//! 4-valent. Output vertex e is the midpoint of edge e; faces are
//! `[F-faces | V-faces]`.
//!
//! Stencils and correspondence ([`simplest_level`]): the scheme is linear,
//! a row is `½ a + ½ b`. Origins: the midpoint of e → (EDGE, e); the F-face
//! of f → (FACE, f), the V-face of v → (VERTEX, v); every output edge lies
//! inside one input face (it cuts a corner of it) → (FACE, that face).
//! Open meshes: the paper has no boundary rule, and the plain mid-edge rule
//! at a boundary would replace the boundary polygon by its midpoint polygon
//! at every level (the hole keeps its n sides and shrinks towards a point).
//! topomesh keeps the boundary polyline instead, the convention of Blender's
//! *keep boundaries* it also uses for [`super::dual`] (the mid-edge step is a
//! rectification, dual-like): a boundary vertex stays, as a corner of its
//! V-face, and boundary edges are split at their midpoints. With E_b
//! boundary edges, V_b boundary vertices and h holes: V' = E + V_b,
//! E' = 2E + E_b, F' = F + V (the holes stay holes, each of n sides now
//! 2n). The boundary is interpolated as a polyline (a crease), the interior
//! is smoothed as on closed meshes.

use super::hosts::{refuse_holes, with_point_spheres, FaceLayout, VertexLayout, MIN_LEN};
use super::corner_origins::edge_origins_by_corner;
use super::level::{with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::Mesh;
use rayon::prelude::*;
use std::borrow::Cow;

mod closed;
mod open;
use closed::build;
use open::{open_build, open_level};

/// One level of mid-edge ("simplest") subdivision. See the module docs.
pub fn simplest(m: &Mesh) -> Result<Mesh> {
    refuse_holes("simplest", m)?;
    with_point_spheres("simplest", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    build(Cow::Borrowed(m))
}

/// [`step`] on a level's input that nobody else holds (the previous level
/// of a multi-level call, issue 19): each part of the input goes once the
/// output no longer needs it. The output is [`step`]'s, bit for bit.
fn step_owned(m: Mesh) -> Result<Mesh> {
    build(Cow::Owned(m))
}


/// [`simplest_level`] on an input the caller gives up (a previous level of
/// a multi-level call): a mesh without point-spheres, asked for no stencils
/// or origins, takes [`step_owned`] (closed) or [`open_build`] on the owned
/// input (open); anything else is [`simplest_level`]'s.
pub fn simplest_level_owned(m: Mesh, req: &Request) -> Result<Level> {
    crate::cancel::check()?;
    if req.stencils || req.origins || m.has_point_spheres() {
        return simplest_level(&m, req);
    }
    if m.n_holes() > 0 {
        return open_build(Cow::Owned(m), req);
    }
    Ok(Level { mesh: step_owned(m)?, stencils: None, origins: None, creases: None })
}

/// One level with what `req` asks for (see the module docs); without
/// requests it is [`simplest`]. Open meshes keep their boundary polyline
/// (module docs).
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn simplest_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, |m, req| {
        if m.n_holes() > 0 {
            return open_level(m, req);
        }
        let mesh = step(m)?;
        let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
        let (_, vert, face) = m.halfedge_columns();
        let stencils = if req.stencils {
            Some(Stencils::build(ne, nv, |e, row| {
                row.add(vert[2 * e], 0.5);
                row.add(vert[2 * e + 1], 0.5);
            })?)
        } else {
            None
        };
        let origins = if req.origins {
            let fl = FaceLayout::new(m)?;
            let vl = VertexLayout::new(m)?;
            let mut o = Origins::with_capacity(ne, mesh.n_edges(), nf + nv);
            o.vertex_kind = vec![EDGE; ne];
            o.vertex.extend(0..ne as u32);
            o.face_kind.extend(std::iter::repeat(FACE).take(nf).chain(std::iter::repeat(VERTEX).take(nv)));
            o.face.extend((0..nf as u32).chain(0..nv as u32));
            // F-face corner c is half-edge fh[c]; V-face slot s is the outgoing half-edge whose slot it is
            let nh = m.n_halfedges();
            let mut slot_he = vec![0u32; nh];
            for h in 0..nh {
                slot_he[vl.vidx[h] as usize] = h as u32;
            }
            edge_origins_by_corner(&mesh, &mut o, |c| {
                let f = if c < nh { face[fl.fh[c] as usize] } else { face[slot_he[c - nh] as usize] };
                (FACE, f)
            })?;
            Some(o)
        } else {
            None
        };
        Ok(Level { mesh, stencils, origins, creases: None })
    })
}

/// [`simplest_level`] that also interpolates vertex data (`(rows, k)`
/// row-major arrays): on a closed mesh without point-spheres each edge's
/// midpoint row (no stencils built), else through the stencils.
pub fn simplest_level_with(m: &Mesh, req: &Request, data: &[(Vec<f64>, usize)]) -> Result<(Level, Vec<Vec<f64>>)> {
    super::level::level_with_data(m, req, data, simplest_level, |a, k| {
        let vert = &m.he_vert;
        let mut out = vec![0.0; m.n_edges() * k];
        out.par_chunks_mut(k.max(1)).with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| {
            let (u, w) = (vert[2 * e] as usize, vert[2 * e + 1] as usize);
            for ((o, x), y) in o.iter_mut().zip(&a[u * k..(u + 1) * k]).zip(&a[w * k..(w + 1) * k]) {
                *o = (x + y) * 0.5;
            }
        });
        crate::cancel::check()?;
        Ok(out)
    })
}


#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn owned_level_equals_the_borrowed_one() {
        // closed inputs (consumed), open and point-sphere ones (the borrowed
        // path); positions compared bit for bit
        for (name, m) in owned_level_cases() {
            let req = Request::plain();
            let a = simplest_level(&m, &req).unwrap().mesh;
            let b = simplest_level_owned(m.clone(), &req).unwrap().mesh;
            assert_eq!((&a, position_bits(&a)), (&b, position_bits(&b)), "{name}");
            // and on the first level's output, the input a multi-level call gives up
            let c = simplest_level(&a, &req).unwrap().mesh;
            let d = simplest_level_owned(a, &req).unwrap().mesh;
            assert_eq!((&c, position_bits(&c)), (&d, position_bits(&d)), "{name} level 2");
        }
    }

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(simplest, |_, (v, e, f)| (e, 2 * e, f + v), |name, _, r| {
            assert!(r.vertices().filter(|&x| r.point_sphere_face(x).is_none()).all(|x| r.valence(x) == 4), "{name} 4-valent");
        });
    }

    #[test]
    fn level_equals_plain_on_corpus() {
        level_matches_plain_on_corpus(simplest, simplest_level, |name, m, lv| {
            let o = lv.origins.as_ref().unwrap();
            let fl = FaceLayout::new(m).unwrap();
            assert!(origin_counts(&o.vertex_kind, &o.vertex, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
            assert!(origin_counts(&o.face_kind, &o.face, VERTEX, m.n_vertices()).iter().enumerate().all(|(v, &c)| c == usize::from(m.v_out[v] & crate::mesh::POINT == 0)), "{name}");
            assert!(origin_counts(&o.face_kind, &o.face, FACE, m.n_faces()).iter().all(|&c| c == 1), "{name}");
            // each face is the origin of its n corner-cutting edges
            let fe = origin_counts(&o.edge_kind, &o.edge, FACE, m.n_faces());
            for f in 0..m.n_faces() {
                assert_eq!(fe[f], fl.degree(f), "{name} face {f}");
            }
        });
    }

    #[test]
    fn open_meshes_keep_their_boundary_polyline() {
        for (name, m) in open_meshes() {
            let (v, e, f) = counts(&m);
            let nb = (0..m.n_halfedges()).filter(|&h| m.f_hole[m.he_face[h] as usize]).count();
            let vb = (0..v).filter(|&x| crate::schemes::creases::ring(&m, m.v_out[x]).any(|h| m.f_hole[m.he_face[h as usize] as usize])).count();
            let lv = simplest_level(&m, &full_request()).unwrap();
            check_level(name, &m, &lv);
            let r = &lv.mesh;
            assert_eq!(counts(r), (e + vb, 2 * e + nb, f + v), "{name}");
            assert_eq!((open_euler(r), r.n_holes()), (open_euler(&m), m.n_holes()), "{name}");
            let rb = (0..r.n_halfedges()).filter(|&h| r.f_hole[r.he_face[h] as usize]).count();
            assert_eq!(rb, 2 * nb, "{name}: boundary edges split");
            // every boundary point of the output lies on the input's boundary polyline
            for h in 0..r.n_halfedges() {
                if r.f_hole[r.he_face[h] as usize] {
                    let p = r.pos[r.he_vert[h] as usize];
                    let on = (0..m.n_halfedges()).filter(|&k| m.f_hole[m.he_face[k] as usize]).any(|k| {
                        let (a, b) = (m.pos[m.he_vert[k] as usize], m.pos[m.he_vert[k ^ 1] as usize]);
                        (p - a).length() < 1e-12 || (p - b).length() < 1e-12 || (p - (a + b) * 0.5).length() < 1e-12
                    });
                    assert!(on, "{name}: boundary point {p} off the input boundary");
                }
            }
            // a second level works on the output (open input again)
            let two = simplest_level(r, &full_request()).unwrap();
            check_level(name, r, &two);
        }
    }

    #[test]
    fn cube_gives_cuboctahedron() {
        let r = simplest(&crate::primitives::cube()).unwrap();
        assert_eq!(r.face_size_histogram().get(&3), Some(&8));
        assert_eq!(r.face_size_histogram().get(&4), Some(&6));
    }
}

/// The builders the direct column fills replaced, kept as references.
#[cfg(test)]
mod reference;

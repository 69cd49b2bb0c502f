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
//! Open meshes are refused (no boundary rule yet: the plain mid-edge rule
//! at a boundary would average the boundary polygon into itself without
//! refining it).

use super::hosts::{check_output_size, refuse_holes, with_point_spheres, FaceLayout, VertexLayout, MIN_LEN};
use super::corner_origins::edge_origins_by_corner;
use super::level::{with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// One level of mid-edge ("simplest") subdivision. See the module docs.
pub fn simplest(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("simplest", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("simplest", 2 * m.n_halfedges(), m.n_edges())?;
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (next, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;
    let pos: Vec<_> = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        // cancelled: zeros, the check below reports it
        if crate::cancel::requested() {
            DVec3::ZERO
        } else {
            (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5
        }
    }).collect();
    crate::cancel::check()?;
    let hu = nh as u32;
    let mut cv = vec![0u32; 2 * nh];
    let mut tw = vec![0u32; 2 * nh];
    {
        let (cf, cvf) = cv.split_at_mut(nh);
        let (tf, tvf) = tw.split_at_mut(nh);
        cf.par_iter_mut().zip(tf.par_iter_mut()).with_min_len(MIN_LEN).enumerate().for_each(|(c, (v, t))| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let h = fl.fh[c];
            *v = h >> 1;
            *t = hu + vl.vidx[next[h as usize] as usize];
        });
        let (pc, pt) = (super::hosts::SyncPtr(cvf.as_mut_ptr()), super::hosts::SyncPtr(tvf.as_mut_ptr()));
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|x| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let slot = vl.vidx[x] as usize;
            // SAFETY: vidx is a permutation of 0..nh.
            unsafe {
                *pc.get().add(slot) = (x >> 1) as u32;
                *pt.get().add(slot) = fl.cidx[prev[x] as usize];
            }
        });
    }
    crate::cancel::check()?;
    let mut sizes = Vec::with_capacity(nf + nv);
    sizes.extend((0..nf).map(|f| fl.degree(f) as u32));
    sizes.extend((0..nv).map(|v| vl.valence(v)));
    Mesh::from_corner_twins(pos, &sizes, &cv, &tw)
}

/// One level with what `req` asks for (see the module docs); without
/// requests it is [`simplest`]. Refuses hole faces.
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn simplest_level(m: &Mesh, req: &Request) -> Result<Level> {
    refuse_holes("simplest", m)?;
    with_point_spheres_level(m, req, |m, req| {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

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
    fn level_refuses_holes() {
        match simplest_level(&cube_with_hole(), &Request { stencils: true, ..Default::default() }) {
            Err(crate::error::MeshError::Precondition(msg)) => assert!(msg.starts_with("simplest") && msg.contains("no boundary rules"), "{msg}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn cube_gives_cuboctahedron() {
        let r = simplest(&crate::primitives::cube()).unwrap();
        assert_eq!(r.face_size_histogram().get(&3), Some(&8));
        assert_eq!(r.face_size_histogram().get(&4), Some(&6));
    }
}

//! Dual Loop (TopMod's `subdivideDualLoop` in `DLFLSubdiv.h`: dual, Loop,
//! dual) without Loop's output mesh (issue 16: Loop's step and the last
//! dual were nearly all of the time, the dual only walking Loop's mesh).
//!
//! Loop fans the dual's non-triangles first; call the fanned dual T (all
//! triangles, V_T vertices, E_T edges, F_T faces, H_T = 3F_T corners).
//! Loop's step ([`super::super::primal_columns`], no face points) lays, per
//! face f of T and corner k (half-edge h = corner k from `f_start`), the
//! triangle 4f + k `[tail h, e(h), e(prev h)]` (corners a(h), slot 1, b(h))
//! and then the middle 4f + 3 `[e(h₀), e(h₁), e(h₂)]`; its vertices are
//! `[vertex points | edge points]`. The last dual turns every Loop vertex
//! into a face, walking its rotation from its first corner:
//!
//! * vertex point v: from a(g), g the outgoing half-edge of v first in face
//!   order, the triangles 4 face(h) + k(h) in T's rotation (h → twin prev h),
//!   crossing the child of edge(prev h) at v;
//! * edge point of e = {h, t}: the cycle slot1(h), b(next t), mid(t),
//!   slot1(t), b(next h), mid(h) (mid(x): the middle triangle of face(x)),
//!   from the lowest of Loop's candidate corners (slot 1 of a side at its
//!   corner 0 or 1, else b of the next corner), crossing the edges Loop's
//!   step lays there: the child of edge x at tail x (key x) and the inner
//!   edge of corner x (slot 1 of x, key H_T + x).
//!
//! So V' = 4F_T (every vertex 3-valent), E' = 2E_T + 3F_T, F' = V_T + E_T.
//! Positions are Loop's (the same masks, [`loop_subdivision`]) and the
//! centroids of its triangles summed from their first corner, as the dual
//! sums; edges are numbered by first crossing ([`DualWalk`]), so the output
//! is the composition's bit for bit (`keyed::hashes`). Holes, point-spheres
//! and traced builds (face parents) take the composition.
//!
//! [`loop_subdivision`]: crate::schemes::loop_subdivision

use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, POINT};
use crate::schemes::dual::dual;
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::face_parents::via_origins;
use crate::schemes::hosts::{check_output_size, fan_triangulate};
use crate::schemes::loop_subdivision as l;
use glam::DVec3;

/// The composition `dual(loop(dual(m)))`, as TopMod writes it.
pub(crate) fn composed(m: &Mesh) -> Result<Mesh> {
    let d = dual(m)?;
    dual(&via_origins(&d, |r| l::loop_level(&d, r), || l::loop_subdivision(&d))?)
}

/// [`composed`], the same output and errors, in one pass over the fanned
/// dual.
pub(crate) fn dual_loop(m: &Mesh) -> Result<Mesh> {
    if m.n_faces() == 0 || m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0) || crate::schemes::face_parents::recording() {
        return composed(m);
    }
    let d = dual(m)?;
    crate::cancel::check()?;
    let fan = fan_triangulate(&d)?;
    dual_of_loop(fan.as_ref().unwrap_or(&d))
}

/// `dual(loop_subdivision(t))` for a closed mesh `t` of triangles.
fn dual_of_loop(t: &Mesh) -> Result<Mesh> {
    let (nv, ne, nf, nh) = (t.n_vertices(), t.n_edges(), t.n_faces(), t.n_halfedges());
    check_output_size("loop", 4 * nh, nv + ne)?;
    check_output_size("dual", 4 * nh, 4 * nf)?;
    let (next, vert, face) = t.halfedge_columns();
    let prev = &t.he_prev;
    // corner index of every half-edge in its face (from f_start)
    let mut loc = vec![0u8; nh];
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let h0 = t.f_start[f];
        let h1 = next[h0 as usize];
        let h2 = next[h1 as usize];
        if h1 == h0 || h2 == h0 || next[h2 as usize] != h0 {
            return Err(MeshError::Invariant(format!("dual loop: face {f} of the fanned dual is not a triangle")));
        }
        loc[h1 as usize] = 1;
        loc[h2 as usize] = 2;
    }
    // Loop's edge points (its masks, `loop_subdivision`)
    let p = &t.pos;
    let mut ep = Vec::with_capacity(ne);
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let (a, b) = (2 * e, 2 * e + 1);
        let ab = p[vert[a] as usize] + p[vert[b] as usize];
        let cd = p[vert[prev[a] as usize] as usize] + p[vert[prev[b] as usize] as usize];
        ep.push(ab * 0.375 + cd * 0.125);
    }
    // the centroids of Loop's middle triangles; those of the corner
    // triangles are placed by the walk round their vertex point
    let mut pos = crate::mesh::zeroed_points(4 * nf);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let h0 = t.f_start[f] as usize;
        let h1 = next[h0] as usize;
        let h2 = next[h1] as usize;
        let mut s = DVec3::ZERO;
        s += ep[h0 >> 1];
        s += ep[h1 >> 1];
        s += ep[h2 >> 1];
        pos[4 * f + 3] = s / 3.0;
    }
    // Loop's triangle at corner h, and its middle triangle of face(h)
    let tri = |h: usize| 4 * face[h] + loc[h] as u32;
    let mid = |h: usize| 4 * face[h] + 3;
    let betas: Vec<f64> = (0..64).map(l::loop_beta).collect();
    let mut walk = DualWalk::new(pos, 4 * nh, nv + ne, 2 * nh);
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let s = t.v_out[v] as usize;
        // Loop's vertex point (its neighbours summed from v_out, as Loop
        // sums), and the outgoing half-edge first in face order
        let (mut h, mut g, mut best, mut sum, mut n) = (s, s, u32::MAX, DVec3::ZERO, 0usize);
        loop {
            sum += p[vert[h ^ 1] as usize];
            n += 1;
            let c = 3 * face[h] + loc[h] as u32;
            if c < best {
                (best, g) = (c, h);
            }
            h = (prev[h] ^ 1) as usize;
            if h == s {
                break;
            }
        }
        let beta = if n < betas.len() { betas[n] } else { l::loop_beta(n) };
        let vp = p[v] * (1.0 - n as f64 * beta) + sum * beta;
        let (mut h, mut last) = (g, crate::mesh::NONE);
        loop {
            let q = prev[h] as usize;
            let x = tri(h);
            let mut c = DVec3::ZERO;
            c += vp;
            c += ep[h >> 1];
            c += ep[q >> 1];
            walk.positions_mut()[x as usize] = c / 3.0;
            walk.put(v, x, q ^ 1, &mut last);
            h = q ^ 1;
            if h == g {
                break;
            }
        }
        walk.close(v, last);
    }
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let (h, tw) = (2 * e, 2 * e + 1);
        let (nh_, nt) = (next[h] as usize, next[tw] as usize);
        let ring = [(tri(h), h), (tri(nt), nh + nt), (mid(tw), nh + tw), (tri(tw), tw), (tri(nh_), nh + nh_), (mid(h), nh + h)];
        // Loop's first corner of the edge point: per side x, slot 1 of x
        // at corner 0 or 1, else b(next x); ring index and corner position
        let cand = |x: usize, at_slot1: usize, at_b: usize| {
            let k = loc[x] as u32;
            if k < 2 { (12 * face[x] + 3 * k + 1, at_slot1) } else { (12 * face[x] + 2, at_b) }
        };
        let (a, b) = (cand(h, 0, 4), cand(tw, 3, 1));
        let j0 = if a.0 < b.0 { a.1 } else { b.1 };
        let mut last = crate::mesh::NONE;
        for j in 0..6 {
            let (f, key) = ring[(j0 + j) % 6];
            walk.put(nv + e, f, key, &mut last);
        }
        walk.close(nv + e, last);
    }
    Mesh::from_columns(walk.finish()?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::{one_gon_two_gon_cube, open_meshes};

    /// Every column, positions bit for bit.
    fn same(a: &Mesh, b: &Mesh) -> bool {
        let bits = |m: &Mesh| m.pos.iter().flat_map(|p| p.to_array()).map(f64::to_bits).collect::<Vec<_>>();
        bits(a) == bits(b)
            && a.v_out == b.v_out
            && a.he_next == b.he_next
            && a.he_prev == b.he_prev
            && a.he_vert == b.he_vert
            && a.he_face == b.he_face
            && a.f_start == b.f_start
            && a.f_hole == b.f_hole
    }

    /// The one-pass build is the composition: the same columns and bits or
    /// the same error, on the corpus (non-convex faces, self-loops,
    /// two-gons, one-gons, genus 3, point-spheres, a Sierpinski output,
    /// valence-3 and other vertices), a Loop output (valence 6), a jittered
    /// torus and open meshes (which take the composition); traced builds
    /// too (they take the composition).
    #[test]
    fn dual_loop_is_its_composition() {
        use crate::schemes::face_parents::traced;
        let mut ms = super::super::tests::meshes();
        ms.push(("one_gon_two_gon", one_gon_two_gon_cube()));
        ms.push(("loop_cube", l::loop_subdivision(&crate::primitives::cube()).unwrap()));
        let mut jt = crate::primitives::torus(9, 7, 2.0, 0.7).unwrap();
        for (i, p) in jt.pos.iter_mut().enumerate() {
            *p += DVec3::new((i as f64 * 1.7).sin(), (i as f64 * 2.3).cos(), (i as f64 * 0.9).sin()) * 0.05;
        }
        ms.push(("jittered_torus", jt));
        ms.extend(open_meshes());
        let mut fused_runs = 0;
        for (name, m) in &ms {
            match (dual_loop(m), composed(m)) {
                (Ok(a), Ok(b)) => {
                    a.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
                    assert!(same(&a, &b), "{name}: the fused build differs from the composition");
                    fused_runs += (m.n_holes() == 0 && !m.v_out.iter().any(|&o| o & POINT != 0)) as usize;
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{name}"),
                (a, b) => panic!("{name}: fused {:?}, composition {:?}", a.err(), b.err()),
            }
            match (traced(m, || dual_loop(m)), traced(m, || composed(m))) {
                (Ok((a, pa)), Ok((b, pb))) => {
                    assert!(same(&a, &b), "{name}: traced, the builds differ");
                    assert_eq!(pa, pb, "{name}: face parents");
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{name}"),
                (a, b) => panic!("{name}: traced, fused {:?}, composition {:?}", a.err(), b.err()),
            }
        }
        assert!(fused_runs >= 12, "{fused_runs} meshes took the one pass");
    }

    /// The comparison sees a change: one Loop point moved by one ulp
    /// changes the output.
    #[test]
    fn the_comparison_sees_one_ulp() {
        let m = crate::primitives::cube();
        let a = dual_loop(&m).unwrap();
        let mut b = a.clone();
        b.pos[5].y = f64::from_bits(b.pos[5].y.to_bits() ^ 1);
        assert!(!same(&a, &b));
        let mut c = a.clone();
        c.he_next.swap(0, 2);
        assert!(!same(&a, &c));
    }
}

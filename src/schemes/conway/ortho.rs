//! Ortho, `join(ambo(m))` (Hart: `o = de = daa`), without ambo's mesh
//! (issue 16: ambo's 2E-edge mesh was built only to be read by the fused
//! join, [`super::dual_ambo`]).
//!
//! Ambo A of m ([`super::ambo`]): vertex e at the midpoint of edge e; face
//! f's face with, per corner h in face order, the corner at `mid(h)` whose
//! side is the corner edge `C(next h)`; vertex v's face with, per corner g
//! of v's rotation, the corner at `mid(g)` whose side is `C(g)` (`C(g)`
//! joins `mid(prev g)` and `mid(g)`). Every key is met first in the face
//! faces, so A's half-edge of the face corner at h is `2·cidx(h)`, of the
//! vertex corner at g `2·cidx(prev g) + 1`, A's edge j is `C(next fh[j])`,
//! its first side in face order is always the face corner, and A's
//! `v_out[e]` is the face corner of e's side met first. The rotation of A
//! round `mid(e)` from there is: face corner h0, vertex corner h0, face
//! corner `twin h0`, vertex corner `twin h0`. Join reads nothing else of A,
//! so it runs here on those formulas with the same arithmetic: the output
//! is the composition's bit for bit (`keyed::hashes`). Holes,
//! point-spheres and traced builds (face parents) take the composition.

use super::build::{reserve, reserve_from, In};
use super::dual_ambo::{first_side, join};
use crate::budget::Counts;
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::hosts::check_output_size;
use glam::DVec3;

/// `join(&ambo(m)?)` (ortho), the same output and errors.
pub(crate) fn ortho(m: &Mesh) -> Result<Mesh> {
    if m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0) || crate::schemes::face_parents::recording() {
        return join(&super::ambo(m)?);
    }
    crate::cancel::check()?;
    let c = In::new(m)?;
    let (nv, ne, nf, nh) = (c.nv, c.ne, c.nf, c.nh);
    let (next, prev, vert, face) = (c.next, c.prev, c.vert, c.face);
    let (fh, cidx) = (&c.fl.fh, &c.fl.cidx);
    // ambo's checks (`reserve`, then its builder's on 2H corners)
    reserve("ambo", m, ne, 2 * ne, nf + nv)?;
    check_output_size("ambo", 2 * nh, ne)?;
    // join's on ambo (`Counts::of` of A: a face of 3 corners per triangle
    // and per 3-valent vertex; C(g) is a self-loop when prev g and g share
    // their edge), then the dual's on ambo(A)'s counts
    let (nva, nea, nfa) = (ne, nh, nf + nv);
    let rotation = |v: usize| {
        let s = m.v_out[v];
        let mut g = Some(s);
        std::iter::from_fn(move || {
            let x = g?;
            let n = prev[x as usize] ^ 1;
            g = (n != s).then_some(n);
            Some(x)
        })
    };
    let f3 = (0..nf).filter(|&f| c.fl.degree(f) == 3).count() + (0..nv).filter(|&v| rotation(v).take(4).count() == 3).count();
    let loops = (0..nh).filter(|&g| prev[g] >> 1 == (g >> 1) as u32).count() as u64;
    let ca = Counts::closed(nva as u64, nea as u64, nfa as u64, f3 as u64, loops);
    reserve_from("ambo", &ca, nea, 2 * nea, nfa + nva)?;
    check_output_size("dual", 4 * nh, nfa + nva)?;
    // A's vertex e (`Ctx::mid`), and the midpoint of A's edge C(g), as
    // join sums A's positions (`dual_ambo::centroids`)
    let pos_in = &m.pos;
    let mid: Vec<DVec3> = (0..ne).map(|e| (pos_in[vert[2 * e] as usize] + pos_in[vert[2 * e + 1] as usize]) * 0.5).collect();
    let amid = |g: u32| (mid[(prev[g as usize] >> 1) as usize] + mid[(g >> 1) as usize]) * 0.5;
    // join's vertices: the centroids of ambo(A)'s faces: A's faces (face
    // faces, vertex faces), then A's vertices
    let mut pos = Vec::with_capacity(nfa + nva);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let hs = c.fl.corners(f);
        let mut s = DVec3::ZERO;
        for &h in hs {
            s += amid(next[h as usize]);
        }
        pos.push(s / hs.len() as f64);
    }
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let (mut s, mut k) = (DVec3::ZERO, 0usize);
        for g in rotation(v) {
            s += amid(g);
            k += 1;
        }
        pos.push(s / k as f64);
    }
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let h0 = first_side(&c, e);
        let t0 = h0 ^ 1;
        let mut s = DVec3::ZERO;
        s += amid(next[h0 as usize]);
        s += amid(h0);
        s += amid(next[t0 as usize]);
        s += amid(t0);
        pos.push(s / 4usize as f64);
    }
    // join's faces, one per A edge j (face corner h = fh[j] first, then
    // the vertex corner g = next h); keys: A's half-edges
    let nfa32 = nfa as u32;
    let mut walk = DualWalk::new(pos, 4 * nea, nea, 2 * nea);
    for (j, &h) in fh.iter().enumerate() {
        crate::cancel::poll(j)?;
        let g = next[h as usize];
        let mut last = NONE;
        walk.put(j, face[h as usize], 2 * j, &mut last);
        let r = prev[g as usize] ^ 1;
        walk.put(j, nfa32 + (h >> 1), 2 * cidx[prev[r as usize] as usize] as usize + 1, &mut last);
        walk.put(j, nf as u32 + vert[g as usize], 2 * j + 1, &mut last);
        walk.put(j, nfa32 + (g >> 1), 2 * cidx[g as usize] as usize, &mut last);
        walk.close(j, last);
    }
    Mesh::from_columns(walk.finish()?)
}

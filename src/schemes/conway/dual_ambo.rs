//! Join, `dual(ambo(m))` (Hart: `j = da`), without building ambo's output
//! (issue 16: join is the last two steps of ortho, `o = de = daa`, and the
//! first two of bevel, `b = ta = dkda`; ambo's 2E-edge mesh was built only
//! to be walked by the dual).
//!
//! Ambo ([`super::ambo`]) gives vertex e at the midpoint of edge e; the
//! face of every face f (corners h from `f_start`, corner at `mid(h)` on
//! key `next h`), then the face of every vertex v (its rotation g from
//! `v_out`, corner at `mid(g)` on key g). Every key is met first in the face
//! faces, so ambo's half-edge of the face corner at h is `2·cidx(h)` and
//! ambo's `v_out[e]` is the face corner of whichever side of e comes first
//! in face order. The dual's vertex i is the centroid of ambo's face i,
//! summed from that face's first corner; its face e goes round ambo's
//! vertex e from that corner h0:
//!
//! `face(h0)` crossing key h0, vertex face `tail(h0)` crossing key
//! `next(twin h0)`, `face(twin h0)` crossing key `twin h0`, vertex face
//! `tail(twin h0)` crossing key `next h0`.
//!
//! Edges are numbered by first crossing, as [`crate::schemes::dual`] does,
//! so the output is the composition's bit for bit (`keyed::hashes`).

use super::build::{reserve, In};
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual::dual;
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::face_parents::{self as fp, Step, VERT};
use crate::schemes::hosts::check_output_size;
use glam::DVec3;

/// `dual(&ambo(m)?)`, the same output, errors and face parents (with holes
/// or point-spheres it is that composition).
pub(crate) fn join(m: &Mesh) -> Result<Mesh> {
    if m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0) {
        return dual(&super::ambo(m)?);
    }
    crate::cancel::check()?;
    let c = In::new(m)?;
    let (nv, ne, nf, nh) = (c.nv, c.ne, c.nf, c.nh);
    // ambo's own checks, then the dual's on ambo's counts
    reserve("ambo", m, ne, 2 * ne, nf + nv)?;
    check_output_size("dual", 2 * nh, nf + nv)?;
    let (next, vert, face) = (c.next, c.vert, c.face);
    let pos = centroids(&c)?;
    // keys: ambo's edges, named by the input half-edge g of C(g)
    let mut walk = DualWalk::new(pos, 4 * ne, ne, nh);
    let nf32 = nf as u32;
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let h0 = first_side(&c, e);
        let t0 = h0 ^ 1;
        let mut last = NONE;
        walk.put(e, face[h0 as usize], h0 as usize, &mut last);
        walk.put(e, nf32 + vert[h0 as usize], next[t0 as usize] as usize, &mut last);
        walk.put(e, face[t0 as usize], t0 as usize, &mut last);
        walk.put(e, nf32 + vert[t0 as usize], next[h0 as usize] as usize, &mut last);
        walk.close(e, last);
    }
    let cols = walk.finish()?;
    if fp::recording() {
        // ambo then dual, composed: face e is born around ambo's vertex e,
        // whose origin is the face of e's first side; vertex f is face f's,
        // vertex nf + v is vertex v's
        let face = (0..ne).map(|e| c.face[2 * e]).collect();
        let vertex = (0..nf as u32).chain((0..nv as u32).map(|v| VERT | v)).collect();
        fp::record(Some(Step { in_v: nv, in_f: nf, face, vertex }));
    }
    Mesh::from_columns(cols)
}

/// The side of edge e met first in face order: ambo's `v_out` of its
/// midpoint is that side's face corner.
#[inline]
pub(super) fn first_side(c: &In<'_>, e: usize) -> u32 {
    let (a, b) = (2 * e as u32, 2 * e as u32 + 1);
    if c.fl.cidx[a as usize] < c.fl.cidx[b as usize] { a } else { b }
}

/// Join's vertices: the centroids of ambo's faces, the face faces then the
/// vertex faces, each summed from its first corner as the dual sums it.
pub(super) fn centroids(c: &In<'_>) -> Result<Vec<DVec3>> {
    let (m, next, prev, vert) = (c.m, c.next, c.prev, c.vert);
    let pos_in = &m.pos;
    // ambo's midpoint of the edge of h (`Ctx::mid`: the same bits)
    let mid = |h: u32| {
        let e = (h >> 1) as usize;
        (pos_in[vert[2 * e] as usize] + pos_in[vert[2 * e + 1] as usize]) * 0.5
    };
    // the mean of the midpoints round a cycle from `s` (a face by `next`,
    // a vertex's rotation by `twin ∘ prev`), summed in cycle order
    let ring_mean = |s: u32, step: &dyn Fn(u32) -> u32| {
        let (mut h, mut sum, mut k) = (s, DVec3::ZERO, 0usize);
        loop {
            sum += mid(h);
            k += 1;
            h = step(h);
            if h == s {
                break;
            }
        }
        sum / k as f64
    };
    let mut pos = Vec::with_capacity(c.nf + c.nv);
    for f in 0..c.nf {
        crate::cancel::poll(f)?;
        pos.push(ring_mean(m.f_start[f], &|h| next[h as usize]));
    }
    for v in 0..c.nv {
        crate::cancel::poll(v)?;
        pos.push(ring_mean(m.v_out[v], &|g| prev[g as usize] ^ 1));
    }
    Ok(pos)
}

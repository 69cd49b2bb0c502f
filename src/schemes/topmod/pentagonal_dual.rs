//! `dual(pentagon_preserving(x))` (dual pentagon preserving after its first
//! dual) without building pentagon preserving's output (issue 16: that
//! build was about half of the composition's time, only for the dual to
//! walk it). On faces of 3 or more corners, pentagon preserving (see
//! `pentagonal`) lays per face f the inner face I(f), then per corner h
//! (layout index g) the pentagon P(h) = [m(h), head h, m(next h),
//! i(next h), i(h)] (ids `f + off[f]`, `f + 1 + g`), with midpoints m(e) at
//! V + e and inner points i(h) at V + E + g. The dual's vertex of each face
//! is its centroid (summed from its first corner, as the dual sums); its
//! face w goes round vertex w from w's first corner in face order, crossing
//! the side that enters each corner (keys as pentagon preserving's: edge
//! half h, inner side H + h, spoke 2H + h):
//!
//! * old v: P(twin x) → P(twin rot x) for the x leaving v, crossing x;
//! * m(e), h a side of e: P(h) (1st corner) → P(prev h) (3rd) → P(twin h)
//!   → P(prev twin h), crossing 2H + h, h, 2H + twin h, twin h;
//! * i(h): I(f) → P(prev h) (4th) → P(h) (5th), crossing H + prev h,
//!   2H + h, H + h.
//!
//! Edges are numbered by first crossing, as [`crate::schemes::dual`] does,
//! so the output is the composition's bit for bit (`keyed::hashes`). Inputs
//! with one-gons or two-gons (laid differently) take the composition.

use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual_walk::{corner_mean, DualWalk};
use crate::schemes::dual::dual;
use crate::schemes::face_parents::{self as fp, Step, VERT};
use crate::schemes::hosts::check_output_size;
use crate::schemes::keyed::In;
use glam::DVec3;

/// `dual(&pentagon_preserving(x, scale)?)`, the same output.
pub(crate) fn dual_of_pentagon_preserving(x: &Mesh, scale: f64) -> Result<Mesh> {
    let composed = || dual(&super::pentagonal::pentagon_preserving(x, scale)?);
    if !(scale.is_finite() && (0.0..=1.0).contains(&scale)) || x.n_holes() > 0 || x.v_out.iter().any(|&o| o & POINT != 0) {
        return composed();
    }
    let i = In::new(x)?;
    let (nv, ne, nf, nh) = (i.nv, i.ne, i.nf, i.nh);
    if (0..nf).any(|f| i.fl.degree(f) < 3) {
        return composed();
    }
    let (next, prev, vert, face) = (i.next, i.prev, i.vert, i.face);
    let (fh, off, cidx) = (&i.fl.fh, &i.fl.off, &i.fl.cidx);
    let n_pf = nf + nh;
    check_output_size("pentagon_preserving", 6 * nh, nv + ne + nh)?;
    check_output_size("dual", 6 * nh, n_pf)?;
    let (pp, inner) = super::pentagonal::preserving_positions(&i, scale);
    crate::cancel::check()?;
    let mid = |h: usize| pp[nv + (h >> 1)];
    let ip = |h: usize| pp[inner[h] as usize];
    // the dual's vertices: centroids of I(f), P(h), in face order
    let mut pos = Vec::with_capacity(n_pf);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let hs = i.fl.corners(f);
        pos.push(corner_mean(hs, ip));
        for &h in hs {
            let (h, nx) = (h as usize, next[h as usize] as usize);
            let mut s = DVec3::ZERO;
            s += mid(h);
            s += pp[vert[h ^ 1] as usize];
            s += mid(nx);
            s += ip(nx);
            s += ip(h);
            pos.push(s / 5.0);
        }
    }
    drop((pp, inner));
    let n_out_he = 6 * nh;
    let n_pv = nv + ne + nh;
    let mut walk = DualWalk::new(pos, n_out_he, n_pv, 3 * nh);
    // the corner of the dual's face w at the centroid of face `pf`,
    // crossing key `key`
    let mut put = |w: usize, pf: u32, key: usize, last: &mut u32| walk.put(w, pf, key, last);
    let p_id = |h: usize| (face[h] as usize + 1 + cidx[h] as usize) as u32;
    // old vertices: v is P(y)'s 2nd corner for each y entering v, from the
    // lowest layout index
    let mut first = vec![NONE; nv];
    for &y in fh {
        let v = vert[y as usize ^ 1] as usize;
        if first[v] == NONE {
            first[v] = y ^ 1;
        }
    }
    let mut lasts = vec![NONE; n_pv];
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let s = first[v] as usize;
        let (mut x, mut last) = (s, NONE);
        loop {
            put(v, p_id(x ^ 1), x, &mut last);
            x = prev[x] as usize ^ 1;
            if x == s {
                break;
            }
        }
        lasts[v] = last;
    }
    let (n1, n2) = (nh, 2 * nh);
    let mut mid_src = Vec::with_capacity(if fp::recording() { ne } else { 0 });
    for e in 0..ne {
        crate::cancel::poll(e)?;
        let (h, t) = (2 * e, 2 * e + 1);
        let (ph, pt) = (prev[h] as usize, prev[t] as usize);
        // (face, corner position, crossing key, source half-edge)
        let ring: [(u32, u32, usize, usize); 4] = [(p_id(h), 0, n2 + h, h), (p_id(ph), 2, h, ph), (p_id(t), 0, n2 + t, t), (p_id(pt), 2, t, pt)];
        let k0 = (0..4).min_by_key(|&k| (ring[k].0, ring[k].1)).unwrap_or(0);
        if fp::recording() {
            mid_src.push(face[ring[k0].3]);
        }
        let mut last = NONE;
        for k in 0..4 {
            let (pf, _, key, _) = ring[(k0 + k) % 4];
            put(nv + e, pf, key, &mut last);
        }
        lasts[nv + e] = last;
    }
    for (g, &h) in fh.iter().enumerate() {
        crate::cancel::poll(g)?;
        let (h, w) = (h as usize, nv + ne + g);
        let f = face[h] as usize;
        let p = prev[h] as usize;
        let mut last = NONE;
        put(w, (f + off[f] as usize) as u32, n1 + p, &mut last);
        put(w, p_id(p), n2 + h, &mut last);
        put(w, p_id(h), n1 + h, &mut last);
        lasts[w] = last;
    }
    drop(put);
    let cols = walk.finish_at(&lasts)?;
    if fp::recording() {
        // pentagon preserving then dual, composed: each face from its
        // vertex's source (old v; a midpoint's first face's; h's face), each
        // centroid from its face's input face
        let fc = (0..nv as u32).map(|v| VERT | v).chain(mid_src).chain(fh.iter().map(|&h| face[h as usize])).collect();
        let mut vertex = Vec::with_capacity(n_pf);
        for f in 0..nf {
            vertex.extend(std::iter::repeat(f as u32).take(1 + i.fl.degree(f)));
        }
        fp::record(Some(Step { in_v: nv, in_f: nf, face: fc, vertex }));
    }
    Mesh::from_columns(cols)
}

//! `dual(dual_12_6_4(x))` (TopMod's 12.6.4 after its first dual) without
//! building dual 12.6.4's output (issue 16: that build was about half of
//! 12.6.4's time, only for the dual to walk it). Dual 12.6.4 (see its
//! module) lays the face F(f) of every face, then the quad E(e) of every
//! edge, then the face V(v) of every vertex (ids f, F + e, F + E + v), with
//! the points 2h, 2h + 1 of half-edge h; every point is 3-valent. The
//! dual's vertex of each face is its centroid (summed from its first
//! corner, as the dual sums); its face w goes round point w from its corner
//! in F(face h), which comes first, crossing the side that enters each
//! corner (keys as dual 12.6.4's: side h, corner cut H + h, quad side
//! 2H + h):
//!
//! * point 2h: F(face h), V(tail h), E(edge h), crossing H + h, 2H + h, h;
//! * point 2h + 1: F(face h), E(edge h), V(head h), crossing h,
//!   2H + twin h, H + next h.
//!
//! Edges are numbered by first crossing, as [`crate::schemes::dual`] does,
//! so the output is the composition's bit for bit (`keyed::hashes`).

use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::dual::dual;
use crate::schemes::face_parents::{self as fp, Step, VERT};
use crate::schemes::hosts::check_output_size;
use crate::schemes::keyed::In;
use glam::DVec3;

/// `dual(&dual_12_6_4(x, scale)?)`, the same output.
pub(crate) fn dual_of_dual_12_6_4(x: &Mesh, scale: f64) -> Result<Mesh> {
    if !(scale.is_finite() && scale > 0.0 && scale <= 1.0) || x.n_holes() > 0 || x.v_out.iter().any(|&o| o & POINT != 0) {
        return dual(&super::twelve_six_four::dual_12_6_4(x, scale)?);
    }
    let i = In::new(x)?;
    let (nv, ne, nf, nh) = (i.nv, i.ne, i.nf, i.nh);
    let (next, prev, face) = (i.next, i.prev, i.face);
    let n_tf = nf + ne + nv;
    check_output_size("dual_12_6_4", 6 * nh, 2 * nh)?;
    check_output_size("dual", 6 * nh, n_tf)?;
    let tp = super::twelve_six_four::positions(&i, scale);
    crate::cancel::check()?;
    // the dual's vertices: centroids of F(f), E(e), V(v)
    let mut pos = Vec::with_capacity(n_tf);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let hs = i.fl.corners(f);
        let mut s = DVec3::ZERO;
        for &h in hs {
            s += tp[2 * h as usize];
            s += tp[2 * h as usize + 1];
        }
        pos.push(s / (2 * hs.len()) as f64);
    }
    for e in 0..ne {
        let (h, t) = (2 * e, 2 * e + 1);
        let mut s = DVec3::ZERO;
        s += tp[2 * h + 1];
        s += tp[2 * h];
        s += tp[2 * t + 1];
        s += tp[2 * t];
        pos.push(s / 4.0);
    }
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let k0 = x.v_out[v] as usize;
        let (mut k, mut s, mut n) = (k0, DVec3::ZERO, 0usize);
        loop {
            let p = prev[k] as usize;
            s += tp[2 * k];
            s += tp[2 * p + 1];
            n += 2;
            k = p ^ 1;
            if k == k0 {
                break;
            }
        }
        pos.push(s / n as f64);
    }
    drop(tp);
    let n_out_he = 6 * nh;
    let mut walk = DualWalk::new(pos, n_out_he, 2 * nh, 3 * nh);
    // the corner of the dual's face w at the centroid of face `tf`,
    // crossing key `key`
    let mut put = |w: usize, tf: usize, key: usize, last: &mut u32| walk.put(w, tf as u32, key, last);
    let (e_id, v_id) = (|h: usize| nf + (h >> 1), |v: u32| nf + ne + v as usize);
    let mut lasts = vec![NONE; 2 * nh];
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let f = face[h] as usize;
        let mut last = NONE;
        put(2 * h, f, nh + h, &mut last);
        put(2 * h, v_id(i.vert[h]), 2 * nh + h, &mut last);
        put(2 * h, e_id(h), h, &mut last);
        lasts[2 * h] = last;
        let mut last = NONE;
        put(2 * h + 1, f, h, &mut last);
        put(2 * h + 1, e_id(h), 2 * nh + (h ^ 1), &mut last);
        put(2 * h + 1, v_id(i.vert[h ^ 1]), nh + next[h] as usize, &mut last);
        lasts[2 * h + 1] = last;
    }
    drop(put);
    let cols = walk.finish_at(&lasts)?;
    if fp::recording() {
        // dual 12.6.4 then dual, composed: face 2h, 2h + 1 (around h's
        // points) from h's face; the centroids of F(f), E(e), V(v) from f,
        // e's first side's face and v
        let fc = face.iter().flat_map(|&f| [f, f]).collect();
        let vertex = (0..nf as u32).chain((0..ne).map(|e| face[2 * e])).chain((0..nv as u32).map(|v| VERT | v)).collect();
        fp::record(Some(Step { in_v: nv, in_f: nf, face: fc, vertex }));
    }
    Mesh::from_columns(cols)
}

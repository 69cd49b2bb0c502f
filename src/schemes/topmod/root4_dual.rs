//! `dual(root4(x))` (dual hexagon preserving after its first dual) without
//! building root-4's output (issue 16: that build was about half of the
//! composition's time, only for the dual to walk it). Root-4 (see
//! `loop_style`) lays the inner face I(f) of every face, then the hexagon
//! H(e) of every edge (ids f, F + e), with the inner point i(h) of every
//! corner. The dual's vertex of each face is its centroid (summed from its
//! first corner, as the dual sums); its face w goes round root-4's vertex w
//! from w's first corner in face order, crossing the side that enters each
//! corner (keys as root-4's: inner side h, spoke H + h):
//!
//! * old v: H(edge y) → H(edge rot y) for the half-edges y leaving v,
//!   crossing H + y, from the first corner in the hexagons' order;
//! * i(h): I(face h), H(edge prev h), H(edge h), crossing prev h, H + h, h.
//!
//! Edges are numbered by first crossing, as [`crate::schemes::dual`] does,
//! so the output is the composition's bit for bit (`keyed::hashes`).

use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual_walk::{corner_mean, DualWalk};
use crate::schemes::dual::dual;
use crate::schemes::face_parents::{self as fp, Step, VERT};
use crate::schemes::hosts::check_output_size;
use crate::schemes::keyed::In;
use glam::DVec3;

/// `dual(&root4(x, weight, twist)?)`, the same output.
pub(crate) fn dual_of_root4(x: &Mesh, weight: f64, twist: f64) -> Result<Mesh> {
    let unit = |t: f64| t.is_finite() && (0.0..=1.0).contains(&t);
    if !(unit(weight) && unit(twist)) || x.n_holes() > 0 || x.v_out.iter().any(|&o| o & POINT != 0) {
        return dual(&super::loop_style::root4(x, weight, twist)?);
    }
    let i = In::new(x)?;
    let (nv, ne, nf, nh) = (i.nv, i.ne, i.nf, i.nh);
    let (next, prev, vert, face) = (i.next, i.prev, i.vert, i.face);
    let n_rf = nf + ne;
    check_output_size("root4", 4 * nh, nv + nh)?;
    check_output_size("dual", 4 * nh, n_rf)?;
    let rp = super::loop_style::root4_positions(&i, weight, twist);
    crate::cancel::check()?;
    let inner = |h: usize| rp[nv + h];
    // the dual's vertices: centroids of I(f), then H(e)
    let mut pos = Vec::with_capacity(n_rf);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let hs = i.fl.corners(f);
        pos.push(corner_mean(hs, inner));
    }
    for e in 0..ne {
        let (h, t) = (2 * e, 2 * e + 1);
        let (nx, nt) = (next[h] as usize, next[t] as usize);
        let mut s = DVec3::ZERO;
        s += rp[vert[t] as usize];
        s += inner(nx);
        s += inner(h);
        s += rp[vert[h] as usize];
        s += inner(nt);
        s += inner(t);
        pos.push(s / 6.0);
    }
    drop(rp);
    let n_out_he = 4 * nh;
    let mut walk = DualWalk::new(pos, n_out_he, nv + nh, 2 * nh);
    // the corner of the dual's face w at the centroid of root-4's face
    // `rf`, crossing key `key`
    let mut put = |w: usize, rf: usize, key: usize, last: &mut u32| walk.put(w, rf as u32, key, last);
    let h_id = |y: usize| nf + (y >> 1);
    // each old vertex's first corner: hexagon e lists tail(2e + 1) before
    // tail(2e)
    let mut first = vec![NONE; nv];
    for e in 0..ne {
        for y in [2 * e + 1, 2 * e] {
            let v = vert[y] as usize;
            if first[v] == NONE {
                first[v] = y as u32;
            }
        }
    }
    let mut lasts = vec![NONE; nv + nh];
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let s = first[v] as usize;
        let (mut y, mut last) = (s, NONE);
        loop {
            put(v, h_id(y), nh + y, &mut last);
            y = prev[y] as usize ^ 1;
            if y == s {
                break;
            }
        }
        lasts[v] = last;
    }
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let p = prev[h] as usize;
        let mut last = NONE;
        put(nv + h, face[h] as usize, p, &mut last);
        put(nv + h, h_id(p), nh + h, &mut last);
        put(nv + h, h_id(h), h, &mut last);
        lasts[nv + h] = last;
    }
    drop(put);
    let cols = walk.finish_at(&lasts)?;
    if fp::recording() {
        // root-4 then dual, composed: the face of old v from v, that of
        // i(h) from h's face; the centroids of I(f), H(e) from f and e's
        // first side's face
        let fc = (0..nv as u32).map(|v| VERT | v).chain(face.iter().copied()).collect();
        let vertex = (0..nf as u32).chain((0..ne).map(|e| face[2 * e])).collect();
        fp::record(Some(Step { in_v: nv, in_f: nf, face: fc, vertex }));
    }
    Mesh::from_columns(cols)
}

//! `dual(checkerboard(x))` without building checkerboard's output (issue
//! 16: dual checkerboard spent half its time building 9E edges only for
//! the dual to walk them). Checkerboard (see its module) lays, per face f,
//! the inset face I(f), then per corner h (layout index g) the corner quad
//! Q(h) and the side quad S(h): face ids `f + 2 off[f]`, `f + 1 + 2g`,
//! `f + 2 + 2g`. The dual's vertex of each is its centroid (summed from
//! its first corner, as the dual sums); the dual's face w goes round
//! checkerboard's vertex w (old vertices, trisection points tp(h), inset
//! points ip(h)) from its first corner in face order, crossing at each
//! corner the side that enters it:
//!
//! * old v: Q(h) → Q(twin prev h), crossing the segment `twin prev h`;
//! * tp(h): Q(h) → Q(next twin h) (4th corner) → S(twin h) (2nd) → S(h)
//!   (1st) → Q(h), crossing the segment h, `kb + next twin h`, the middle
//!   segment of h's edge, `ka + h`;
//! * ip(h): I(f) → S(prev h) (3rd) → Q(h) (3rd) → S(h) (4th) → I(f),
//!   crossing `ki + prev h`, `kb + h`, `ka + h`, `ki + h`; I(f) comes first.
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

/// `dual(&checkerboard(x, thickness)?)`, the same output.
pub(crate) fn dual_of_checkerboard(x: &Mesh, thickness: f64) -> Result<Mesh> {
    if !(thickness.is_finite() && thickness > 0.0 && thickness <= 0.5) || x.n_holes() > 0 || x.v_out.iter().any(|&o| o & POINT != 0) {
        return dual(&super::checkerboard::checkerboard(x, thickness)?);
    }
    let i = In::new(x)?;
    let (nv, ne, nf, nh) = (i.nv, i.ne, i.nf, i.nh);
    let (next, prev, vert) = (i.next, i.prev, i.vert);
    let (fh, off, cidx) = (&i.fl.fh, &i.fl.off, &i.fl.cidx);
    let (n_cv, n_cf, n_keys) = (nv + 2 * nh, nf + 2 * nh, 4 * nh + ne);
    check_output_size("checkerboard", 9 * nh, n_cv)?;
    check_output_size("dual", 2 * n_keys, n_cf)?;
    let cp = super::checkerboard::positions(&i, thickness);
    crate::cancel::check()?;
    let (tp, ip) = (|h: usize| cp[nv + h], |h: usize| cp[nv + nh + h]);
    // the dual's vertices: centroids of checkerboard's faces, in face order
    let mut pos = Vec::with_capacity(n_cf);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let hs = i.fl.corners(f);
        pos.push(corner_mean(hs, ip));
        for &h in hs {
            let h = h as usize;
            let (p, nx) = (prev[h] as usize, next[h] as usize);
            let mut q = DVec3::ZERO;
            q += cp[vert[h] as usize];
            q += tp(h);
            q += ip(h);
            q += tp(p ^ 1);
            pos.push(q / 4.0);
            let mut s = DVec3::ZERO;
            s += tp(h);
            s += tp(h ^ 1);
            s += ip(nx);
            s += ip(h);
            pos.push(s / 4.0);
        }
    }
    drop(cp);
    let face_of = |h: usize| i.face[h] as usize;
    let q_id = |h: usize| (face_of(h) + 1 + 2 * cidx[h] as usize) as u32;
    let s_id = |h: usize| (face_of(h) + 2 + 2 * cidx[h] as usize) as u32;
    let (km, ki, ka, kb) = (nh, nh + ne, 2 * nh + ne, 3 * nh + ne);
    let n_out_he = 2 * n_keys;
    let mut walk = DualWalk::new(pos, n_out_he, n_cv, n_keys);
    let mut lasts = vec![NONE; n_cv];
    // one corner of the dual's face w: the centroid of checkerboard face
    // `cf`, the side crossing key `key`
    let mut put = |w: usize, cf: u32, key: usize, last: &mut u32| walk.put(w, cf, key, last);
    // old vertices: from the corner of lowest layout index
    let mut first = vec![NONE; nv];
    for &h in fh {
        let v = vert[h as usize] as usize;
        if first[v] == NONE {
            first[v] = h;
        }
    }
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let s = first[v] as usize;
        let (mut h, mut last) = (s, NONE);
        loop {
            let t = prev[h] as usize ^ 1;
            put(v, q_id(h), t, &mut last);
            h = t;
            if h == s {
                break;
            }
        }
        lasts[v] = last;
    }
    // trisection points: four corners, from the first in face order
    // (face id, then position in the face)
    let mut tp_src = Vec::with_capacity(if fp::recording() { nh } else { 0 });
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let x = next[h ^ 1] as usize;
        let ring: [(u32, usize, u32); 4] = [(q_id(h), h, 1), (q_id(x), kb + x, 3), (s_id(h ^ 1), km + (h >> 1), 1), (s_id(h), ka + h, 0)];
        let k0 = (0..4).min_by_key(|&k| (ring[k].0, ring[k].2)).unwrap_or(0);
        if fp::recording() {
            tp_src.push(i.face[[h, x, h ^ 1, h][k0]]);
        }
        let mut last = NONE;
        for k in 0..4 {
            let (cf, key, _) = ring[(k0 + k) % 4];
            put(nv + h, cf, key, &mut last);
        }
        lasts[nv + h] = last;
    }
    // inset points: the inset face first
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let f = face_of(h);
        let p = prev[h] as usize;
        let mut last = NONE;
        put(nv + nh + h, (f + 2 * off[f] as usize) as u32, ki + p, &mut last);
        put(nv + nh + h, s_id(p), kb + h, &mut last);
        put(nv + nh + h, q_id(h), ka + h, &mut last);
        put(nv + nh + h, s_id(h), ki + h, &mut last);
        lasts[nv + nh + h] = last;
    }
    drop(put);
    let cols = walk.finish_at(&lasts)?;
    if fp::recording() {
        // checkerboard then dual, composed: face w is born around
        // checkerboard's vertex w (whose source is the face of its first
        // corner), vertex c inside the input face of checkerboard's face c
        let face = (0..nv as u32).map(|v| VERT | v).chain(tp_src).chain(i.face.iter().copied()).collect();
        let mut vertex = Vec::with_capacity(n_cf);
        for f in 0..nf {
            vertex.extend(std::iter::repeat(f as u32).take(1 + 2 * i.fl.degree(f)));
        }
        fp::record(Some(Step { in_v: nv, in_f: nf, face, vertex }));
    }
    Mesh::from_columns(cols)
}

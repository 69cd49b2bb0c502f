//! Bevel, `dual(kis(join(m)))` (Hart: `b = ta = dkda`), without building
//! join's mesh (issue 16: join's E quads were built only to be read by the
//! fused `dual(kis(·))`, and the two builds were most of bevel's time).
//!
//! [`super::dual_ambo::join`] lays join's face e as the quad of corners
//! `4e + i`: `face(h0)`, vertex face `tail(h0)`, `face(twin h0)`, vertex
//! face `tail(twin h0)` (h0 the side of e met first in face order), each
//! corner's side crossing an ambo edge `C(g)`, g an input half-edge. That
//! quad is join's face e from its first corner, and join's face order is
//! e's order, so [`super::dual_kis`] over join only needs, per corner, its
//! vertex and the corner of its twin side; half-edge ids of join never
//! matter there (its keys only name edges, numbered by first crossing).
//! So the corners are laid here in join's face order and `dual_kis`'s walk
//! runs over them with the same arithmetic: the output is the
//! composition's bit for bit (`keyed::hashes`); holes and point-spheres
//! take the composition.

use super::build::{reserve, reserve_from, In};
use super::dual_ambo::{centroids, first_side, join};
use super::dual_kis::dual_kis;
use crate::budget::Counts;
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::face_parents::{self as fp, Step, VERT};
use crate::schemes::hosts::check_output_size;
use glam::DVec3;

/// `dual_kis(&join(m)?)` (bevel), the same output, errors and face parents.
pub(crate) fn bevel(m: &Mesh) -> Result<Mesh> {
    if m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0) {
        return dual_kis(&join(m)?);
    }
    crate::cancel::check()?;
    let c = In::new(m)?;
    let (nv, ne, nf, nh) = (c.nv, c.ne, c.nf, c.nh);
    // join's checks (ambo's, then the dual's on ambo's counts)
    reserve("ambo", m, ne, 2 * ne, nf + nv)?;
    check_output_size("dual", 2 * nh, nf + nv)?;
    // join's counts: quads only, and every edge joins a face centroid to
    // a vertex face's, so no self-loops (`Counts::of` of join's mesh)
    let (nvj, nej, nfj, nhj) = (nf + nv, nh, ne, 2 * nh);
    let jc = Counts::closed(nvj as u64, nej as u64, nfj as u64, 0, 0);
    // then kis's checks on join, and the last dual's on kis's counts
    reserve_from("kis", &jc, nvj + nfj, nej + nhj, nhj)?;
    check_output_size("dual", 2 * (nej + nhj), nhj)?;
    let (prev, vert, face) = (c.prev, c.vert, c.face);
    let jpos = centroids(&c)?;
    // join's corners: jv the vertex, jt the corner of the twin side
    let h0s: Vec<u32> = (0..ne).map(|e| first_side(&c, e)).collect();
    let nf32 = nf as u32;
    let mut jv = Vec::with_capacity(nhj);
    for &h0 in &h0s {
        let t0 = h0 ^ 1;
        jv.extend([face[h0 as usize], nf32 + vert[h0 as usize], face[t0 as usize], nf32 + vert[t0 as usize]]);
    }
    crate::cancel::check()?;
    // key g is crossed at corner 0 or 2 of the quad of g's edge (g = h0 or
    // twin h0) and at corner 3 or 1 of the quad of prev g's edge (g =
    // next h0 or next twin h0)
    let mut jt = vec![0u32; nhj];
    for g in 0..nh {
        let (e, p) = (g >> 1, prev[g]);
        let ep = (p >> 1) as usize;
        let a = 4 * e as u32 + if g as u32 == h0s[e] { 0 } else { 2 };
        let b = 4 * ep as u32 + if p == h0s[ep] { 3 } else { 1 };
        jt[a as usize] = b;
        jt[b as usize] = a;
    }
    drop(h0s);
    let nxt = |x: u32| (x & !3) | ((x + 1) & 3);
    let prv = |x: u32| (x & !3) | ((x + 3) & 3);
    let p = |x: u32| jpos[jv[x as usize] as usize];
    // dual_kis's vertices: kis's triangle centroids in join's corner order,
    // over kis's apex (`kis::apex`: centroid, Newell normal, mean distance)
    let mut pos = Vec::with_capacity(nhj);
    for e in 0..nfj {
        crate::cancel::poll(e)?;
        let cs = [4 * e as u32, 4 * e as u32 + 1, 4 * e as u32 + 2, 4 * e as u32 + 3];
        let s: DVec3 = cs.iter().map(|&x| p(x)).sum();
        let cen = s / cs.len() as f64;
        let a = super::kis::apex_of(cen, || cs.iter().map(|&x| p(x)));
        for &x in &cs {
            let mut s = DVec3::ZERO;
            s += p(x);
            s += p(nxt(x));
            s += a;
            pos.push(s / 3.0);
        }
    }
    // dual_kis's walk (see there): first kis corner of each join vertex in
    // kis's face order, tail corner of T(x) as 2x, head corner as 2x + 1
    let mut first = vec![NONE; nvj];
    for x in 0..nhj as u32 {
        let (t, d) = (jv[x as usize] as usize, jv[nxt(x) as usize] as usize);
        if first[t] == NONE {
            first[t] = 2 * x;
        }
        if first[d] == NONE {
            first[d] = 2 * x + 1;
        }
    }
    // keys: join's edge of corner x by its lower corner, spokes nhj + x
    let edge = |x: u32| x.min(jt[x as usize]) as usize;
    let spoke = |x: u32| nhj + x as usize;
    let mut walk = DualWalk::new(pos, 2 * (nej + nhj), nvj + nfj, 2 * nhj);
    for v in 0..nvj {
        crate::cancel::poll(v)?;
        let last = super::dual_kis::vertex_ring(&mut walk, v, first[v], |h, head| {
            if head { (h, edge(h), 2 * jt[h as usize]) } else { (h, spoke(h), 2 * prv(h) + 1) }
        });
        walk.close(v, last);
    }
    for e in 0..nfj {
        crate::cancel::poll(e)?;
        let s = 4 * e as u32;
        let (mut h, mut last) = (s, NONE);
        loop {
            let n = nxt(h);
            walk.put(nvj + e, h, spoke(n), &mut last);
            h = n;
            if h == s {
                break;
            }
        }
        walk.close(nvj + e, last);
    }
    let cols = walk.finish()?;
    if fp::recording() {
        // join, kis, dual composed: face w < nvj is born around join's
        // vertex w (face w, or vertex w - nf), face nvj + e around kis's
        // apex of join's face e (from the face of e's first side, as join's
        // face e); vertex x inside join's face x / 4
        let face = (0..nf as u32).chain((0..nv as u32).map(|v| VERT | v)).chain((0..ne).map(|e| c.face[2 * e])).collect();
        let vertex = (0..nhj).map(|x| c.face[2 * (x / 4)]).collect();
        fp::record(Some(Step { in_v: nv, in_f: nf, face, vertex }));
    }
    Mesh::from_columns(cols)
}

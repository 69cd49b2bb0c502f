//! `dual(kis(m))` (zip, and the last two steps of bevel; truncate's one
//! pass, `truncate.rs`, runs the same walk over the dual it never builds)
//! without building kis's output (issue 16: kis's 2E triangles were built
//! only to be walked by the dual, half of zip's time).
//!
//! Kis (all faces) lays, per input corner h of face f in face-layout order
//! (corner index g), the triangle T(g) = [tail h, head h, apex f] with the
//! side keys `edge(h)`, spoke `next h`, spoke `h`; its vertices are the
//! input's, then one apex per face. The dual's vertex g is T(g)'s centroid
//! (summed from its tail corner, as the dual sums); its face w goes round
//! kis vertex w from that vertex's first corner in kis's face order:
//!
//! * around input vertex v the triangles alternate: the tail corner of
//!   T(h) (crossing spoke h) is followed by the head corner of T(prev h)
//!   (crossing edge(prev h)), which is followed by the tail corner of
//!   T(twin prev h);
//! * around the apex of f: T(h) (crossing spoke `next h`), then T(next h).
//!
//! Edges are numbered by first crossing, as [`crate::schemes::dual`] does,
//! so the output is the composition's bit for bit (`keyed::hashes`).

use super::build::{reserve, Ctx};
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::dual::dual;
use crate::schemes::face_parents::{self as fp, Step, VERT};
use crate::schemes::hosts::check_output_size;
use glam::DVec3;

/// `dual(&kis(m, None)?)`, the same output (with holes or point-spheres it
/// is that composition).
pub(crate) fn dual_kis(m: &Mesh) -> Result<Mesh> {
    if m.n_holes() > 0 || m.v_out.iter().any(|&o| o & POINT != 0) {
        return dual(&super::kis(m, None)?);
    }
    let c = Ctx::new(m)?;
    let (nv, ne, nf, nh) = (c.nv, c.ne, c.nf, c.nh);
    // kis's own checks, then the dual's on kis's counts
    reserve("kis", m, nv + nf, ne + nh, nh)?;
    check_output_size("dual", 2 * (ne + nh), nh)?;
    let (next, prev, vert) = (c.next, c.prev, c.vert);
    let fh = &c.fl.fh;
    let cidx = &c.fl.cidx;
    // centroids of the triangles, in corner order
    let mut pos = Vec::with_capacity(nh);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let a = super::kis::apex(&c, f);
        for h in c.corners(f) {
            let mut s = DVec3::ZERO;
            s += c.p(c.tail(h));
            s += c.p(c.head(h));
            s += a;
            pos.push(s / 3.0);
        }
    }
    // first kis corner of each input vertex, in kis's face order: tail
    // corner of T(h) as 2h, head corner as 2h + 1
    let mut first = vec![NONE; nv];
    for &h in fh {
        let (t, d) = (vert[h as usize] as usize, vert[h as usize ^ 1] as usize);
        if first[t] == NONE {
            first[t] = 2 * h;
        }
        if first[d] == NONE {
            first[d] = 2 * h + 1;
        }
    }
    let nho = 2 * (ne + nh);
    // slot[key] (kis's keys: edge e, spoke ne + h): 0 before its first
    // crossing, else its output edge + 1
    let mut walk = DualWalk::new(pos, nho, nv + nf, ne + nh);
    let mut lasts = vec![NONE; nv + nf];
    for v in 0..nv {
        crate::cancel::poll(v)?;
        lasts[v] = vertex_ring(&mut walk, v, first[v], |h, head| {
            if head {
                // head corner of T(h): crosses edge(h), then the tail corner of T(twin h)
                (cidx[h as usize], (h >> 1) as usize, 2 * (h ^ 1))
            } else {
                // tail corner of T(h): crosses spoke h, then the head corner of T(prev h)
                (cidx[h as usize], ne + h as usize, 2 * prev[h as usize] + 1)
            }
        });
    }
    let mut put = |w: usize, g: u32, key: usize, last: &mut u32| walk.put(w, g, key, last);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let s = fh[c.fl.off[f] as usize];
        let (mut h, mut last) = (s, NONE);
        loop {
            let n = next[h as usize];
            put(nv + f, cidx[h as usize], ne + n as usize, &mut last);
            h = n;
            if h == s {
                break;
            }
        }
        lasts[nv + f] = last;
    }
    drop(put);
    let cols = walk.finish_at(&lasts)?;
    if fp::recording() {
        // kis then dual, composed: face w is born around kis vertex w (an
        // input vertex, or the apex of face f), vertex g inside face(h)
        let face = (0..nv as u32).map(|v| VERT | v).chain(0..nf as u32).collect();
        let vertex = fh.iter().map(|&h| c.face[h as usize]).collect();
        fp::record(Some(Step { in_v: nv, in_f: nf, face, vertex }));
    }
    Mesh::from_columns(cols)
}

/// The dual face `w` of a kis vertex, walked from `s` over the corners of
/// the kis triangles around it (`2h`: the tail corner of triangle `h`,
/// `2h + 1`: its head corner): `cross(h, head)` gives that triangle's
/// output vertex, the key of the side crossed and the next corner. Returns
/// the last half-edge put, for [`DualWalk::close`]. Shared by kis's dual
/// and bevel's (`bevel.rs`, over join's corners).
pub(super) fn vertex_ring(walk: &mut DualWalk, w: usize, s: u32, cross: impl Fn(u32, bool) -> (u32, usize, u32)) -> u32 {
    let (mut x, mut last) = (s, NONE);
    loop {
        let (g, key, next) = cross(x >> 1, x & 1 == 1);
        walk.put(w, g, key, &mut last);
        x = next;
        if x == s {
            return last;
        }
    }
}

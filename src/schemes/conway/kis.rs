//! Kis (Hart's `k`, `kN`): a pyramid on every face, or on the N-sided
//! faces only.
//!
//! Topology (polyhedronisme `kisN`): each chosen face of n corners becomes
//! the n triangles `[tail(h), head(h), apex]`, one per corner `h`; its edges
//! keep their other side, the n spokes `v–apex` are new. Other faces are
//! kept. With S the chosen faces and Σ their corners:
//!
//! ```text
//! V' = V + |S|,   E' = E + Σ,   F' = F − |S| + Σ
//! k (all faces):  V' = V + F,   E' = 3E,   F' = 2E
//! ```
//!
//! Face sizes: Σ triangles, the unchosen faces unchanged. New vertices
//! follow the input ones, in face order.
//!
//! Geometry (polyhedronisme, `apexdist` 0.1): the apex sits over the face
//! centroid along the face's unit normal, at 0.1 of the face's mean
//! centroid–corner distance (polyhedronisme uses 0.1 on unit-size seeds;
//! scaling by the face keeps it size-free). A degenerate face (zero normal)
//! gets its apex at the centroid.

use super::build::{reserve, Ctx, In, Out};
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use glam::DVec3;
use crate::schemes::hosts::with_point_spheres;

/// Kis of every face (`n = None`) or of the faces with `n` corners.
pub fn kis(m: &Mesh, n: Option<usize>) -> Result<Mesh> {
    with_point_spheres("kis", m, |m| step(m, n))
}

fn step(m: &Mesh, n: Option<usize>) -> Result<Mesh> {
    let c = Ctx::new(m)?;
    let chosen = |f: usize| n.map_or(true, |n| c.fl.degree(f) == n);
    let (mut s, mut sigma) = (0usize, 0usize);
    for f in (0..c.nf).filter(|&f| chosen(f)) {
        s += 1;
        sigma += c.fl.degree(f);
    }
    reserve("kis", m, c.nv + s, c.ne + sigma, c.nf - s + sigma)?;
    fan("kis", &c, chosen, |f| apex(&c, f))
}

/// Kis's apex over face `f` (see the module docs); shared with
/// [`super::dual_kis`], which must give the same bits.
#[inline]
pub(crate) fn apex(c: &Ctx<'_>, f: usize) -> DVec3 {
    let r = c.corners(f).map(|h| c.p(c.tail(h)).distance(c.cen[f])).sum::<f64>() / c.fl.degree(f) as f64;
    c.cen[f] + c.normal(f) * (0.1 * r)
}

/// The centroid fan written once, for Conway's kis and TopMod's stellate:
/// each `chosen` face of n corners becomes the n triangles
/// `[tail(h), head(h), apex(f)]`, the other faces stay. Apices follow the
/// input's vertices in face order; input edge e keeps id e, the spoke of
/// corner g is E + g.
pub(crate) fn fan(name: &str, c: &In<'_>, chosen: impl Fn(usize) -> bool, apex: impl Fn(usize) -> DVec3) -> Result<Mesh> {
    let mut pos = c.positions(c.nf);
    let mut at = vec![NONE; c.nf];
    let mut sigma = 0;
    for (f, a) in at.iter_mut().enumerate() {
        if chosen(f) {
            *a = pos.len() as u32;
            pos.push(apex(f));
            sigma += c.fl.degree(f);
        }
    }
    crate::cancel::check()?;
    let spoke = |g: u32| c.ne as u32 + g;
    let mut out = Out::new(pos, c.ne + c.nh, c.nf + sigma, c.nh + 2 * sigma).of(c);
    out.keeps_vertices(c.nv);
    for (f, &a) in at.iter().enumerate() {
        crate::cancel::poll(f)?;
        out.from_face(f);
        let hs = c.fl.corners(f);
        if a == NONE {
            out.face(hs.iter().map(|&h| (c.vert[h as usize], h >> 1)));
            continue;
        }
        for &h in hs {
            out.face([(c.vert[h as usize], h >> 1), (c.vert[h as usize ^ 1], spoke(c.next[h as usize])), (a, spoke(h))]);
        }
    }
    out.finish(name)
}

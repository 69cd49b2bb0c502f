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
    apex_of(c.cen[f], || c.corners(f).map(|h| c.p(c.tail(h))))
}

/// Kis's apex over a polygon with centroid `cen` and the corners
/// `corners()` gives in cycle order: along the unit Newell normal at 0.1 of
/// the mean centroid–corner distance (also bevel's, over join's faces).
pub(crate) fn apex_of<I: Iterator<Item = DVec3>>(cen: DVec3, corners: impl Fn() -> I) -> DVec3 {
    let (mut n, mut first, mut last, mut k) = (DVec3::ZERO, None, DVec3::ZERO, 0usize);
    for q in corners() {
        if first.is_some() {
            n += last.cross(q);
        } else {
            first = Some(q);
        }
        last = q;
        k += 1;
    }
    if let Some(q) = first {
        n += last.cross(q);
    }
    let r = corners().map(|q| q.distance(cen)).sum::<f64>() / k as f64;
    let u = crate::geometry::unit_newell(n, &corners);
    let a = cen + u * (0.1 * r);
    if (a.is_finite() && (r > 0.0 || u == DVec3::ZERO)) || !cen.is_finite() {
        return a;
    }
    // coordinates past ~1e154 (r overflows, the apex is NaN) or below
    // ~1e-154 (r underflows to 0): the mean distance of the corners
    // divided by their largest coordinate, times it; ordinary inputs never
    // come here, so their bits are unchanged
    let s = corners().map(|q| (q - cen).abs().max_element()).fold(0.0, f64::max);
    if !(s > 0.0 && s.is_finite()) {
        return cen;
    }
    let r = corners().map(|q| ((q - cen) / s).length()).sum::<f64>() / k as f64;
    cen + u * (0.1 * r * s)
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

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

use super::build::{reserve, Ctx, Out};
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use crate::schemes::hosts::with_point_spheres;

/// Kis of every face (`n = None`) or of the faces with `n` corners.
pub fn kis(m: &Mesh, n: Option<usize>) -> Result<Mesh> {
    with_point_spheres("kis", m, |m| step(m, n))
}

fn step(m: &Mesh, n: Option<usize>) -> Result<Mesh> {
    let c = Ctx::new(m)?;
    let chosen = |f: usize| match n {
        None => true,
        Some(n) => c.fl.degree(f) == n,
    };
    let (mut s, mut sigma) = (0usize, 0usize);
    for f in 0..c.nf {
        if chosen(f) {
            s += 1;
            sigma += c.fl.degree(f);
        }
    }
    reserve("kis", m, c.nv + s, c.ne + sigma, c.nf - s + sigma)?;
    let mut pos = Vec::with_capacity(c.nv + s);
    pos.extend_from_slice(m.positions());
    let mut apex = vec![NONE; c.nf];
    for (f, a) in apex.iter_mut().enumerate() {
        if chosen(f) {
            *a = pos.len() as u32;
            let r = c.corners(f).map(|h| c.p(c.tail(h)).distance(c.cen[f])).sum::<f64>() / c.fl.degree(f) as f64;
            pos.push(c.cen[f] + c.normal(f) * (0.1 * r));
        }
    }
    crate::cancel::check()?;
    // edge ids: input edge e is e; the spoke of corner g is ne + g
    let spoke = |g: usize| (c.ne + g) as u32;
    let mut out = Out::new(pos, c.ne + c.nh, c.nh + 2 * sigma, c.nf + sigma);
    for (f, &a) in apex.iter().enumerate() {
        crate::cancel::poll(f)?;
        if a == NONE {
            out.face(c.corners(f).map(|h| (c.tail(h), (h >> 1) as u32)));
            continue;
        }
        for h in c.corners(f) {
            let nx = c.next(h);
            out.face([(c.tail(h), (h >> 1) as u32), (c.head(h), spoke(nx)), (a, spoke(h))]);
        }
    }
    out.finish("kis")
}

//! Snub (`s` = `dg`) and volute's last step (`v` = `dwd`): `dual(gyro(m))`
//! and `dual(whirl(x))` without gyro's or whirl's output (issue 16: their
//! 2E pentagons or hexagons were built only to be walked by the dual, and
//! snub and volute were the slowest rows per output corner of the Conway
//! operators).
//!
//! Gyro and whirl (`chiral.rs`) lay, per input half-edge h in index order,
//! one polygon: gyro the pentagon P(h) = [centre(f), p(h), p(twin h),
//! head(h), p(next h)] (f = face(h)), whirl the hexagon H(h) = [q(h), p(h),
//! p(twin h), head(h), p(next h), q(next h)], then (whirl only) per face f
//! the inner face [q(h) for h of f]. The sides leaving their corners carry
//! keys, each carried by two sides:
//!
//! | key | gyro: corners carrying it | whirl: corners carrying it |
//! | --- | --- | --- |
//! | mid(e) | 1 of P(2e), 1 of P(2e + 1) | 1 of H(2e), 1 of H(2e + 1) |
//! | outer(g) | 2 of P(twin g), 3 of P(prev g) | 2 of H(twin g), 3 of H(prev g) |
//! | spoke(g) (gyro) | 0 of P(g), 4 of P(prev g) | |
//! | q(g)–p(g) (whirl) | | 0 of H(g), 4 of H(prev g) |
//! | q(g)–q(next g) (whirl) | | 5 of H(g), the inner face's corner g |
//!
//! The dual's vertex per polygon is its centroid, summed from its first
//! corner as the dual sums a face. Its face w goes round the polygons'
//! vertex w (gyro: the input vertices, the face centres, the points p(h);
//! whirl: the input vertices, the p(h), the q(h)) from that vertex's first
//! corner in the builder's face order (the lowest polygon, then the lowest
//! corner): at each corner c, the dual's corner is c's polygon with the key
//! of c's previous side, and the walk goes on at the other corner of that
//! key (the twin of the previous side, as [`crate::schemes::dual`] turns
//! round a vertex). Edges are numbered by first crossing ([`DualWalk`]), so
//! the outputs are the compositions' bit for bit
//! (`fused_builds_are_their_compositions`). Holes, point-spheres and traced
//! builds (face parents) take the compositions.

use super::build::{reserve, Ctx};
use super::chiral::{gyro, whirl};
use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use crate::schemes::dual::dual;
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::hosts::{check_output_size, fusable};
use glam::DVec3;

/// Per input vertex, its lowest incoming half-edge (the first polygon with
/// the vertex as its corner 3), or None if a vertex has none.
fn first_in(c: &Ctx) -> Option<Vec<u32>> {
    let mut first = vec![NONE; c.nv];
    for h in 0..c.nh {
        let v = &mut first[c.head(h) as usize];
        if *v == NONE {
            *v = h as u32;
        }
    }
    (!first.contains(&NONE)).then_some(first)
}

/// `dual(&gyro(m)?)` (snub), the same output and errors.
pub(crate) fn snub(m: &Mesh) -> Result<Mesh> {
    if !fusable(m) {
        return dual(&gyro(m)?);
    }
    let c = Ctx::new(m)?;
    let (nv, ne, nf, nh) = (c.nv, c.ne, c.nf, c.nh);
    // gyro's own check, then the dual's on gyro's counts
    reserve("gyro", m, nv + nf + nh, 5 * ne, nh)?;
    check_output_size("dual", 10 * ne, nh)?;
    let Some(first) = first_in(&c) else { return dual(&gyro(m)?) };
    let (next, prev) = (c.next, c.prev);
    // the pentagons' centroids, summed from the centre
    let mut pos = Vec::with_capacity(nh);
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let mut s = DVec3::ZERO;
        s += c.cen[c.face[h] as usize];
        s += c.third(h);
        s += c.third(h ^ 1);
        s += c.p(c.head(h));
        s += c.third(c.next(h));
        pos.push(s / 5.0);
    }
    // corners 5P + i; gyro's keys: spoke g, mid nh + e, outer 2nh + g
    let step = |x: usize| {
        let (p, n) = (x / 5, next[x / 5] as usize);
        let (key, other) = match x % 5 {
            // the previous side is corner 4's: spoke(next P), also corner 0 of P(next P)
            0 => (n, 5 * n),
            1 => (p, 5 * prev[p] as usize + 4),
            2 => (nh + (p >> 1), 5 * (p ^ 1) + 1),
            3 => (2 * nh + (p ^ 1), 5 * prev[p ^ 1] as usize + 3),
            _ => (2 * nh + n, 5 * (n ^ 1) + 2),
        };
        (p as u32, key, other)
    };
    // first corners: input vertex v at corner 3 of P(its lowest incoming h);
    // centre f at corner 0 of f's lowest half-edge; p(g) at the lowest of
    // corner 1 of P(g), 2 of P(twin g), 4 of P(prev g)
    let start = |w: usize| {
        if w < nv {
            5 * first[w] as usize + 3
        } else if w < nv + nf {
            5 * c.fl.corners(w - nv).iter().min().copied().unwrap_or(0) as usize
        } else {
            let g = w - nv - nf;
            (5 * g + 1).min(5 * (g ^ 1) + 2).min(5 * prev[g] as usize + 4)
        }
    };
    Mesh::from_columns(DualWalk::new(pos, 10 * ne, nv + nf + nh, 3 * nh).rings(nv + nf + nh, start, step)?)
}

/// `dual(&whirl(x)?)` (volute's last two steps), the same output and errors.
pub(crate) fn dual_whirl(x: &Mesh) -> Result<Mesh> {
    if !fusable(x) {
        return dual(&whirl(x)?);
    }
    let c = Ctx::new(x)?;
    let (nv, ne, nf, nh) = (c.nv, c.ne, c.nf, c.nh);
    // whirl's own check, then the dual's on whirl's counts
    reserve("whirl", x, nv + 2 * nh, 7 * ne, nf + nh)?;
    check_output_size("dual", 14 * ne, nf + nh)?;
    let Some(first) = first_in(&c) else { return dual(&whirl(x)?) };
    let (next, prev) = (c.next, c.prev);
    // whirl's points: p(h) a third along h, q(h) a third of the way from
    // the centroid of face h to p(h)
    let q = |h: usize| c.cen[c.face[h] as usize].lerp(c.third(h), 1.0 / 3.0);
    // the hexagons' centroids (from q(h)), then the inner faces' (from
    // their first corner)
    let mut pos = Vec::with_capacity(nh + nf);
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let n = c.next(h);
        let mut s = DVec3::ZERO;
        s += q(h);
        s += c.third(h);
        s += c.third(h ^ 1);
        s += c.p(c.head(h));
        s += c.third(n);
        s += q(n);
        pos.push(s / 6.0);
    }
    for f in 0..nf {
        crate::cancel::poll(f)?;
        pos.push(crate::schemes::dual_walk::corner_mean(c.fl.corners(f), q));
    }
    // corners 6P + i of the hexagons, then 6nh + g of the inner faces;
    // whirl's keys: inner side g, mid nh + e, outer 2nh + g, q(g)–p(g) 3nh + g
    let step = |x: usize| {
        if x >= 6 * nh {
            // inner face of f at g: the previous side is prev g's, also corner 5 of H(prev g)
            let g = x - 6 * nh;
            let pg = prev[g] as usize;
            return ((nh + c.face[g] as usize) as u32, pg, 6 * pg + 5);
        }
        let (p, n) = (x / 6, next[x / 6] as usize);
        let (key, other) = match x % 6 {
            // the previous side is corner 5's: the inner side P, also the inner face's corner P
            0 => (p, 6 * nh + p),
            1 => (3 * nh + p, 6 * prev[p] as usize + 4),
            2 => (nh + (p >> 1), 6 * (p ^ 1) + 1),
            3 => (2 * nh + (p ^ 1), 6 * prev[p ^ 1] as usize + 3),
            4 => (2 * nh + n, 6 * (n ^ 1) + 2),
            _ => (3 * nh + n, 6 * n),
        };
        (p as u32, key, other)
    };
    // first corners (every vertex has one in a hexagon, which come first):
    // input vertex v at corner 3 of H(its lowest incoming h); p(g) at the
    // lowest of corner 1 of H(g), 2 of H(twin g), 4 of H(prev g); q(g) at
    // the lower of corner 0 of H(g) and 5 of H(prev g)
    let start = |w: usize| {
        if w < nv {
            6 * first[w] as usize + 3
        } else if w < nv + nh {
            let g = w - nv;
            (6 * g + 1).min(6 * (g ^ 1) + 2).min(6 * prev[g] as usize + 4)
        } else {
            let g = w - nv - nh;
            (6 * g).min(6 * prev[g] as usize + 5)
        }
    };
    Mesh::from_columns(DualWalk::new(pos, 14 * ne, nv + 2 * nh, 4 * nh).rings(nv + 2 * nh, start, step)?)
}

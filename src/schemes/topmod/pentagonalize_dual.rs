//! `dual(pentagonalize(x))` (dual pentagonalization after its first dual,
//! TopMod's `subdivideDualPentagonal`) without building pentagonalization's
//! output (issue 16: its 2E pentagons were built only for the dual to walk
//! them; the row was the slowest per output corner of the TopMod menu).
//!
//! Pentagonalization (`pentagonal::pentagonalize`) lays, per face f and
//! corner h in face-layout order (index g), the pentagon Q(h) = [p(h),
//! p(twin h), head(h), p(next h), c(f)], whose sides, from its corners 0–4,
//! carry the keys mid(edge h), seg(twin h), seg(next h), spoke(next h) and
//! spoke(h) (seg(k): the third of k at its tail). Each key is carried by two
//! sides: mid(e) by corner 0 of Q(2e) and of Q(2e + 1); seg(k) by corner 1
//! of Q(twin k) and corner 2 of Q(prev k); spoke(k) by corner 3 of Q(prev k)
//! and corner 4 of Q(k).
//!
//! The dual's vertex g is Q's centroid, summed from p(h) as the dual sums a
//! face. Its face w goes round pentagonalization's vertex w (the input
//! vertices, the points p(h), the centroids c(f)) from w's first corner in
//! face order (the lowest pentagon, then the lowest corner): at each corner,
//! the dual's corner is the pentagon with the key of its previous side, and
//! the walk goes on at the other corner of that key (the twin of the
//! previous side, as [`crate::schemes::dual`] turns round a vertex). Edges
//! are numbered by first crossing ([`DualWalk`]), so the output is the
//! composition's bit for bit (`dual_pentagonalize_is_its_composition`).
//! Holes, point-spheres, bad offsets and traced builds (face parents) take
//! the composition.

use crate::error::Result;
use crate::mesh::{Mesh, NONE};
use crate::schemes::dual::dual;
use crate::schemes::dual_walk::DualWalk;
use crate::schemes::hosts::{check_output_size, fusable};
use crate::schemes::keyed::In;
use glam::DVec3;

/// `dual(&pentagonalize(x, offset)?)`, the same output and errors.
pub(crate) fn dual_of_pentagonalize(x: &Mesh, offset: f64) -> Result<Mesh> {
    let composed = || dual(&super::pentagonal::pentagonalize(x, offset)?);
    if !(offset.is_finite() && (0.0..=1.0).contains(&offset) && fusable(x)) {
        return composed();
    }
    let i = In::new(x)?;
    let (nv, ne, nf, nh) = (i.nv, i.ne, i.nf, i.nh);
    // pentagonalization's own check (its builder's), then the dual's
    check_output_size("pentagonalize", 10 * ne, nv + nh + nf)?;
    check_output_size("dual", 10 * ne, nh)?;
    let (next, prev, vert, face) = (i.next, i.prev, i.vert, i.face);
    let (fh, cidx) = (&i.fl.fh, &i.fl.cidx);
    // per input vertex, the lowest pentagon with it as corner 2 (its h enters the vertex)
    let mut first = vec![NONE; nv];
    for &h in fh {
        let v = &mut first[vert[h as usize ^ 1] as usize];
        if *v == NONE {
            *v = h;
        }
    }
    if first.contains(&NONE) {
        return composed(); // a vertex without a corner: not a closed mesh's
    }
    let cent = i.centroids();
    crate::cancel::check()?;
    let p = |h: usize| i.p(h).lerp(i.q(h), 1.0 / 3.0).lerp(cent[face[h] as usize], offset);
    // the pentagons' centroids, in layout order, summed from p(h)
    let mut pos = Vec::with_capacity(nh);
    for (g, &h) in fh.iter().enumerate() {
        crate::cancel::poll(g)?;
        let h = h as usize;
        let mut s = DVec3::ZERO;
        s += p(h);
        s += p(h ^ 1);
        s += i.q(h);
        s += p(next[h] as usize);
        s += cent[face[h] as usize];
        pos.push(s / 5.0);
    }
    // corners 5h + i (Q(h)'s corner i); keys: seg k, mid nh + e, spoke nh + ne + k
    let spoke = nh + ne;
    let step = |x: usize| {
        let (h, n) = (x / 5, next[x / 5] as usize);
        let (key, other) = match x % 5 {
            // the previous side is corner 4's: spoke(h), also corner 3 of Q(prev h)
            0 => (spoke + h, 5 * prev[h] as usize + 3),
            1 => (nh + (h >> 1), 5 * (h ^ 1)),
            2 => (h ^ 1, 5 * prev[h ^ 1] as usize + 2),
            3 => (n, 5 * (n ^ 1) + 1),
            _ => (spoke + n, 5 * n + 4),
        };
        (cidx[h], key, other)
    };
    // the order of corners in pentagonalization's face order
    let rank = |x: usize| 5 * cidx[x / 5] as usize + x % 5;
    let start = |w: usize| {
        if w < nv {
            5 * first[w] as usize + 2
        } else if w < nv + nh {
            // p(k): corner 0 of Q(k), 1 of Q(twin k), 3 of Q(prev k)
            let k = w - nv;
            [5 * k, 5 * (k ^ 1) + 1, 5 * prev[k] as usize + 3].into_iter().min_by_key(|&x| rank(x)).unwrap_or(5 * k)
        } else {
            // c(f): corner 4 of Q(f's first corner)
            5 * fh[i.fl.off[w - nv - nh] as usize] as usize + 4
        }
    };
    let n = nv + nh + nf;
    Mesh::from_columns(DualWalk::new(pos, 10 * ne, n, 2 * nh + ne).rings(n, start, step)?)
}

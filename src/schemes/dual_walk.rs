//! The columns of a dual written by walking round its faces: the one-pass
//! dual ([`super::dual`]) and the compositions fused with their last dual
//! (`topmod::*_dual`, `conway::dual_kis`, `topmod::compose::dual_dual`) lay
//! each output face's corners in turn. A corner's side crosses an edge of
//! the mesh being dualized, named by a key; the first crossing of a key
//! makes output edge `n` (half-edge `2n`), the second its twin (`2n + 1`),
//! so edges are numbered by first crossing as [`super::dual`] numbers them.

use crate::error::{MeshError, Result};
use crate::mesh::{Columns, NONE};
use glam::DVec3;

pub(crate) struct DualWalk {
    cols: Columns,
    /// Per key: 0 before its first crossing, else its output edge + 1.
    slot: Vec<u32>,
    n_out: u32,
}

impl DualWalk {
    /// A walk writing `n_halfedges` half-edges and `n_faces` faces over the
    /// output vertices `pos`, whose sides cross `n_keys` keys.
    pub(crate) fn new(pos: Vec<DVec3>, n_halfedges: usize, n_faces: usize, n_keys: usize) -> DualWalk {
        DualWalk::over(Columns::new(pos, n_halfedges, n_faces), n_keys)
    }

    /// [`DualWalk::new`] for `n_points` output vertices whose positions are
    /// given at [`finish_with`](Self::finish_with) (computed beside the walk).
    pub(crate) fn for_points(n_points: usize, n_halfedges: usize, n_faces: usize, n_keys: usize) -> DualWalk {
        DualWalk::over(Columns::for_points(n_points, n_halfedges, n_faces), n_keys)
    }

    /// A walk over fresh columns, no vertex given its first corner yet.
    fn over(mut cols: Columns, n_keys: usize) -> DualWalk {
        cols.v_out.fill(NONE);
        DualWalk { cols, slot: vec![0; n_keys], n_out: 0 }
    }

    /// [`finish`](Self::finish) of a walk made by [`for_points`](Self::for_points),
    /// with its `n_points` positions.
    pub(crate) fn finish_with(mut self, pos: Vec<DVec3>) -> Result<Columns> {
        if pos.len() != self.cols.v_out.len() {
            return Err(MeshError::Invariant(format!("dual: {} positions for {} vertices", pos.len(), self.cols.v_out.len())));
        }
        self.cols.pos = pos;
        self.finish()
    }

    /// The output vertices' positions, for walks that place them as they go.
    pub(crate) fn positions_mut(&mut self) -> &mut [DVec3] {
        &mut self.cols.pos
    }

    /// The next corner of face `w`: at output vertex `v`, its side crossing
    /// `key`; `last` is the face's previous corner (`NONE` before its first)
    /// and becomes this one.
    #[inline]
    pub(crate) fn put(&mut self, w: usize, v: u32, key: usize, last: &mut u32) {
        let i = crossing(&mut self.slot[key], &mut self.n_out);
        let c = &mut self.cols;
        c.he_vert[i as usize] = v;
        c.he_face[i as usize] = w as u32;
        let o = &mut c.v_out[v as usize];
        if *o == NONE {
            *o = i;
        }
        if *last == NONE {
            c.f_start[w] = i;
        } else {
            c.he_next[*last as usize] = i;
            c.he_prev[i as usize] = *last;
        }
        *last = i;
    }

    /// Closes face `w`, whose last corner is `last`.
    #[inline]
    pub(crate) fn close(&mut self, w: usize, last: u32) {
        let c = &mut self.cols;
        let s = c.f_start[w];
        c.he_next[last as usize] = s;
        c.he_prev[s as usize] = last;
    }

    /// The columns, once every key was crossed twice (every face closed).
    pub(crate) fn finish(self) -> Result<Columns> {
        all_crossed(self.cols.he_next.len(), self.n_out)?;
        Ok(self.cols)
    }

    /// The dual's faces `0..n`, each walked round a vertex of a mesh that
    /// is never built, whose corners the caller names by index arithmetic:
    /// face w from corner `start(w)`, where `step(x)` gives corner x's face
    /// (the output vertex), the key of the side entering x and the other
    /// corner whose side carries that key (where the walk goes on: the twin
    /// of the entering side, as [`super::dual`] turns round a vertex).
    pub(crate) fn rings(mut self, n: usize, start: impl Fn(usize) -> usize, step: impl Fn(usize) -> (u32, usize, usize)) -> Result<Columns> {
        let mut lasts = Vec::with_capacity(n);
        for w in 0..n {
            crate::cancel::poll(w)?;
            let s = start(w);
            let (mut x, mut last) = (s, NONE);
            loop {
                let (f, key, nx) = step(x);
                self.put(w, f, key, &mut last);
                x = nx;
                if x == s {
                    break;
                }
            }
            lasts.push(last);
        }
        self.finish_at(&lasts)
    }

    /// [`finish`](Self::finish) for walks that closed no face yet: face `w`
    /// is closed at `lasts[w]` once the count is checked.
    pub(crate) fn finish_at(mut self, lasts: &[u32]) -> Result<Columns> {
        all_crossed(self.cols.he_next.len(), self.n_out)?;
        for (w, &last) in lasts.iter().enumerate() {
            self.close(w, last);
        }
        Ok(self.cols)
    }
}

/// The output half-edge of a side crossing a key whose slot is `slot` (0
/// before its first crossing, else its output edge + 1): the first crossing
/// makes output edge `n_out` (half-edge `2 n_out`), the second is its twin.
/// [`DualWalk`] and the in-place and open duals (`dual_in_place`,
/// `dual_open`) number with it.
#[inline]
pub(crate) fn crossing(slot: &mut u32, n_out: &mut u32) -> u32 {
    if *slot == 0 {
        *n_out += 1;
        *slot = *n_out;
        2 * (*n_out - 1)
    } else {
        2 * (*slot - 1) + 1
    }
}

/// Every key crossed twice: `n_out` edges for `nh` corners.
pub(crate) fn all_crossed(nh: usize, n_out: u32) -> Result<()> {
    if 2 * n_out as usize != nh {
        return Err(MeshError::Invariant(format!("dual: {nh} corners but {} half-edges", 2 * n_out)));
    }
    Ok(())
}

/// The rotation of the vertex whose outgoing half-edge is `s`, into `cyc`:
/// h₀ = s, h₁, … with h_{j+1} = prev(h_j) ^ 1, collected backwards through
/// `next` alone (rot⁻¹(g) = next(g ^ 1)), so the in-place duals can give
/// up `he_prev` first. Corner h_j's side crosses edge(prev h_j) =
/// h_{j+1} >> 1.
pub(crate) fn rotation(next: &[u32], s: u32, cyc: &mut Vec<u32>) {
    cyc.clear();
    cyc.push(s);
    let mut g = next[(s ^ 1) as usize];
    while g != s {
        cyc.push(g);
        g = next[(g ^ 1) as usize];
    }
    cyc[1..].reverse();
}

/// The `he_face` and `he_prev` columns of output faces given by their
/// starts and `next`: face w walked from `starts[w]`, in parallel. A walk
/// longer than the half-edges (an output face that does not close: a bug
/// in the caller's numbering) is reported instead of looping.
pub(crate) fn faces_and_prev(next: &[u32], starts: &[u32], face: &mut [u32], prev: &mut [u32]) -> Result<()> {
    use rayon::prelude::*;
    let nh = next.len();
    let long = std::sync::atomic::AtomicBool::new(false);
    let (pf, pp) = (super::hosts::SyncPtr(face.as_mut_ptr()), super::hosts::SyncPtr(prev.as_mut_ptr()));
    debug_assert!(face.len() == nh && prev.len() == nh);
    starts.par_iter().enumerate().with_min_len(super::hosts::MIN_LEN).for_each(|(w, &s)| {
        let (mut h, mut n) = (s, 0usize);
        loop {
            let nx = next[h as usize];
            // SAFETY: every half-edge lies on one output face, whose task
            // alone writes it and the previous-pointer of its successor.
            unsafe {
                *pf.get().add(h as usize) = w as u32;
                *pp.get().add(nx as usize) = h;
            }
            h = nx;
            n += 1;
            if h == s || n > nh {
                break;
            }
        }
        if n > nh {
            long.store(true, std::sync::atomic::Ordering::Relaxed);
        }
    });
    if long.into_inner() {
        return Err(MeshError::Invariant("dual: an output face does not close".into()));
    }
    Ok(())
}

/// The dual's vertex of a face whose corners `hs` carry the points `p(h)`:
/// their mean, summed in corner order from zero as the dual sums a face's
/// corners ([`super::dual::centroids_of`]), so the fused builds give the
/// composition's bits.
#[inline]
pub(crate) fn corner_mean(hs: &[u32], p: impl Fn(usize) -> DVec3) -> DVec3 {
    let mut s = DVec3::ZERO;
    for &h in hs {
        s += p(h as usize);
    }
    s / hs.len() as f64
}

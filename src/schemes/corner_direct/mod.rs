//! Corner (face-varying) data through one level, read straight off the
//! scheme's output numbering: the fast path of the generic corner transfer
//! ([`super::corner_transfer`]) on closed meshes (issue 15: attributes at
//! the cost of their bytes).
//!
//! The generic transfer needs the level's stencils and origins and finds
//! every output corner a *home* input face by search. Each scheme here
//! knows by index arithmetic where its output corners come from, and
//! writes the value the generic transfer defines: the output vertex's row
//! read with the home face's corner values.
//!
//! * Doo-Sabin, honeycomb, dual ([`per_vertex`]): every output vertex is
//!   born inside one input face (a corner point, a centroid), so every
//!   corner at it takes that face's mask of the face's corner values.
//! * Simplest, vertex truncation, √3, Sierpinski ([`per_corner`]): a point
//!   on an input edge (or an old vertex) has one value per face beside it;
//!   each output corner reads it in the face its output face lies in, or,
//!   for the faces around an old vertex, in the face whose corner its
//!   outgoing side cuts (the generic rules 1–3).
//! * Midpoint and Loop (also on non-triangles, through its fan) read the
//!   bilinear child values of [`super::corner_linear`].
//!
//! The paths apply when the input is closed and has no point-spheres: then
//! input exported corner `c` is face-layout corner `c` and every output face
//! is exported. Each checks the output corners' vertices against the layout
//! it assumes (or relies on the output vertex numbering, which the output
//! hashes pin) and returns `None` otherwise; so do open meshes, Sierpinski
//! on self-loops, and Menger (no direct path): the caller then runs the
//! generic transfer.
//!
//! One difference from the generic transfer, where a face passes a vertex
//! at several corners (self-loops, Sierpinski's pyramids): the generic
//! rows are keyed by vertex and give such a vertex the mean of those
//! corners' values; here every corner is read as itself. Data given per
//! (face, vertex) — every UV layout without a wrap inside one face — gets
//! the same values from both (tested).

mod per_corner;
mod per_vertex;
#[cfg(test)]
mod tests;

pub use per_corner::{sierpinski, simplest, sqrt3, truncation};
pub use per_vertex::{doo_sabin, dual, honeycomb};

use super::hosts::FaceLayout;
use crate::error::Result;
use crate::mesh::{Mesh, POINT};
use rayon::prelude::*;

/// Output faces per parallel block.
const BLOCK: usize = 1024;

/// The direct paths' precondition on the level's input: closed, no
/// point-spheres (see the module docs).
pub fn applies(m: &Mesh) -> bool {
    !m.f_hole.iter().any(|&h| h) && !m.v_out.iter().any(|&o| o & POINT != 0)
}

/// The input's face layout when the direct paths apply and `rows` holds
/// one row of `k > 0` per corner; `None` otherwise.
fn layout(m: &Mesh, rows: &[f64], k: usize) -> Result<Option<FaceLayout>> {
    if k == 0 || !applies(m) || rows.len() != m.n_halfedges() * k {
        return Ok(None);
    }
    FaceLayout::new(m).map(Some)
}

/// The number of corners of output face `g` (a closed mesh's face).
fn degree(out: &Mesh, g: usize) -> usize {
    let s = out.f_start[g];
    let (mut h, mut n) = (s, 0);
    loop {
        n += 1;
        h = out.he_next[h as usize];
        if h == s {
            return n;
        }
    }
}

/// The exported corner rows of `out`, a closed mesh without point-spheres
/// (every face exported, its corners from `f_start` in `next` order):
/// `face(g, rows)` writes the `degree(g) × k` rows of output face `g` and
/// returns false where the face is not what the caller's layout says,
/// which makes the result `None`. Parallel over blocks of faces.
fn exported_rows(out: &Mesh, k: usize, face: impl Fn(usize, &mut [f64]) -> bool + Sync) -> Result<Option<Vec<f64>>> {
    let nf = out.n_faces();
    if out.f_hole.iter().any(|&h| h) || out.f_start.iter().any(|&s| s & POINT != 0) {
        return Ok(None);
    }
    let blocks = nf.div_ceil(BLOCK);
    let range = |b: usize| b * BLOCK..((b + 1) * BLOCK).min(nf);
    let counts: Vec<usize> = (0..blocks)
        .into_par_iter()
        .map(|b| if crate::cancel::requested() { 0 } else { range(b).map(|g| degree(out, g)).sum() })
        .collect();
    crate::cancel::check()?;
    let mut res = vec![0.0; counts.iter().sum::<usize>() * k];
    let mut chunks = Vec::with_capacity(blocks);
    let mut rest: &mut [f64] = &mut res;
    for &c in &counts {
        let (a, b) = std::mem::take(&mut rest).split_at_mut(c * k);
        chunks.push(a);
        rest = b;
    }
    let ok = chunks.into_par_iter().enumerate().all(|(b, o)| {
        if crate::cancel::requested() {
            return true; // the check below reports it
        }
        let mut at = 0;
        for g in range(b) {
            let n = degree(out, g) * k;
            if !face(g, &mut o[at..at + n]) {
                return false;
            }
            at += n;
        }
        true
    });
    crate::cancel::check()?;
    Ok(ok.then_some(res))
}

/// The output half-edges of face `g`'s corners, from its first.
fn corners(out: &Mesh, g: usize) -> impl Iterator<Item = u32> + '_ {
    let s = out.f_start[g];
    let mut h = Some(s);
    std::iter::from_fn(move || {
        let r = h?;
        let n = out.he_next[r as usize];
        h = (n != s).then_some(n);
        Some(r)
    })
}

/// Per input face the mean of its corner rows (layout order).
fn face_means(fl: &FaceLayout, rows: &[f64], k: usize) -> Result<Vec<f64>> {
    let nf = fl.off.len() - 1;
    let mut out = vec![0.0; nf * k];
    if k == 0 {
        return Ok(out);
    }
    out.par_chunks_mut(k).with_min_len(super::hosts::MIN_LEN).enumerate().for_each(|(f, o)| {
        let (s, e) = (fl.off[f] as usize, fl.off[f + 1] as usize);
        let w = 1.0 / (e - s) as f64;
        for c in s..e {
            for (o, x) in o.iter_mut().zip(&rows[c * k..(c + 1) * k]) {
                *o += x * w;
            }
        }
    });
    crate::cancel::check()?;
    Ok(out)
}

/// `o = (1 − t) x + t y`, row by row.
#[inline]
fn lerp(o: &mut [f64], x: &[f64], y: &[f64], t: f64) {
    for ((o, x), y) in o.iter_mut().zip(x).zip(y) {
        *o = (1.0 - t) * x + t * y;
    }
}

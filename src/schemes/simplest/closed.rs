//! The closed level of [`super::simplest`]: the half-edge columns written by
//! index arithmetic from the input's face ranks, one pass for a borrowed
//! input, column by column for one given up (issue 19).

use super::super::hosts::{check_output_size, FaceLayout, SyncPtr, MIN_LEN};
use crate::error::Result;
use crate::mesh::{Columns, Mesh};
use glam::DVec3;
use rayon::prelude::*;
use std::borrow::Cow;

/// Connectivity straight into the columns (issue 19), numbered exactly as
/// `from_corner_twins` numbered the corners `[F-corners | V-slots]` it was
/// given (the `output_hashes` test holds it to that). Every F-corner c
/// (half-edge h at rank c in the faces' cycles, side m(h) → m(next h))
/// precedes its twin, a V-slot, so it is the first corner of edge c: it gets
/// half-edge 2c and its twin 2c + 1, the side m(x) → m(prev x) of the
/// V-face of vert[x] with x = next h (inside face[h], cutting its corner at
/// vert[x]). Walking on: the F-face goes to next h; the V-face rotates x to
/// prev[x] ^ 1 = h ^ 1, whose slot side starts the edge of prev(h ^ 1). So
/// each pair (2c, 2c + 1) is a lookup, written from its half-edge h.
///
/// A borrowed input gets its four half-edge columns in one pass and the
/// positions after the ranks are freed. An input given up (`Cow::Owned`)
/// loses its vertex starts, face starts and hole flags before any half-edge
/// column exists, and then each of its columns as soon as the output
/// columns still to come no longer read it (see the body).
pub(super) fn build(mut src: Cow<'_, Mesh>) -> Result<Mesh> {
    let m: &Mesh = &src;
    check_output_size("simplest", 2 * m.n_halfedges(), m.n_edges())?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (cidx, off) = FaceLayout::ranks(m)?;
    // a face starts at its first corner: F-face f at corner off[f], V-face v
    // at the slot of v_out[v]
    let prev = &m.he_prev;
    let f_start = crate::cancel::par_collect(nf + nv, |i| if i < nf { 2 * off[i] } else { 2 * cidx[prev[m.v_out[i - nf] as usize] as usize] + 1 })?;
    drop(off);
    // midpoint e is first seen at the lower of its two F-corners (every
    // F-corner comes before every V-slot)
    let v_out: Vec<u32> = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| 2 * cidx[2 * e].min(cidx[2 * e + 1])).collect();
    if let Cow::Owned(m) = &mut src {
        (m.v_out, m.f_start, m.f_hole) = (Vec::new(), Vec::new(), Vec::new());
    }
    let nfu = nf as u32;
    let mut cols = Columns { pos: Vec::new(), v_out, he_next: Vec::new(), he_prev: Vec::new(), he_vert: Vec::new(), he_face: Vec::new(), f_start, f_hole: vec![false; nf + nv] };
    // the pair (2c, 2c + 1) of F-corner c = cidx[h] in each column, written
    // from h (x = next h); prev's second entry: the slot before x's in its
    // rotation is next(x ^ 1)'s, whose side starts the edge of x ^ 1
    let ci = |k: u32| 2 * cidx[k as usize];
    let next_pair = |prev: &[u32], h: usize, x: usize| (ci(x as u32), ci(prev[h ^ 1]) + 1);
    let prev_pair = |prev: &[u32], h: usize, x: usize| (ci(prev[h]), ci((x ^ 1) as u32) + 1);
    let vert_pair = |h: usize, x: usize| ((h >> 1) as u32, (x >> 1) as u32);
    let face_pair = |face: &[u32], vert: &[u32], h: usize, x: usize| (face[h], nfu + vert[x]);
    if matches!(src, Cow::Borrowed(_)) {
        // nothing to free: one pass writes the four columns
        let m: &Mesh = &src;
        let (next, prev, vert, face) = (&m.he_next, &m.he_prev, &m.he_vert, &m.he_face);
        let c4 = scatter(&cidx, |h| {
            let x = next[h] as usize;
            [next_pair(prev, h, x), prev_pair(prev, h, x), vert_pair(h, x), face_pair(face, vert, h, x)]
        })?;
        let [n, p, v, f] = c4;
        (cols.he_next, cols.he_prev, cols.he_vert, cols.he_face) = (n, p, v, f);
        drop(cidx);
        cols.pos = midpoints(m)?;
        return Mesh::from_columns(cols);
    }
    // An input given up (the previous level of a multi-level call): each
    // output column comes after the input columns only it needed have gone:
    // positions first (then the input's positions go), faces (then its
    // faces and vertices), next and prev (then its connectivity), the
    // vertex column last, from the ranks and the output's own next. Peak at
    // a level: 105 B per output face instead of the one pass's 125, on
    // triangle and quad inputs (`examples/peak_levels.rs`).
    cols.pos = midpoints(&src)?;
    let Cow::Owned(mut m) = src else { unreachable!() };
    m.pos = Vec::new();
    {
        let (next, vert, face) = (&m.he_next, &m.he_vert, &m.he_face);
        let c1 = scatter(&cidx, |h| [face_pair(face, vert, h, next[h] as usize)])?;
        let [f] = c1;
        cols.he_face = f;
    }
    (m.he_face, m.he_vert) = (Vec::new(), Vec::new());
    {
        let (next, prev) = (&m.he_next, &m.he_prev);
        let c2 = scatter(&cidx, |h| {
            let x = next[h] as usize;
            [next_pair(prev, h, x), prev_pair(prev, h, x)]
        })?;
        let [n, p] = c2;
        (cols.he_next, cols.he_prev) = (n, p);
    }
    drop(m);
    // vert[2c] = h / 2 (vert_pair's first) through the ranks; then
    // vert[2c + 1] = x / 2 is the entry of x's F-corner, the output's next of 2c
    let mut vcol: Vec<u32> = Vec::with_capacity(2 * nh);
    {
        let pv = SyncPtr(vcol.as_mut_ptr());
        cidx.par_iter().with_min_len(MIN_LEN).enumerate().for_each(|(h, &c)| {
            if crate::cancel::requested() {
                return;
            }
            // SAFETY: the ranks are a bijection onto 0..H; one task per slot
            unsafe { *pv.get().add(2 * c as usize) = (h >> 1) as u32 };
        });
        drop(cidx);
        // every even slot is written unless cancelled (then no odd slot is read)
        crate::cancel::check()?;
        let on = &cols.he_next;
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|c| {
            if crate::cancel::requested() {
                return;
            }
            // SAFETY: reads even slots (2 · a rank, all written above), writes odd ones, one task each
            unsafe { *pv.get().add(2 * c + 1) = *pv.get().add(on[2 * c] as usize) };
        });
        crate::cancel::check()?;
    }
    // SAFETY: both passes ran in full (not cancelled): every slot is written
    unsafe { vcol.set_len(2 * nh) };
    cols.he_vert = vcol;
    Mesh::from_columns(cols)
}

/// K columns of 2H entries with `pair(h)[k]` at `2c` and `2c + 1` of
/// column k, c = `cidx[h]`, for every half-edge h, written in parallel
/// into memory never zeroed first (`calloc` on reused heap memory clears
/// it with a `memset` that faults the pages in before the writes: about a
/// sixth of a warm torus level-2 call under `perf`).
fn scatter<const K: usize>(cidx: &[u32], pair: impl Fn(usize) -> [(u32, u32); K] + Sync) -> Result<[Vec<u32>; K]> {
    let n = 2 * cidx.len();
    let mut cols: [Vec<u32>; K] = std::array::from_fn(|_| Vec::with_capacity(n));
    let ptrs: [SyncPtr<u32>; K] = std::array::from_fn(|k| SyncPtr(cols[k].as_mut_ptr()));
    let ptrs = &ptrs;
    (0..cidx.len()).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let i = 2 * cidx[h] as usize;
        for (p, (a, b)) in ptrs.iter().zip(pair(h)) {
            // SAFETY: the ranks are a bijection onto 0..H (a walk of every
            // face cycle), so each pair (2c, 2c + 1) is written by one task,
            // inside the capacity
            unsafe {
                *p.get().add(i) = a;
                *p.get().add(i + 1) = b;
            }
        }
    });
    crate::cancel::check()?;
    for c in &mut cols {
        // SAFETY: not cancelled, so every task ran and every slot is written
        unsafe { c.set_len(n) };
    }
    Ok(cols)
}

/// Output vertex e: the midpoint of edge e (reads the positions and the
/// vertex column only).
fn midpoints(m: &Mesh) -> Result<Vec<DVec3>> {
    let (p, vert) = (&m.pos, &m.he_vert);
    let pos = (0..vert.len() / 2).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        // cancelled: zeros, the check below reports it
        if crate::cancel::requested() {
            DVec3::ZERO
        } else {
            (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5
        }
    }).collect();
    crate::cancel::check()?;
    Ok(pos)
}

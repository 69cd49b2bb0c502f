//! The open √3 levels' half-edge columns written straight from their corner
//! groups (issue 19: no corner or twin lists).
//!
//! Each input half-edge owns consecutive output corners: a real one the
//! three of its triangle, a hole one one (odd step) or three (even step)
//! corners of its hole's face. [`Group`] gives their vertices and twin
//! corners by the steps' closed forms ([`super::boundary`]). The corners are
//! numbered as [`Mesh::from_trusted_twins`] numbers corner lists: an edge by
//! its first corner (the one before its twin), counted in corner order, so a
//! first corner `c` is half-edge `2 rank(c)` and its twin `2 rank(c) + 1`.
//! A bitmap of the first corners and a count per 64 of them give every rank
//! (each task sets a word's bits at once: corners follow the half-edges).
//! Each vertex leaves from its first corner in corner order, found by an
//! atomic minimum over the corners and walked to from its face's start.
//! The test `direct_columns_equal_the_list_build` holds the result to the
//! list build, element order included.

use super::boundary::Ctx;
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, NONE};
use crate::schemes::hosts::{SyncPtr, MIN_LEN};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering::Relaxed};

/// Half-edges per task of the first-corner pass.
const CHUNK: usize = 1 << 14;

/// The output corners of one input half-edge: `n` (1 or 3) consecutive
/// corners from `c`, with their vertices (zeros unless asked for: the
/// first-corner pass reads only the twins), twin corners and, for the
/// correspondence, each corner's edge origin and (real half-edges) its
/// triangle's face origin.
#[derive(Clone, Copy)]
pub(super) struct Group {
    pub c: u32,
    pub n: u32,
    pub cv: [u32; 3],
    pub tw: [u32; 3],
    pub origin: [(u8, u32); 3],
    pub face_origin: (u8, u32),
}

/// The columns (positions left to the caller) of the corners `group`
/// describes for every input half-edge; `per_hole` corners per hole side.
pub(super) fn columns(x: &Ctx, per_hole: u32, n_points: usize, group: impl Fn(usize, bool) -> Group + Sync) -> Result<Columns> {
    let m = x.m;
    let nh = m.n_halfedges();
    let n_tri = x.n_tri;
    let n_corners = 3 * n_tri + per_hole as usize * (nh - n_tri);
    let hole_faces: Vec<u32> = x.hole_faces().collect();
    let n_faces = n_tri + hole_faces.len();
    let bad = |what: &str| MeshError::Invariant(format!("sqrt3: {what}"));
    if n_corners > crate::mesh::MAX_ELEMENTS || n_points > crate::mesh::MAX_ELEMENTS {
        return Err(bad("too many elements for 31-bit ids"));
    }
    // the first corners (twin after them)
    let words = n_corners.div_ceil(64);
    let first: Vec<AtomicU64> = (0..words).map(|_| AtomicU64::new(0)).collect();
    let wrong = AtomicBool::new(false);
    // chunks of half-edges in order: a real one's corners follow the last
    // real one's, so a chunk gathers a word's bits and sets them at once
    (0..nh.div_ceil(CHUNK)).into_par_iter().for_each(|k| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let (mut word, mut bits) = (usize::MAX, 0u64);
        for h in k * CHUNK..((k + 1) * CHUNK).min(nh) {
            let g = group(h, false);
            for i in 0..g.n as usize {
                let (c, t) = (g.c as usize + i, g.tw[i] as usize);
                if t >= n_corners || t == c {
                    wrong.store(true, Relaxed);
                } else if t > c {
                    if c / 64 != word {
                        if bits != 0 {
                            first[word].fetch_or(bits, Relaxed);
                        }
                        (word, bits) = (c / 64, 0);
                    }
                    bits |= 1 << (c % 64);
                }
            }
        }
        if bits != 0 {
            first[word].fetch_or(bits, Relaxed);
        }
    });
    crate::cancel::check()?;
    if wrong.load(Relaxed) {
        return Err(bad("a corner's twin is out of range"));
    }
    let first: Vec<u64> = first.into_iter().map(AtomicU64::into_inner).collect();
    let mut rank = Vec::with_capacity(words);
    let mut acc = 0u32;
    for w in &first {
        rank.push(acc);
        acc += w.count_ones();
    }
    if 2 * acc as usize != n_corners {
        return Err(bad("the corners do not pair up"));
    }
    let is_first = |c: usize| first[c / 64] >> (c % 64) & 1 == 1;
    let rank_of = |c: usize| rank[c / 64] + (first[c / 64] & ((1u64 << (c % 64)) - 1)).count_ones();
    // a second corner's twin must be a first one, or two corners would share an id
    let id = |c: usize, t: usize| {
        if t > c {
            2 * rank_of(c)
        } else {
            if !is_first(t) {
                wrong.store(true, Relaxed);
            }
            2 * rank_of(t) + 1
        }
    };
    let mut cols = Columns::for_points(n_points, n_corners, n_faces);
    cols.f_hole[n_tri..].fill(true);
    cols.v_out.fill(NONE);
    {
        // SAFETY: AtomicU32 has u32's layout; the column is not otherwise used in this block
        let vmin: &[AtomicU32] = unsafe { &*(cols.v_out.as_mut_slice() as *mut [u32] as *const [AtomicU32]) };
        let sp = |v: &mut Vec<u32>| SyncPtr(v.as_mut_ptr());
        let (pn, pp, pv, pf, ps) = (sp(&mut cols.he_next), sp(&mut cols.he_prev), sp(&mut cols.he_vert), sp(&mut cols.he_face), sp(&mut cols.f_start));
        // SAFETY (both loops): the ids are a bijection from the corners onto
        // 0..n_corners when the groups' twins pair the corners (the steps'
        // closed forms, held to the list build by the tests), so each
        // half-edge and face is written by one task. Half of the corners are
        // first ones (checked above) and every second one's twin must be a
        // first one (checked as the ids are made); a pairing bug beyond that
        // would leave an id unwritten, which debug builds' validation reports,
        // as it did for the corner lists this replaces.
        let write = |ids: &[u32], verts: &[u32], corners: &[u32], f: usize| unsafe {
            *ps.get().add(f) = ids[0];
            for k in 0..ids.len() {
                // (no modulo: a division per corner cost more than the writes)
                let (a, b) = (ids[k], ids[if k + 1 == ids.len() { 0 } else { k + 1 }]);
                *pn.get().add(a as usize) = b;
                *pp.get().add(b as usize) = a;
                *pv.get().add(a as usize) = verts[k];
                *pf.get().add(a as usize) = f as u32;
                // the minimum only falls: a corner above it needs no atomic
                let v = &vmin[verts[k] as usize];
                if v.load(Relaxed) > corners[k] {
                    v.fetch_min(corners[k], Relaxed);
                }
            }
        };
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|h| {
            if crate::cancel::requested() || x.tri(h as u32) == NONE {
                return; // cancelled: the check after the loop; hole sides: below
            }
            let g = group(h, true);
            if g.cv.iter().any(|&v| v as usize >= n_points) {
                wrong.store(true, Relaxed);
                return;
            }
            let ids: [u32; 3] = std::array::from_fn(|i| id(g.c as usize + i, g.tw[i] as usize));
            write(&ids, &g.cv, &[g.c, g.c + 1, g.c + 2], x.tri(h as u32) as usize);
        });
        crate::cancel::check()?;
        if wrong.load(Relaxed) {
            return Err(bad("a corner's vertex is out of range, or two corners have the same twin"));
        }
        // the holes' faces, each side's corners in cycle order
        let (mut ids, mut verts, mut corners) = (Vec::new(), Vec::new(), Vec::new());
        for (j, &f) in hole_faces.iter().enumerate() {
            crate::cancel::poll(j)?;
            (ids.clear(), verts.clear(), corners.clear());
            let s = m.f_start[f as usize];
            let mut h = s;
            loop {
                let g = group(h as usize, true);
                if g.cv[..g.n as usize].iter().any(|&v| v as usize >= n_points) {
                    return Err(bad("a corner's vertex is out of range"));
                }
                for i in 0..g.n as usize {
                    ids.push(id(g.c as usize + i, g.tw[i] as usize));
                    verts.push(g.cv[i]);
                    corners.push(g.c + i as u32);
                }
                h = m.he_next[h as usize];
                if h == s {
                    break;
                }
            }
            write(&ids, &verts, &corners, n_tri + j);
        }
        if wrong.load(Relaxed) {
            return Err(bad("two corners have the same twin"));
        }
    }
    // every vertex's first corner, as `from_trusted_twins` picks it: its
    // rank when it is a first corner, else walked to from its face's first
    // corner (triangles 3t..3t + 2, then the holes in face order)
    let hole_first: Vec<u32> = hole_faces.iter().map(|&f| group(m.f_start[f as usize] as usize, false).c).collect();
    let Columns { v_out, he_next, f_start, .. } = &mut cols;
    let unused = AtomicU32::new(NONE);
    v_out.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
        let c = *o;
        if c == NONE {
            unused.fetch_min(v as u32, Relaxed);
            return;
        }
        if is_first(c as usize) {
            *o = 2 * rank_of(c as usize);
            return;
        }
        // a second corner: its id is its face's k-th half-edge
        let (f, k) = if (c as usize) < 3 * n_tri {
            (c as usize / 3, c % 3)
        } else {
            let j = hole_first.partition_point(|&s| s <= c) - 1;
            (n_tri + j, c - hole_first[j])
        };
        let mut e = f_start[f];
        for _ in 0..k {
            e = he_next[e as usize];
        }
        *o = e;
    });
    let v = unused.into_inner();
    if v != NONE {
        return Err(MeshError::InvalidArgument(format!("vertex {v} is not used by any face")));
    }
    Ok(cols)
}

/// The corner and twin lists of the same groups, for the list build the
/// direct columns are tested against.
#[cfg(test)]
pub(super) fn lists(x: &Ctx, per_hole: u32, group: impl Fn(usize, bool) -> Group) -> (Vec<u32>, Vec<u32>) {
    let nh = x.m.n_halfedges();
    let n_corners = 3 * x.n_tri + per_hole as usize * (nh - x.n_tri);
    let (mut cv, mut tw) = (vec![0u32; n_corners], vec![0u32; n_corners]);
    for h in 0..nh {
        let g = group(h, true);
        for i in 0..g.n as usize {
            cv[g.c as usize + i] = g.cv[i];
            tw[g.c as usize + i] = g.tw[i];
        }
    }
    (cv, tw)
}

//! The direct constructor: columns filled by the caller (a scheme's index
//! arithmetic), taken as they are after a proportional, parallel check.
//!
//! [`Mesh::from_corner_twins`] pairs corners, numbers half-edges and picks
//! every vertex's first corner; a scheme that knows its output's structure
//! can compute all of that in closed form and write the columns at once
//! (issue 19: the builder was most of a large level). The mesh module stays
//! scheme-agnostic: it hands out exactly-sized columns ([`Columns`]) and
//! checks what it gets back.

use super::{Mesh, NONE, POINT};
use crate::error::{MeshError, Result};
use glam::DVec3;
use rayon::prelude::*;

/// The columns of a mesh under construction, exactly sized, with every
/// entry still to be written by the caller (see [`Mesh`] for their meaning).
pub struct Columns {
    pub pos: Vec<DVec3>,
    pub v_out: Vec<u32>,
    pub he_next: Vec<u32>,
    pub he_prev: Vec<u32>,
    pub he_vert: Vec<u32>,
    pub he_face: Vec<u32>,
    pub f_start: Vec<u32>,
    pub f_hole: Vec<bool>,
}

impl Columns {
    /// Columns for `n_halfedges` half-edges and `n_faces` faces around the
    /// given positions. The integer columns are zeroed (calloc'd, so their
    /// pages are first touched by the caller's parallel fill, not here).
    pub fn new(pos: Vec<DVec3>, n_halfedges: usize, n_faces: usize) -> Columns {
        let nv = pos.len();
        let mut c = Columns {
            pos,
            v_out: vec![0; nv],
            he_next: vec![0; n_halfedges],
            he_prev: vec![0; n_halfedges],
            he_vert: vec![0; n_halfedges],
            he_face: vec![0; n_halfedges],
            f_start: vec![0; n_faces],
            f_hole: vec![false; n_faces],
        };
        c.populate();
        c
    }

    /// [`super::populate`] on every column but the positions (the caller's).
    fn populate(&mut self) {
        // each column's whole allocation: exactly its size
        for col in [&mut self.he_next, &mut self.he_prev, &mut self.he_vert, &mut self.he_face, &mut self.v_out, &mut self.f_start] {
            super::populate(col, usize::MAX);
        }
        super::populate(&mut self.f_hole, usize::MAX);
    }

    /// [`Columns::new`] for `n_points` vertices whose positions the caller
    /// sets later (`pos` left empty, nothing allocated for it): builders
    /// that compute positions after freeing their temporaries.
    pub fn for_points(n_points: usize, n_halfedges: usize, n_faces: usize) -> Columns {
        let mut c = Columns::new(Vec::new(), n_halfedges, n_faces);
        c.v_out = vec![0; n_points];
        super::populate(&mut c.v_out, n_points);
        c
    }

    /// [`Columns::new`] with the four half-edge columns allocated but not
    /// written: empty, with room for `n_halfedges` entries each, which the
    /// caller writes through their pointers (`as_mut_ptr`) and then declares
    /// written ([`Columns::assume_filled`]). `vec![0; n]` is a `calloc`,
    /// which on heap memory glibc reuses (every warm call) clears with a
    /// `memset` on the calling thread: a serial pass over the level's largest
    /// columns that also takes the page faults the parallel fill would have
    /// shared (issue 19: Catmull-Clark's level 2 on two threads 112–121 →
    /// 99–107 ms). Debug builds fill the room with `u32::MAX`, so an entry
    /// the caller never writes fails [`Mesh::from_columns`]'s range check.
    pub fn unfilled(pos: Vec<DVec3>, n_halfedges: usize, n_faces: usize) -> Columns {
        let room = || {
            let mut v: Vec<u32> = Vec::with_capacity(n_halfedges);
            if cfg!(debug_assertions) {
                v.spare_capacity_mut()[..n_halfedges].fill(std::mem::MaybeUninit::new(u32::MAX));
            }
            v
        };
        let nv = pos.len();
        let mut c = Columns { pos, v_out: vec![0; nv], he_next: room(), he_prev: room(), he_vert: room(), he_face: room(), f_start: vec![0; n_faces], f_hole: vec![false; n_faces] };
        c.populate();
        c
    }

    /// [`Columns::unfilled`] for `n_points` vertices whose positions the
    /// caller sets later (as [`Columns::for_points`]).
    pub fn for_points_unfilled(n_points: usize, n_halfedges: usize, n_faces: usize) -> Columns {
        let mut c = Columns::unfilled(Vec::new(), n_halfedges, n_faces);
        c.v_out = vec![0; n_points];
        super::populate(&mut c.v_out, n_points);
        c
    }

    /// Declares the `n_halfedges` entries of the four half-edge columns of
    /// [`Columns::unfilled`] written.
    ///
    /// # Safety
    /// Every entry `0..n_halfedges` of `he_next`, `he_prev`, `he_vert` and
    /// `he_face` was written through the columns' pointers (a fill that
    /// was cancelled part way must return before this: its check after the
    /// loops sees the flag, which is never cleared while a call runs,
    /// [`crate::cancel::reset`]).
    pub unsafe fn assume_filled(&mut self, n_halfedges: usize) {
        for c in [&mut self.he_next, &mut self.he_prev, &mut self.he_vert, &mut self.he_face] {
            assert!(c.is_empty() && n_halfedges <= c.capacity(), "assume_filled: columns of Columns::unfilled for {n_halfedges} half-edges");
            // SAFETY: within the capacity, and written (the caller's contract)
            unsafe { c.set_len(n_halfedges) };
        }
    }
}

/// `n` points at the origin from zeroed (calloc) memory: a fresh block's
/// pages are mapped zero, so unlike `vec![DVec3::ZERO; n]` nothing writes
/// the whole block before the caller's fill (issue 19: one pass less over
/// a level's largest column; the fill then takes the page faults). That
/// pass was also a sequential write no poll could interrupt: on memory the
/// machine had not touched yet it took 2-4 s for a 0.75 GB column, which
/// was Ctrl-C's latency.
pub fn zeroed_points(n: usize) -> Vec<DVec3> {
    let mut v = std::mem::ManuallyDrop::new(vec![0.0f64; 3 * n]);
    let (ptr, len, cap) = (v.as_mut_ptr(), v.len(), v.capacity());
    assert_eq!(len, cap, "vec! allocates exactly");
    // SAFETY: DVec3 is three f64 (size 24, align 8, no padding), so 3n
    // zeroed f64 are n valid points with the same size and alignment, and
    // the allocation's layout (3n f64) equals that of n DVec3.
    const _: () = assert!(std::mem::size_of::<DVec3>() == 24 && std::mem::align_of::<DVec3>() == 8);
    let mut v = unsafe { Vec::from_raw_parts(ptr as *mut DVec3, len / 3, cap / 3) };
    super::populate(&mut v, n);
    v
}

/// Room for `n` points that the caller writes in full (through
/// `spare_capacity_mut`) before declaring them written with `set_len`: no
/// `calloc`, whose `memset` of reused heap memory runs on one thread
/// ([`Columns::unfilled`]). Debug builds fill the room with NaN, so a point
/// never written shows in the tests' position comparisons.
pub fn unfilled_points(n: usize) -> Vec<DVec3> {
    let mut v = Vec::with_capacity(n);
    if cfg!(debug_assertions) {
        v.spare_capacity_mut()[..n].fill(std::mem::MaybeUninit::new(DVec3::NAN));
    }
    super::populate(&mut v, n);
    v
}

/// The points of `room`, once every one is written.
///
/// # Safety
/// Every element of `room` was written.
pub unsafe fn written(room: &[std::mem::MaybeUninit<DVec3>]) -> &[DVec3] {
    // SAFETY: MaybeUninit<T> has T's layout, and the elements are
    // initialized (the caller's contract)
    unsafe { &*(room as *const [std::mem::MaybeUninit<DVec3>] as *const [DVec3]) }
}

/// Elements per task of the range check.
const CHUNK: usize = 1 << 15;

/// Whether every entry of `col` is below `bound` (point-sphere links, which
/// carry [`POINT`], are allowed where `point_below` is given), in parallel.
fn in_range(col: &[u32], bound: usize, point_below: Option<usize>) -> bool {
    col.par_chunks(CHUNK).all(|ch| match point_below {
        // branch-free folds vectorize; the point case is rare
        None => (ch.iter().fold(0u32, |a, &x| a.max(x)) as usize) < bound,
        Some(pb) => ch.iter().all(|&x| if x & POINT != 0 { ((x & !POINT) as usize) < pb } else { (x as usize) < bound }),
    }) || col.is_empty()
}

impl Mesh {
    /// Takes columns a scheme filled by index arithmetic. Checked here, in
    /// time proportional to the size and in parallel: column lengths, an
    /// even number of half-edges, and every reference in range (so no later
    /// lookup can fail); debug builds run the full [`Mesh::validate`].
    /// Everything else (the invariants I2–I9) is the caller's contract,
    /// which its tests check with `validate`.
    pub fn from_columns(c: Columns) -> Result<Mesh> {
        let (nv, nh, nf) = (c.pos.len(), c.he_next.len(), c.f_start.len());
        let bad = |what: &str| Err(MeshError::Invariant(format!("direct build: {what}")));
        if c.v_out.len() != nv || c.he_prev.len() != nh || c.he_vert.len() != nh || c.he_face.len() != nh || c.f_hole.len() != nf || nh % 2 != 0 {
            return bad("column lengths disagree");
        }
        if nv > super::MAX_ELEMENTS || nh > super::MAX_ELEMENTS || nf > super::MAX_ELEMENTS {
            return bad("too many elements for 31-bit ids");
        }
        let ok = || {
            let (a, b) = rayon::join(|| in_range(&c.he_next, nh, None) && in_range(&c.he_prev, nh, None), || in_range(&c.he_vert, nv, None) && in_range(&c.he_face, nf, None));
            let (d, e) = rayon::join(|| in_range(&c.v_out, nh, Some(nf)), || in_range(&c.f_start, nh, Some(nv)));
            a && b && d && e
        };
        if !ok() {
            return bad("a reference is out of range");
        }
        debug_assert!(!c.v_out.contains(&NONE));
        let m = Mesh {
            pos: c.pos,
            v_out: c.v_out,
            he_next: c.he_next,
            he_prev: c.he_prev,
            he_vert: c.he_vert,
            he_face: c.he_face,
            f_start: c.f_start,
            f_hole: c.f_hole,
        };
        #[cfg(debug_assertions)]
        m.validate()?;
        Ok(m)
    }

    /// A mesh from faces listed as corners (`sizes`, the tail vertex `cv` of
    /// every corner) and the half-edge `ids` the caller numbered them with in
    /// closed form (a bijection onto `0..cv.len()`, twins `2e` and `2e + 1`):
    /// the columns are filled face by face in parallel, each vertex's `v_out`
    /// is its first corner, `holes` marks faces. What
    /// [`Mesh::from_corner_twins`] gives for the same corners when `ids` are
    /// its numbering (edges by first corner), without pairing, numbering or
    /// checking twins; no point-spheres. Checked as [`Mesh::from_columns`].
    pub fn from_corner_ids(pos: Vec<DVec3>, sizes: &[u32], cv: &[u32], ids: &[u32], holes: Vec<bool>) -> Result<Mesh> {
        let mut c = Columns::new(pos, cv.len(), sizes.len());
        fill_corner_ids(&mut c, sizes, cv, ids, holes)?;
        Mesh::from_columns(c)
    }

    /// A mesh from faces listed as corners (`sizes`, tail vertices `cv`)
    /// whose `twins` the caller made in closed form, so they are trusted
    /// (not paired nor checked, as [`Mesh::from_corner_ids`]): numbered here
    /// as [`Mesh::from_corner_twins`] numbers them (edges by first corner),
    /// in place of the twins. The lists are freed before `points` computes
    /// the `n_points` positions (issue 19: an open level's peak holds the
    /// output's columns and the lists, or the columns and the positions,
    /// never all three), with whatever else it makes on the way (a level's
    /// stencils), handed back beside the mesh. `holes` marks faces; no
    /// point-spheres.
    pub(crate) fn from_trusted_twins<T>(
        n_points: usize,
        sizes: Vec<u32>,
        cv: Vec<u32>,
        mut twins: Vec<u32>,
        holes: Vec<bool>,
        points: impl FnOnce() -> Result<(Vec<DVec3>, T)>,
    ) -> Result<(Mesh, T)> {
        number_in_place(&mut twins)?;
        let mut c = Columns::new(Vec::new(), cv.len(), sizes.len());
        c.v_out = vec![0; n_points];
        fill_corner_ids(&mut c, &sizes, &cv, &twins, holes)?;
        drop((sizes, cv, twins));
        let extra;
        (c.pos, extra) = points()?;
        if c.pos.len() != n_points {
            return Err(MeshError::Invariant(format!("direct build: {} points for {n_points} vertices", c.pos.len())));
        }
        Ok((Mesh::from_columns(c)?, extra))
    }

    /// Gives the columns back for reuse (e.g. as the next level's scratch).
    pub fn into_columns(self) -> Columns {
        Columns {
            pos: self.pos,
            v_out: self.v_out,
            he_next: self.he_next,
            he_prev: self.he_prev,
            he_vert: self.he_vert,
            he_face: self.he_face,
            f_start: self.f_start,
            f_hole: self.f_hole,
        }
    }
}

/// The columns of [`Mesh::from_corner_ids`] (its checks included), into
/// `c`, whose `v_out` holds one entry per vertex.
fn fill_corner_ids(c: &mut Columns, sizes: &[u32], cv: &[u32], ids: &[u32], holes: Vec<bool>) -> Result<()> {
    let (nc, nf, nv) = (cv.len(), sizes.len(), c.v_out.len());
    let bad = |what: &str| Err(MeshError::Invariant(format!("direct build: {what}")));
    if ids.len() != nc || holes.len() != nf || nc % 2 != 0 || nc > super::MAX_ELEMENTS || nf > super::MAX_ELEMENTS {
        return bad("corner, id and face counts disagree");
    }
    let mut off = Vec::with_capacity(nf + 1);
    let mut acc = 0usize;
    off.push(0u32);
    for &k in sizes {
        acc += k as usize;
        if k == 0 || acc > nc {
            return bad("face sizes do not cover the corners");
        }
        off.push(acc as u32);
    }
    if acc != nc || !in_range(ids, nc, None) || !in_range(cv, nv, None) {
        return bad("a corner's id or vertex is out of range");
    }
    c.f_hole = holes;
    {
        let sp = |v: &mut Vec<u32>| crate::schemes::hosts::SyncPtr(v.as_mut_ptr());
        let (pn, pp, pv, pf, ps) = (sp(&mut c.he_next), sp(&mut c.he_prev), sp(&mut c.he_vert), sp(&mut c.he_face), sp(&mut c.f_start));
        (0..nf).into_par_iter().with_min_len(1024).for_each(|f| {
            let (a, b) = (off[f] as usize, off[f + 1] as usize);
            // SAFETY: `ids` is a bijection (the caller's contract; a
            // duplicate would leave another id unwritten, which the
            // debug validation reports), so every half-edge and face is
            // written by one task.
            unsafe {
                *ps.get().add(f) = ids[a];
                for k in a..b {
                    let (i, n) = (ids[k], ids[if k + 1 == b { a } else { k + 1 }]);
                    *pn.get().add(i as usize) = n;
                    *pp.get().add(n as usize) = i;
                    *pv.get().add(i as usize) = cv[k];
                    *pf.get().add(i as usize) = f as u32;
                }
            }
        });
    }
    // every vertex's first corner, as `from_corner_twins` picks it
    let mut seen = vec![false; nv];
    for (k, &v) in cv.iter().enumerate() {
        if !seen[v as usize] {
            seen[v as usize] = true;
            c.v_out[v as usize] = ids[k];
        }
    }
    if let Some(v) = seen.iter().position(|&s| !s) {
        return Err(MeshError::InvalidArgument(format!("vertex {v} is not used by any face")));
    }
    Ok(())
}

/// [`super::build::number_halfedges`] written over the twins themselves:
/// each corner's twin index becomes its half-edge id (a bitmap of the
/// first corners, 1 bit per corner, instead of two id lists of 4 bytes).
/// Twins must all be set (no point-sphere corners). Cancellable.
pub(crate) fn number_in_place(twin: &mut [u32]) -> Result<()> {
    const CHUNK: usize = 1 << 14; // a multiple of 64: chunks own whole words
    let n = twin.len();
    if twin.contains(&NONE) {
        return Err(MeshError::Invariant("direct build: a corner has no twin".into()));
    }
    let is_first = |c: usize| twin[c] as usize > c;
    let mut first = vec![0u64; n.div_ceil(64)];
    first.par_iter_mut().with_min_len(256).enumerate().for_each(|(w, bits)| {
        for i in 0..64.min(n - 64 * w) {
            *bits |= (is_first(64 * w + i) as u64) << i;
        }
    });
    let bit = |c: usize| first[c / 64] >> (c % 64) & 1 == 1;
    let words = CHUNK / 64;
    let mut base: Vec<u32> = first.chunks(words).map(|w| w.iter().map(|x| x.count_ones()).sum()).collect();
    let mut acc = 0u32;
    for b in base.iter_mut() {
        (*b, acc) = (acc, acc + *b);
    }
    // firsts: 2e, counted in corner order
    twin.par_chunks_mut(CHUNK).enumerate().for_each(|(k, chunk)| {
        if crate::cancel::requested() {
            return; // the check below reports it
        }
        let mut e = base[k];
        for (i, s) in chunk.iter_mut().enumerate() {
            if bit(k * CHUNK + i) {
                *s = 2 * e;
                e += 1;
            }
        }
    });
    crate::cancel::check()?;
    // seconds: their twin's id + 1 (twins are firsts, not written here)
    let p = crate::schemes::hosts::SyncPtr(twin.as_mut_ptr());
    (0..n).into_par_iter().with_min_len(CHUNK).for_each(|c| {
        if !bit(c) {
            // SAFETY: slot c (a second) is written by this task only; slot
            // t (a first) is only read in this pass
            unsafe {
                let t = *p.get().add(c) as usize;
                *p.get().add(c) = *p.get().add(t) + 1;
            }
        }
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;

    /// The in-place numbering gives the two-list numbering's ids, on random
    /// pairings across chunk and word boundaries.
    #[test]
    fn numbering_in_place_equals_the_scan() {
        let mut rng = crate::test_rng::Xorshift::new(11);
        for n in [2usize, 64, 130, 40_002] {
            let mut order: Vec<u32> = (0..n as u32).collect();
            for i in (1..n).rev() {
                order.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
            }
            let mut twin = vec![0u32; n];
            for p in order.chunks(2) {
                (twin[p[0] as usize], twin[p[1] as usize]) = (p[1], p[0]);
            }
            let (want, ne) = crate::mesh::build::number_halfedges(&twin).unwrap();
            number_in_place(&mut twin).unwrap();
            assert_eq!((twin, ne), (want, n / 2), "{n}");
        }
        let mut lone = vec![1, 0, NONE];
        assert!(number_in_place(&mut lone).is_err());
    }

    #[test]
    fn columns_round_trip_and_bad_references_are_refused() {
        let m = primitives::cube();
        let back = Mesh::from_columns(m.clone().into_columns()).unwrap();
        assert_eq!(back, m);
        let mut c = m.clone().into_columns();
        c.he_next[3] = c.he_next.len() as u32;
        assert!(Mesh::from_columns(c).unwrap_err().to_string().contains("out of range"));
        let mut c = m.clone().into_columns();
        c.he_face.pop();
        assert!(Mesh::from_columns(c).unwrap_err().to_string().contains("lengths"));
        assert_eq!(Mesh::from_columns(Mesh::new().into_columns()).unwrap(), Mesh::new());
    }

    /// Unfilled columns written through their pointers give the mesh; an
    /// entry left unwritten is refused in debug builds (the poison), which
    /// is what lets the schemes' tests catch a fill that misses one.
    #[test]
    fn unfilled_columns_take_their_writes() {
        let m = primitives::cube();
        let full = m.clone().into_columns();
        let nh = full.he_next.len();
        let fill = |skip: Option<usize>| {
            let mut c = Columns::unfilled(full.pos.clone(), nh, full.f_start.len());
            c.v_out.copy_from_slice(&full.v_out);
            c.f_start.copy_from_slice(&full.f_start);
            for (dst, src) in [(&mut c.he_next, &full.he_next), (&mut c.he_prev, &full.he_prev), (&mut c.he_vert, &full.he_vert), (&mut c.he_face, &full.he_face)] {
                let p = dst.as_mut_ptr();
                for (i, &x) in src.iter().enumerate() {
                    if Some(i) != skip {
                        // SAFETY: within the room of `unfilled`
                        unsafe { *p.add(i) = x };
                    }
                }
            }
            // SAFETY: every entry written, or (skip) the debug poison read
            unsafe { c.assume_filled(nh) };
            Mesh::from_columns(c)
        };
        assert_eq!(fill(None).unwrap(), m);
        if cfg!(debug_assertions) {
            assert!(fill(Some(5)).unwrap_err().to_string().contains("out of range"));
        }
    }

    /// The cube from its exported corners and the half-edge ids of its own
    /// corners: the same mesh; bad ids, sizes and unused vertices are refused.
    #[test]
    fn corner_ids_rebuild_and_refuse() {
        let m = primitives::cube();
        let p = m.to_polygons();
        let ids: Vec<u32> = m.faces().flat_map(|f| m.face_halfedges(f).map(|h| h.0).collect::<Vec<_>>()).collect();
        let holes = vec![false; p.sizes.len()];
        let back = Mesh::from_corner_ids(m.pos.clone(), &p.sizes, &p.indices, &ids, holes.clone()).unwrap();
        assert_eq!(back, m);
        let mut bad = ids.clone();
        bad[0] = 99;
        assert!(Mesh::from_corner_ids(m.pos.clone(), &p.sizes, &p.indices, &bad, holes.clone()).is_err());
        assert!(Mesh::from_corner_ids(m.pos.clone(), &p.sizes[1..], &p.indices, &ids, holes[1..].to_vec()).is_err());
        let mut pos = m.pos.clone();
        pos.push(DVec3::ZERO);
        assert!(Mesh::from_corner_ids(pos, &p.sizes, &p.indices, &ids, holes).unwrap_err().to_string().contains("not used"));
    }
}

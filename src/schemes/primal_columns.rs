//! The primal host's output written straight into the mesh columns
//! ([`crate::mesh::Columns`]), by index arithmetic on the input (issue 19,
//! item 1), instead of listing corners and twins for
//! [`Mesh::from_corner_twins`].
//!
//! The result is the mesh `from_corner_twins` built, bit for bit: its
//! numbering is reproduced in closed form.
//! * **Corners.** Input face `f` owns the output corners `base[f]..`, one
//!   sub-block of `S` corners per input corner `h` (local index `k`), in the
//!   layout of [`super::hosts::primal_host`]: a face with a face point (`Q`,
//!   `S = 4`) `[v→e(h), e(h)→fp, fp→e(prev h), e(prev h)→v]`; a triangle
//!   without one (`T`, `S = 3`) `[v→e(h), e(h)→e(prev h), e(prev h)→v]` and
//!   then the middle triangle; a hole (`H`, `S = 2`) `[v→e(h), e(h)→v(next h)]`.
//!   The two *outer* corners along an input edge are `a(h)` (`v→e(h)`) and
//!   `b(h)` (`e(prev h)→v`, in `H` the second corner of the previous
//!   sub-block); `twin(a(h)) = b(next(twin h))`.
//! * **Half-edges.** `from_corner_twins` numbers edges by their first corner
//!   (the one whose twin comes later): corner `c` gets `2e` with `e` the
//!   number of first corners before it, its twin `2e + 1`. Pass 1 marks, per
//!   input corner, which of its sub-block's corners are first (an inner
//!   corner by its position, an outer one by comparing with its twin's
//!   position) and counts them; a prefix over faces gives every face's edge
//!   base, so every id is a lookup plus a popcount (a later corner's id is
//!   its twin's plus one, one hop away).
//! * **Vertices' corners.** `v_out` is the id of a vertex's first corner:
//!   for a vertex point the `a` corner of the outgoing half-edge that comes
//!   first in face order, for an edge point the lowest of its candidates,
//!   for a face point its face's third corner.

use super::hosts::{FaceLayout, SyncPtr, HOLE, MIN_LEN};
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, NONE};
use glam::DVec3;
use rayon::prelude::*;

const Q: u8 = 0;
const T: u8 = 1;
const H: u8 = 2;

/// Per input face: where its output starts (24 bytes: the face-point
/// entry doubles as the kind, so no padding).
#[derive(Clone, Copy, Default)]
struct FaceInfo {
    /// First input corner (FaceLayout index).
    off: u32,
    /// Degree.
    n: u32,
    /// First output corner.
    base: u32,
    /// First output face.
    fbase: u32,
    /// Number of output edges whose first corner lies before `base`.
    ebase: u32,
    /// The face's `face_point` entry: its point's index, [`NONE`] or [`HOLE`].
    fp: u32,
}

impl FaceInfo {
    #[inline]
    fn kind(&self) -> u8 {
        match self.fp {
            NONE => T,
            HOLE => H,
            _ => Q,
        }
    }
    /// Output corners and output faces of this face's block.
    #[inline]
    fn block(&self) -> (u32, u32) {
        match self.kind() {
            Q => (4 * self.n, self.n),
            T => (12, 4),
            _ => (2 * self.n, 1),
        }
    }
    #[inline]
    fn stride(&self) -> u32 {
        match self.kind() {
            Q => 4,
            T => 3,
            _ => 2,
        }
    }
    /// Offset in this face's block of the lower of the two output corners
    /// at the edge point of input corner `k`'s edge on this side: the inner
    /// corner after `a(h)` (slot 1, not in a hole) and `b(next h)`. Index
    /// arithmetic only (`next h` is corner `k + 1` of the same face).
    #[inline]
    fn edge_point_corner(&self, k: u32) -> u32 {
        let k1 = (k + 1) % self.n;
        match self.kind() {
            Q => (4 * k + 1).min(4 * k1 + 3),
            T => (3 * k + 1).min(3 * k1 + 2),
            // b(next h) is the second corner of h's own sub-block
            _ => 2 * k + 1,
        }
    }
}

/// Calls `f(k, h)` for the corners of the face whose first half-edge is
/// `s`, in cycle order (the order of [`FaceLayout::corners`], without its
/// corner list: the late build frees that list before the columns).
#[inline]
fn each_corner(next: &[u32], s: u32, mut f: impl FnMut(u32, u32)) {
    let (mut h, mut k) = (s, 0u32);
    loop {
        f(k, h);
        k += 1;
        h = next[h as usize];
        if h == s {
            break;
        }
    }
}

struct Ctx<'a> {
    prev: &'a [u32],
    face: &'a [u32],
    cidx: &'a [u32],
    fi: Vec<FaceInfo>,
    /// Per input corner: `rank << 4 | mask`, the number of first corners of
    /// its face's block before its sub-block, and which of the sub-block's
    /// corners are first.
    rm: Vec<u32>,
}

impl Ctx<'_> {
    /// Face info and local index of input half-edge `h`.
    #[inline]
    fn loc(&self, h: u32) -> (&FaceInfo, u32, u32) {
        let c = self.cidx[h as usize];
        let fi = &self.fi[self.face[h as usize] as usize];
        (fi, c - fi.off, c)
    }
    /// Output corner index of `a(h)`.
    #[inline]
    fn pos_a(&self, h: u32) -> u32 {
        let (fi, k, _) = self.loc(h);
        fi.base + fi.stride() * k
    }
    /// [`Self::loc`] of `next[t]`, by index arithmetic on `t`'s own: the
    /// face's next corner. One dependent load fewer than through `next`,
    /// and `t`'s entries share a cache line with its twin's, which the
    /// callers (`t = h ^ 1`) have usually just read.
    #[inline]
    fn loc_next(&self, t: u32) -> (&FaceInfo, u32, u32) {
        let (fi, k, _) = self.loc(t);
        let k1 = if k + 1 == fi.n { 0 } else { k + 1 };
        (fi, k1, fi.off + k1)
    }
    /// Output corner index of `b(h)`, from [`Self::loc`] of `h`.
    #[inline]
    fn pos_b(&self, (fi, k, _): (&FaceInfo, u32, u32)) -> u32 {
        match fi.kind() {
            Q => fi.base + 4 * k + 3,
            T => fi.base + 3 * k + 2,
            _ => fi.base + 2 * ((k + fi.n - 1) % fi.n) + 1,
        }
    }
    /// Id of the first corner at `slot` of input corner `c`'s sub-block.
    #[inline]
    fn first_id(&self, fi: &FaceInfo, c: u32, slot: u32) -> u32 {
        let rm = self.rm[c as usize];
        2 * (fi.ebase + (rm >> 4) + (rm & 15 & ((1 << slot) - 1)).count_ones())
    }
    #[inline]
    fn is_first(&self, c: u32, slot: u32) -> bool {
        self.rm[c as usize] >> slot & 1 != 0
    }
    /// Id of `a(h)` when it is the first corner of its edge.
    #[inline]
    fn first_a(&self, h: u32) -> u32 {
        let (fi, _, c) = self.loc(h);
        self.first_id(fi, c, 0)
    }
    /// Sub-block (input corner) and slot of `b(h)`.
    #[inline]
    fn slot_b(fi: &FaceInfo, k: u32, c: u32) -> (u32, u32) {
        match fi.kind() {
            Q => (c, 3),
            T => (c, 2),
            _ => (fi.off + (k + fi.n - 1) % fi.n, 1),
        }
    }
    /// Id of `b(h)` when it is the first corner of its edge, from
    /// [`Self::loc`] of `h`.
    #[inline]
    fn first_b(&self, (fi, k, c): (&FaceInfo, u32, u32)) -> u32 {
        let (c, s) = Self::slot_b(fi, k, c);
        self.first_id(fi, c, s)
    }
    #[inline]
    fn id_a(&self, h: u32) -> u32 {
        let (fi, _, c) = self.loc(h);
        if self.is_first(c, 0) {
            self.first_id(fi, c, 0)
        } else {
            self.first_b(self.loc_next(h ^ 1)) + 1
        }
    }
    #[inline]
    fn id_b(&self, h: u32) -> u32 {
        let (fi, k, c) = self.loc(h);
        let (c, s) = Self::slot_b(fi, k, c);
        if self.is_first(c, s) {
            self.first_id(fi, c, s)
        } else {
            self.first_a(self.prev[h as usize] ^ 1) + 1
        }
    }
}

/// [`super::hosts::primal_host_sides`] by direct column fills; same result.
/// Faces of 2²⁵ corners or more (whose ranks would not fit the packed
/// 28 bits) go through [`super::hosts::primal_host_twins`].
pub(crate) fn primal_columns(m: &Mesh, fl: &FaceLayout, face_point: &[u32], pos: Vec<DVec3>, want_sides: bool) -> Result<(Mesh, Option<Vec<u32>>)> {
    let n = pos.len();
    primal_columns_then(m, fl, face_point, n, want_sides, || Ok(pos))
}

/// [`primal_columns`] with the positions computed by `pos` (which must
/// return `n_points` points) after the connectivity, once the builder's
/// records and ranks are freed: they and the positions are never alive
/// together. The layout and face points are the caller's, so they stay.
pub(crate) fn primal_columns_then(
    m: &Mesh,
    fl: &FaceLayout,
    face_point: &[u32],
    n_points: usize,
    want_sides: bool,
    pos: impl FnOnce() -> Result<Vec<DVec3>>,
) -> Result<(Mesh, Option<Vec<u32>>)> {
    let (mut cols, sides) = if let Some(kind) = super::primal_uniform::applies(m, fl, face_point) {
        super::primal_uniform::fill(m, &fl.cidx, kind, n_points, want_sides)?
    } else {
        let Some(fi) = layout(fl, face_point)? else {
            return super::hosts::primal_host_twins(m, fl, face_point, pos()?, want_sides);
        };
        fill(m, &fl.cidx, fi, n_points, want_sides)?
    };
    cols.pos = points(pos, n_points)?;
    let out = Mesh::from_columns(cols)?;
    Ok((out, want_sides.then_some(sides)))
}

/// `pos()`, checked to hold `n` points.
fn points(pos: impl FnOnce() -> Result<Vec<DVec3>>, n: usize) -> Result<Vec<DVec3>> {
    let p = pos()?;
    if p.len() != n {
        return Err(MeshError::Invariant(format!("primal host: {} points for {n} output vertices", p.len())));
    }
    Ok(p)
}

/// [`primal_columns`] (the side map only when `want_sides`) with the
/// positions computed last, by
/// `pos` (which must return `n_points` points): the face layout, the face
/// points and the builder's records are freed before it runs, and the
/// layout's corner list and offsets before the columns are allocated
/// (issue 19: a level's peak is then the input, the output's connectivity
/// and its positions, without the temporaries; 141 → about 121 B per output
/// quad, 101 → about 84 B per output triangle, `examples/peak_levels.rs`).
/// The open and creased levels pass their layout here too. Same mesh as
/// [`primal_columns`].
pub(crate) fn primal_columns_late(
    m: &Mesh,
    fl: FaceLayout,
    face_point: Vec<u32>,
    n_points: usize,
    want_sides: bool,
    pos: impl FnOnce() -> Result<Vec<DVec3>>,
) -> Result<(Mesh, Option<Vec<u32>>)> {
    if let Some(kind) = super::primal_uniform::applies(m, &fl, &face_point) {
        let FaceLayout { fh, off, cidx } = fl;
        drop((fh, off, face_point));
        let (mut cols, sides) = super::primal_uniform::fill(m, &cidx, kind, n_points, want_sides)?;
        drop(cidx);
        cols.pos = points(pos, n_points)?;
        return Ok((Mesh::from_columns(cols)?, want_sides.then_some(sides)));
    }
    let Some(fi) = layout(&fl, &face_point)? else {
        let p = pos()?;
        return super::hosts::primal_host_twins(m, &fl, &face_point, p, want_sides);
    };
    let FaceLayout { fh, off, cidx } = fl;
    drop((fh, off, face_point));
    let (mut cols, sides) = fill(m, &cidx, fi, n_points, want_sides)?;
    drop(cidx);
    cols.pos = points(pos, n_points)?;
    Ok((Mesh::from_columns(cols)?, want_sides.then_some(sides)))
}

/// The outgoing half-edge of vertex `v` whose corner comes first in face
/// order (lowest `cidx`): its `a` corner is the vertex point's first corner.
#[inline]
pub(super) fn first_outgoing(m: &Mesh, cidx: &[u32], v: usize) -> u32 {
    let s = m.v_out[v];
    let (mut h, mut best) = (s, s);
    loop {
        if cidx[h as usize] < cidx[best as usize] {
            best = h;
        }
        h = m.he_prev[h as usize] ^ 1;
        if h == s {
            return best;
        }
    }
}

/// Pass 0: every input face's output corner and face bases (sequential);
/// `None` when a face has 2²⁵ corners or more.
fn layout(fl: &FaceLayout, face_point: &[u32]) -> Result<Option<Vec<FaceInfo>>> {
    let nf = face_point.len();
    let mut fi = Vec::with_capacity(nf);
    let (mut b, mut fb) = (0u32, 0u32);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let n = fl.degree(f) as u32;
        let info = FaceInfo { off: fl.off[f], n, base: b, fbase: fb, ebase: 0, fp: face_point[f] };
        if n == 0 || (info.kind() == T && n != 3) {
            return Err(MeshError::Invariant(format!("primal host: face {f} of degree {n} has no layout")));
        }
        if n >= 1 << 25 {
            return Ok(None);
        }
        let (len, nfo) = info.block();
        fi.push(info);
        b += len;
        fb += nfo;
    }
    Ok(Some(fi))
}

/// Passes 1–3: the connectivity columns (positions left empty) for
/// `n_points` output vertices, and the side map when asked for. Walks each
/// face's corners through `next` (see [`each_corner`]); the records `fi`
/// and the ranks are freed on return.
fn fill(m: &Mesh, cidx: &[u32], fi: Vec<FaceInfo>, n_points: usize, want_sides: bool) -> Result<(Columns, Vec<u32>)> {
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let (nv, ne, nf) = (m.n_vertices() as u32, m.n_edges() as u32, m.n_faces());
    let (nc, nfo) = fi.last().map_or((0, 0), |l| {
        let (len, n_out) = l.block();
        ((l.base + len) as usize, (l.fbase + n_out) as usize)
    });
    let mut ctx = Ctx { prev, face, cidx, fi, rm: vec![0; m.n_halfedges()] };
    // pass 1: first corners, per input corner and per face
    let cnt: Vec<u32> = {
        let rmp = SyncPtr(ctx.rm.as_mut_ptr());
        let ctx = &ctx;
        (0..nf)
            .into_par_iter()
            .with_min_len(MIN_LEN)
            .map(|f| {
                if crate::cancel::requested() {
                    return 0;
                }
                let fi = &ctx.fi[f];
                let n = fi.n;
                let mut r = 0u32;
                each_corner(next, m.f_start[f], |k, h| {
                    let pa = fi.base + fi.stride() * k;
                    let first_a = ctx.pos_b(ctx.loc_next(h ^ 1)) > pa;
                    let mask = match fi.kind() {
                        Q => {
                            let pb = pa + 3;
                            first_a as u32
                                | ((k + 1 < n || n == 1) as u32) << 1
                                | ((k == 0 && n > 1) as u32) << 2
                                | ((ctx.pos_a(prev[h as usize] ^ 1) > pb) as u32) << 3
                        }
                        T => first_a as u32 | 2 | ((ctx.pos_a(prev[h as usize] ^ 1) > pa + 2) as u32) << 2,
                        // slot 1 is b(next h), whose twin is a(twin h)
                        _ => first_a as u32 | ((ctx.pos_a(h ^ 1) > pa + 1) as u32) << 1,
                    };
                    // SAFETY: input corner fi.off + k belongs to face f only.
                    unsafe { *rmp.get().add((fi.off + k) as usize) = r << 4 | mask };
                    r += mask.count_ones();
                });
                r
            })
            .collect()
    };
    crate::cancel::check()?;
    let mut acc = 0u32;
    for (f, c) in cnt.into_iter().enumerate() {
        ctx.fi[f].ebase = acc;
        acc += c;
    }
    let nh = 2 * acc as usize;
    if nh != nc {
        return Err(MeshError::Invariant(format!("primal host: {nc} corners but {nh} half-edges")));
    }
    let mut cols = Columns::for_points_unfilled(n_points, nh, nfo);
    let ne_out = acc as usize;
    let mut sides = if want_sides { vec![NONE; ne_out] } else { Vec::new() };
    let ctx = &ctx;
    let (pn, pp, pv, pf, ps, po, psd) = (
        SyncPtr(cols.he_next.as_mut_ptr()),
        SyncPtr(cols.he_prev.as_mut_ptr()),
        SyncPtr(cols.he_vert.as_mut_ptr()),
        SyncPtr(cols.he_face.as_mut_ptr()),
        SyncPtr(cols.f_start.as_mut_ptr()),
        SyncPtr(cols.v_out.as_mut_ptr()),
        SyncPtr(sides.as_mut_ptr()),
    );
    let fhole = SyncPtr(cols.f_hole.as_mut_ptr());
    // pass 3: every output corner's id, then the columns
    (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each_init(Vec::<[u32; 4]>::new, |buf, f| {
        if crate::cancel::requested() {
            return;
        }
        let fi = &ctx.fi[f];
        let s = m.f_start[f];
        let n = fi.n as usize;
        // per corner of the block: (id, vertex, face, side)
        buf.clear();
        let fp = (nv + ne).wrapping_add(fi.fp); // used by Q faces only
        match fi.kind() {
            Q => {
                each_corner(next, s, |k, h| {
                    let k = k as usize;
                    let c = fi.off + k as u32;
                    let p = prev[h as usize];
                    let of = fi.fbase + k as u32;
                    let i1 = if ctx.is_first(c, 1) { ctx.first_id(fi, c, 1) } else { ctx.first_id(fi, fi.off, 2) + 1 };
                    let i2 = if ctx.is_first(c, 2) {
                        ctx.first_id(fi, c, 2)
                    } else {
                        ctx.first_id(fi, fi.off + ((k + n - 1) % n) as u32, 1) + 1
                    };
                    buf.push([ctx.id_a(h), vert[h as usize], of, h]);
                    buf.push([i1, nv + (h >> 1), of, NONE]);
                    buf.push([i2, fp, of, NONE]);
                    buf.push([ctx.id_b(h), nv + (p >> 1), of, p ^ 1]);
                });
            }
            T => {
                each_corner(next, s, |k, h| {
                    let c = fi.off + k;
                    let p = prev[h as usize];
                    let of = fi.fbase + k;
                    buf.push([ctx.id_a(h), vert[h as usize], of, h]);
                    buf.push([ctx.first_id(fi, c, 1), nv + (h >> 1), of, NONE]);
                    buf.push([ctx.id_b(h), nv + (p >> 1), of, p ^ 1]);
                });
                each_corner(next, s, |k, h| {
                    let c1 = fi.off + (k + 1) % 3;
                    buf.push([ctx.first_id(fi, c1, 1) + 1, nv + (h >> 1), fi.fbase + 3, NONE]);
                });
            }
            _ => {
                // hs[(k + 1) % n] of the corner list is next[h]
                each_corner(next, s, |_, h| {
                    buf.push([ctx.id_a(h), vert[h as usize], fi.fbase, h]);
                    buf.push([ctx.id_b(next[h as usize]), nv + (h >> 1), fi.fbase, h ^ 1]);
                });
            }
        }
        let len = buf.len();
        // size of the output faces of this block
        let fsize = match fi.kind() {
            Q => 4,
            T => 3,
            _ => len,
        };
        // SAFETY: ids are a bijection from output corners onto half-edges,
        // and every output face, face point and hole flag belongs to one
        // input face, so no two writes hit the same entry.
        unsafe {
            for s in (0..len).step_by(fsize) {
                *ps.get().add(buf[s][2] as usize) = buf[s][0];
                for j in s..s + fsize {
                    let nx = if j + 1 == s + fsize { s } else { j + 1 };
                    let [id, v, of, sd] = buf[j];
                    let idn = buf[nx][0];
                    *pn.get().add(id as usize) = idn;
                    *pp.get().add(idn as usize) = id;
                    *pv.get().add(id as usize) = v;
                    *pf.get().add(id as usize) = of;
                    if want_sides && id & 1 == 0 && sd != NONE {
                        *psd.get().add((id >> 1) as usize) = sd;
                    }
                }
            }
            match fi.kind() {
                Q => *po.get().add(fp as usize) = buf[2][0],
                H => *fhole.get().add(fi.fbase as usize) = true,
                _ => {}
            }
        }
    });
    crate::cancel::check()?;
    // SAFETY: not cancelled, so every face's block ran, and the ids are a
    // bijection onto the half-edges (above): every entry is written
    unsafe { cols.assume_filled(nh) };
    // vertex points: the a corner of the outgoing half-edge first in face order
    cols.v_out[..nv as usize].par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, o)| {
        if crate::cancel::requested() {
            return;
        }
        *o = ctx.id_a(first_outgoing(m, cidx, v));
    });
    // edge points: the lowest of e(h)'s corners, h one of the edge's halves:
    // the inner corner after a(h) (not in a hole) and b(next h). Positions
    // first (arithmetic on the two sides' faces), then the id of the winner
    // only: an id may chase a twin into another face's block.
    cols.v_out[nv as usize..(nv + ne) as usize].par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| {
        if crate::cancel::requested() {
            return;
        }
        let side = |h: u32| {
            let (fi, k, c) = ctx.loc(h);
            let j = fi.edge_point_corner(k);
            (fi.base + j, fi, k, c, j, h)
        };
        let (s0, s1) = (side(2 * e as u32), side(2 * e as u32 + 1));
        let (_, fi, k, c, j, h) = if s0.0 < s1.0 { s0 } else { s1 };
        *o = if fi.kind() != H && j == fi.stride() * k + 1 {
            // slot 1 of h's sub-block
            if ctx.is_first(c, 1) {
                ctx.first_id(fi, c, 1)
            } else {
                ctx.first_id(fi, fi.off, 2) + 1
            }
        } else {
            ctx.id_b(next[h as usize])
        };
    });
    crate::cancel::check()?;
    Ok((cols, sides))
}

#[cfg(test)]
mod tests {
    use super::super::hosts::{primal_host_twins, test_meshes as tm};
    use super::*;

    /// Every face-point pattern the schemes use (a point per face, none on
    /// triangles, holes) on the corpus and the open meshes, also after
    /// InsertEdge (faces and vertices whose stored corner is not their
    /// first): the same mesh and side map as the corner-and-twin build.
    #[test]
    fn columns_equal_the_twin_build() {
        let mut meshes: Vec<(&str, Mesh)> = tm::corpus().into_iter().filter(|(_, m)| !m.v_out.iter().any(|&o| o & crate::mesh::POINT != 0)).collect();
        meshes.extend(tm::open_meshes());
        meshes.push(("handle_cube", tm::handle_cube()));
        meshes.push(("one_two_gon", tm::one_gon_two_gon_cube()));
        for (name, m) in &meshes {
            let fl = FaceLayout::new(m).unwrap();
            let nf = m.n_faces();
            let all: Vec<u32> = (0..nf as u32).map(|f| if m.f_hole[f as usize] { HOLE } else { f }).collect();
            let tri: Vec<u32> = (0..nf).map(|f| if m.f_hole[f] { HOLE } else if fl.degree(f) == 3 { NONE } else { f as u32 }).collect();
            for fp in [all, tri] {
                let n_fp = fp.iter().filter(|&&x| x != NONE && x != HOLE).count();
                // compact face-point indices, as the schemes number them
                let mut k = 0;
                let fp: Vec<u32> = fp.iter().map(|&x| if x == NONE || x == HOLE { x } else { k += 1; k - 1 }).collect();
                let pos: Vec<DVec3> = (0..m.n_vertices() + m.n_edges() + n_fp).map(|i| DVec3::splat(i as f64)).collect();
                for sides in [false, true] {
                    let a = primal_columns(m, &fl, &fp, pos.clone(), sides).unwrap();
                    let b = primal_host_twins(m, &fl, &fp, pos.clone(), sides).unwrap();
                    a.0.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
                    assert_eq!(a, b, "{name}");
                }
            }
        }
    }

    /// The builder alone, old against new, alternating in one process:
    /// `cargo test --release --lib builder_ab -- --ignored --nocapture`
    /// (ns per output face, minimum of 5 runs; `RAYON_NUM_THREADS` as set).
    #[test]
    #[ignore]
    fn builder_ab() {
        use std::time::Instant;
        let mut cc = crate::primitives::torus(400, 250, 1.0, 0.4).unwrap();
        let mut lp = crate::primitives::icosahedron();
        for _ in 0..6 {
            lp = crate::schemes::loop_subdivision::loop_subdivision(&lp).unwrap();
        }
        for level in 1..=4 {
            for (name, m) in [("catmull_clark", &cc), ("loop", &lp)] {
                let fl = FaceLayout::new(m).unwrap();
                let nf = m.n_faces();
                let fp: Vec<u32> = if name == "loop" { vec![NONE; nf] } else { (0..nf as u32).collect() };
                let n_fp = if name == "loop" { 0 } else { nf };
                let pos = crate::mesh::zeroed_points(m.n_vertices() + m.n_edges() + n_fp);
                let (mut old, mut new) = (f64::MAX, f64::MAX);
                let mut faces = 0;
                for _ in 0..5 {
                    let t = Instant::now();
                    let a = primal_host_twins(m, &fl, &fp, pos.clone(), false).unwrap();
                    old = old.min(t.elapsed().as_secs_f64());
                    faces = a.0.n_faces();
                    drop(a);
                    let t = Instant::now();
                    let b = primal_columns(m, &fl, &fp, pos.clone(), false).unwrap();
                    new = new.min(t.elapsed().as_secs_f64());
                    drop(b);
                }
                let t = Instant::now();
                let full = if name == "loop" { crate::schemes::loop_subdivision::loop_subdivision(m) } else { crate::schemes::catmull_clark::catmull_clark(m) }.unwrap();
                let whole = t.elapsed().as_secs_f64();
                drop(full);
                let ns = |t: f64| t / faces as f64 * 1e9;
                println!(
                    "{name} level {level} ({faces} faces, {} threads): host+build old {:.1} ns/face, new {:.1} ns/face ({:.2}x); whole level (new) {:.1} ns/face",
                    rayon::current_num_threads(), ns(old), ns(new), old / new, ns(whole)
                );
            }
            if level < 4 {
                cc = crate::schemes::catmull_clark::catmull_clark(&cc).unwrap();
                lp = crate::schemes::loop_subdivision::loop_subdivision(&lp).unwrap();
            }
        }
    }
}

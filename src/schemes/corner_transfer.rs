//! Corner (face-varying) data through the schemes that have no
//! face-varying rules of their own: every scheme but Catmull-Clark and Loop
//! (those subdivide the data on its face-varying mesh,
//! [`super::face_varying`]).
//!
//! One mechanism for all of them, built from what every level already
//! states: its stencils (each output vertex as weights on input vertices)
//! and its origins. Each output corner gets a *home*: one real input face.
//! Its value is the row of its vertex evaluated with the home face's corner
//! values instead of the vertex values, so it interpolates within one
//! face's values and never across a seam. On data without seams (one value
//! per vertex) that is `S @ a` exactly, wherever the row lies in the home
//! face: every row of Doo-Sabin, the dual, honeycomb, midpoint, simplest,
//! vertex truncation, Sierpinski and Menger's transfer does (a point inside
//! a face, on an edge, or at a vertex).
//!
//! The home of the corner of output vertex `p` in output face `g`, first
//! that applies:
//! 1. the face `p` was born in (a Doo-Sabin or honeycomb corner point, a
//!    dual or midpoint centroid);
//! 2. the face `g` was born from (the F-faces, a midpoint child);
//! 3. the face the corner's outgoing side lies in, then its incoming side
//!    (simplest's and truncation's vertex faces: each corner takes the value
//!    its point has in the face whose corner that side cuts);
//! 4. otherwise (faces that straddle several input faces: the dual's and
//!    Doo-Sabin's faces of a boundary vertex, Sierpinski's back faces,
//!    Menger's strips and vertex faces) the home of the corner before it in
//!    `g`, of the one after it, then the real faces around `p`'s origin and
//!    `g`'s origin, in rotation order: the first of those that contains
//!    every vertex of `p`'s row. Where all of them agree (no seam through
//!    `p`) the choice changes nothing; at a seam the corner takes one
//!    side's value, its neighbour's.
//!
//! A row whose vertices no candidate face holds (√3's vertex smoothing
//! reaches over the one-ring) is read linearly in the home face: a point
//! born from vertex `u` takes the home face's value at `u`, one born from
//! an edge the mean of its ends' values there (FVAR_LINEAR_ALL's
//! convention). A face that passes a row's vertex at several corners gives
//! that vertex the mean of those corners' values (only a face with a
//! repeated vertex, as Sierpinski's output has, can tell them apart).
//!
//! On closed meshes without point-spheres every scheme here but Menger
//! reads the same values straight off its output numbering instead
//! ([`super::corner_direct`]); this transfer serves open meshes, Menger and
//! whatever layout those paths do not recognise.
//!
//! The result is a [`Stencils`] over corners: row = exported output corner,
//! column = exported input corner (both in face order, holes skipped), so
//! `T @ values` carries any `(C, k)` corner array through the level.

//! Cost: [`transfer`] evaluates each output corner's row straight into
//! the output arrays, in parallel blocks of output faces, with no matrix
//! built and nothing allocated per corner; a home face's corners are
//! searched in one contiguous slice of the input's corner vertices (a
//! sorted list only for faces of more than [`SMALL`] corners, where the
//! scan would be quadratic). The terms and
//! their order are those of the matrix [`corner_stencils`], so both give
//! bit-identical values.

use super::level::{Origins, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, NONE, POINT};
use rayon::prelude::*;

/// Faces of at most this many corners are searched by walking their cycle.
const SMALL: usize = 8;
/// Output faces per parallel block.
const FACES_PER_BLOCK: usize = 1024;

const NO_HOME: &str = "corner attributes: an output corner has no input face to take its value from";

/// Exported corner offset of every face (holes and point-sphere faces own
/// none) and the number of exported corners, in parallel.
pub(crate) fn export_offsets(m: &Mesh) -> Result<(Vec<u32>, usize)> {
    let deg: Vec<u32> = (0..m.n_faces())
        .into_par_iter()
        .with_min_len(super::hosts::MIN_LEN)
        .map(|f| {
            let s = m.f_start[f];
            if m.f_hole[f] || s & POINT != 0 || crate::cancel::requested() {
                return 0;
            }
            let (mut h, mut n) = (s, 0u32);
            loop {
                n += 1;
                h = m.he_next[h as usize];
                if h == s {
                    break n;
                }
            }
        })
        .collect();
    crate::cancel::check()?;
    let mut off = Vec::with_capacity(deg.len() + 1);
    let mut k = 0u32;
    off.push(0);
    for d in deg {
        k += d;
        off.push(k);
    }
    Ok((off, k as usize))
}

/// What every output corner's terms are read from (see the module docs).
struct Ctx<'a> {
    input: &'a Mesh,
    out: &'a Mesh,
    s: &'a Stencils,
    o: &'a Origins,
    /// Exported corner offset of each input face.
    ioff: Vec<u32>,
    /// The vertex of every exported input corner: face `f`'s corners are
    /// `ivert[ioff[f]..ioff[f + 1]]`, contiguous, so a search reads one
    /// short slice instead of chasing `he_next`.
    ivert: Vec<u32>,
    /// Per input face of more than [`SMALL`] corners: the start of its
    /// `(vertex, exported corner)` list in `sorted` (sorted by vertex);
    /// `NONE` for the others.
    big: Vec<u32>,
    sorted: Vec<(u32, u32)>,
    /// Per output vertex: its row holds more distinct vertices than any
    /// input face, so no face takes it whole.
    unfit: Vec<bool>,
}

/// Scratch space of one worker, reused from corner to corner.
#[derive(Default)]
struct Scratch {
    cands: Vec<u32>,
    /// `cands` as a set once it is long (the faces around a vertex of high
    /// valence: a linear search per face was quadratic in the valence).
    seen: rustc_hash::FxHashSet<u32>,
    pairs: Vec<(u32, u32)>,
    lin: Vec<u32>,
}

/// Candidates searched linearly for a repeat up to this many.
const CANDS_LINEAR: usize = 16;

impl Scratch {
    /// Appends `f` to the candidates unless it is there (order kept).
    fn push(&mut self, f: u32) {
        if self.cands.len() < CANDS_LINEAR {
            if !self.cands.contains(&f) {
                self.cands.push(f);
            }
            return;
        }
        if self.seen.is_empty() {
            self.seen.extend(self.cands.iter().copied());
        }
        if self.seen.insert(f) {
            self.cands.push(f);
        }
    }

    fn clear(&mut self) {
        self.cands.clear();
        self.seen.clear();
    }
}

impl<'a> Ctx<'a> {
    fn new(input: &'a Mesh, out: &'a Mesh, s: &'a Stencils, o: &'a Origins) -> Result<Ctx<'a>> {
        let (ioff, n_in) = export_offsets(input)?;
        let mut ivert = Vec::with_capacity(n_in);
        for f in 0..input.n_faces() {
            crate::cancel::poll(f)?;
            let mut h = input.f_start[f];
            for _ in ioff[f]..ioff[f + 1] {
                ivert.push(input.he_vert[h as usize]);
                h = input.he_next[h as usize];
            }
        }
        let mut big = vec![NONE; input.n_faces()];
        let mut sorted = Vec::new();
        for f in 0..input.n_faces() {
            let (a, b) = (ioff[f] as usize, ioff[f + 1] as usize);
            if b - a > SMALL {
                big[f] = sorted.len() as u32;
                let start = sorted.len();
                sorted.extend(ivert[a..b].iter().zip(a as u32..b as u32).map(|(&v, c)| (v, c)));
                sorted[start..].sort_unstable();
            }
        }
        // rows over more distinct vertices than any face has (their columns
        // may repeat: honeycomb's name each vertex twice)
        let max_degree = (0..input.n_faces()).map(|f| (ioff[f + 1] - ioff[f]) as usize).max().unwrap_or(0);
        let mut buf = Vec::new();
        let mut unfit = vec![false; s.n_rows()];
        for (p, u) in unfit.iter_mut().enumerate() {
            let (cols, _) = s.row(p);
            if cols.len() > max_degree {
                buf.clear();
                buf.extend_from_slice(cols);
                buf.sort_unstable();
                buf.dedup();
                *u = buf.len() > max_degree;
            }
        }
        Ok(Ctx { input, out, s, o, ioff, ivert, big, sorted, unfit })
    }

    fn real(&self, f: u32) -> bool {
        f != NONE && (f as usize) < self.input.n_faces() && !self.input.f_hole[f as usize]
    }

    fn degree(&self, f: u32) -> usize {
        (self.ioff[f as usize + 1] - self.ioff[f as usize]) as usize
    }

    /// The exported corners of small face `f` at vertex `u`, in cycle
    /// order (the order of a sorted list: corners increase along the cycle).
    #[inline]
    fn at<'b>(&self, f: u32, u: u32, buf: &'b mut [u32; SMALL]) -> &'b [u32] {
        let base = self.ioff[f as usize];
        let mut n = 0usize;
        for (j, &v) in self.corners_of(f).iter().enumerate() {
            if v == u {
                buf[n] = base + j as u32;
                n += 1;
            }
        }
        &buf[..n]
    }

    /// The vertices of real face `f`'s exported corners, in cycle order.
    #[inline]
    fn corners_of(&self, f: u32) -> &[u32] {
        &self.ivert[self.ioff[f as usize] as usize..self.ioff[f as usize + 1] as usize]
    }

    #[inline]
    fn at_big(&self, f: u32, u: u32) -> &[(u32, u32)] {
        let s = self.big[f as usize] as usize;
        let sl = &self.sorted[s..s + self.degree(f)];
        let a = sl.partition_point(|&(w, _)| w < u);
        let b = sl.partition_point(|&(w, _)| w <= u);
        &sl[a..b]
    }

    /// Calls `each(corner, count)` for the `count` exported corners of `f`
    /// at `u` and returns their number.
    #[inline]
    fn for_at(&self, f: u32, u: u32, mut each: impl FnMut(u32, usize)) -> usize {
        if self.big[f as usize] != NONE {
            let cs = self.at_big(f, u);
            for &(_, c) in cs {
                each(c, cs.len());
            }
            cs.len()
        } else {
            let mut buf = [0u32; SMALL];
            let cs = self.at(f, u, &mut buf);
            for &c in cs {
                each(c, cs.len());
            }
            cs.len()
        }
    }

    /// Whether `f` holds vertex `u`.
    #[inline]
    fn has(&self, f: u32, u: u32) -> bool {
        if self.big[f as usize] != NONE {
            return !self.at_big(f, u).is_empty();
        }
        self.corners_of(f).contains(&u)
    }

    fn face_of(&self, kind: u8, i: u32) -> u32 {
        if kind == FACE && self.real(i) {
            i
        } else {
            NONE
        }
    }

    /// Rules 1–3 for output corner `hc`.
    fn direct(&self, hc: u32) -> u32 {
        let (out, o) = (self.out, self.o);
        let p = out.he_vert[hc as usize] as usize;
        let g = out.he_face[hc as usize] as usize;
        let e_out = (hc >> 1) as usize;
        let e_in = (out.he_prev[hc as usize] >> 1) as usize;
        for f in [
            self.face_of(o.vertex_kind[p], o.vertex[p]),
            self.face_of(o.face_kind[g], o.face[g]),
            self.face_of(o.edge_kind[e_out], o.edge[e_out]),
            self.face_of(o.edge_kind[e_in], o.edge[e_in]),
        ] {
            if f != NONE {
                return f;
            }
        }
        NONE
    }

    /// The row of output vertex `p` evaluated in `f`'s corners, into
    /// `terms`; false (and `terms` cleared) when `f` misses one of its
    /// vertices.
    #[inline]
    fn eval(&self, f: u32, p: usize, terms: &mut Vec<(u32, f64)>) -> bool {
        terms.clear();
        let (cols, ws) = self.s.row(p);
        if !cols.iter().all(|&u| self.has(f, u)) {
            return false;
        }
        for (&u, &w) in cols.iter().zip(ws) {
            self.for_at(f, u, |c, n| terms.push((c, w / n as f64)));
        }
        true
    }

    /// Appends the real faces around origin `(kind, i)` to the candidates;
    /// with `one`, stops once there is a candidate.
    fn around(&self, kind: u8, i: u32, sc: &mut Scratch, one: bool) {
        let input = self.input;
        if one && !sc.cands.is_empty() {
            return;
        }
        match kind {
            EDGE => {
                for h in [2 * i, 2 * i + 1] {
                    let f = input.he_face[h as usize];
                    if self.real(f) {
                        sc.push(f);
                    }
                }
            }
            VERTEX => {
                let vo = input.v_out[i as usize];
                if vo & POINT == 0 {
                    for h in super::creases::ring(input, vo) {
                        let f = input.he_face[h as usize];
                        if self.real(f) {
                            sc.push(f);
                            if one {
                                break;
                            }
                        }
                    }
                }
            }
            _ => {
                if self.real(i) {
                    sc.push(i);
                }
            }
        }
    }

    /// The terms `(exported input corner, weight)` of output corner `hc`
    /// (the module docs' rules); empty when no input face is near.
    fn terms(&self, hc: u32, terms: &mut Vec<(u32, f64)>, sc: &mut Scratch) {
        let (out, o) = (self.out, self.o);
        let p = out.he_vert[hc as usize] as usize;
        let g = out.he_face[hc as usize] as usize;
        let first = self.direct(hc);
        // a row over more vertices than any face has fits no face (√3's
        // smoothing of a vertex of high valence): only the first candidate,
        // the linear reading's home, is needed (the search was quadratic in
        // the valence)
        let fits = !self.unfit[p];
        if first != NONE && fits && self.eval(first, p, terms) {
            return;
        }
        terms.clear();
        sc.clear();
        for f in [first, self.direct(out.he_prev[hc as usize]), self.direct(out.he_next[hc as usize])] {
            if self.real(f) {
                sc.push(f);
            }
        }
        self.around(o.vertex_kind[p], o.vertex[p], sc, !fits);
        self.around(o.face_kind[g], o.face[g], sc, !fits);
        // `first` was tried above
        if fits {
            for &f in sc.cands.iter() {
                if f != first && self.eval(f, p, terms) {
                    return;
                }
            }
        }
        terms.clear();
        let Some(&f) = sc.cands.first() else {
            return;
        };
        // read linearly in the first candidate (see the module docs)
        let lin = &mut sc.lin;
        lin.clear();
        match o.vertex_kind[p] {
            VERTEX => lin.push(o.vertex[p]),
            EDGE => {
                let e = o.vertex[p] as usize;
                lin.extend([self.input.he_vert[2 * e], self.input.he_vert[2 * e + 1]]);
            }
            _ => {}
        }
        lin.retain(|&u| self.has(f, u));
        if lin.is_empty() {
            // a face point: its face's mean, corners in vertex order
            let pairs = &mut sc.pairs;
            pairs.clear();
            let base = self.ioff[f as usize];
            pairs.extend(self.corners_of(f).iter().enumerate().map(|(j, &v)| (v, base + j as u32)));
            pairs.sort_unstable();
            let n = pairs.len() as f64;
            terms.extend(pairs.iter().map(|&(_, c)| (c, 1.0 / n)));
        } else {
            let nl = lin.len();
            for &u in lin.iter() {
                self.for_at(f, u, |c, n| terms.push((c, 1.0 / (nl * n) as f64)));
            }
        }
    }
}

/// Carries corner arrays (row-major `(C, k)`, exported input corners) through
/// one level: `input` and `out` the level's meshes, `s` its stencils (rows:
/// `out`'s vertices) and `o` its origins. Each array is replaced by the
/// output's `(C', k)` array. The values equal `corner_stencils(..) @ a`
/// bit for bit.
pub fn transfer(input: &Mesh, out: &Mesh, s: &Stencils, o: &Origins, arrays: &mut [(Vec<f64>, usize)]) -> Result<()> {
    if arrays.is_empty() {
        return Ok(());
    }
    let ctx = Ctx::new(input, out, s, o)?;
    let (ooff, n_out) = export_offsets(out)?;
    let nfo = out.n_faces();
    let nb = nfo.div_ceil(FACES_PER_BLOCK);
    let mut outs: Vec<Vec<f64>> = arrays.iter().map(|(_, k)| vec![0.0; n_out * k]).collect();
    // per block, one output slice per array
    let mut blocks: Vec<Vec<&mut [f64]>> = (0..nb).map(|_| Vec::with_capacity(arrays.len())).collect();
    for (buf, (_, k)) in outs.iter_mut().zip(arrays.iter()) {
        let mut rest: &mut [f64] = buf;
        for (b, blk) in blocks.iter_mut().enumerate() {
            let (gs, ge) = (b * FACES_PER_BLOCK, ((b + 1) * FACES_PER_BLOCK).min(nfo));
            let (x, r) = rest.split_at_mut((ooff[ge] - ooff[gs]) as usize * k);
            blk.push(x);
            rest = r;
        }
    }
    let ins: Vec<(&[f64], usize)> = arrays.iter().map(|(a, k)| (a.as_slice(), *k)).collect();
    // rule 1 depends on the output vertex alone: a vertex born in a real face
    // that holds its row gets its value once (`held`), and each of its
    // corners copies it (the same terms in the same order: the same bits)
    let nvo = out.n_vertices();
    let mut memo: Vec<Vec<f64>> = arrays.iter().map(|(_, k)| vec![0.0; nvo * k]).collect();
    let mut held = vec![false; nvo];
    {
        const VB: usize = 4096;
        let nvb = nvo.div_ceil(VB);
        let mut per: Vec<Vec<&mut [f64]>> = (0..nvb).map(|_| Vec::with_capacity(arrays.len())).collect();
        for (m, (_, k)) in memo.iter_mut().zip(arrays.iter()) {
            if *k == 0 {
                per.iter_mut().for_each(|p| p.push(&mut []));
            } else {
                m.chunks_mut(VB * k).zip(per.iter_mut()).for_each(|(ch, p)| p.push(ch));
            }
        }
        held.par_chunks_mut(VB).zip(per.into_par_iter()).enumerate().for_each_init(Vec::<(u32, f64)>::new, |terms, (b, (hv, mut dst))| {
            if crate::cancel::requested() {
                return; // the check below reports it
            }
            for (i, h) in hv.iter_mut().enumerate() {
                let p = b * VB + i;
                let f = o.vertex[p];
                if o.vertex_kind[p] != FACE || !ctx.real(f) || !ctx.eval(f, p, terms) || terms.is_empty() {
                    continue;
                }
                *h = true;
                for (d, &(a, k)) in dst.iter_mut().zip(&ins) {
                    accumulate(&mut d[i * k..(i + 1) * k], terms, a, k);
                }
            }
        });
        crate::cancel::check()?;
    }
    blocks.into_par_iter().enumerate().try_for_each_init(
        || (Vec::<(u32, f64)>::new(), Scratch::default()),
        |(terms, sc), (b, mut dst)| -> Result<()> {
            if crate::cancel::requested() {
                return Ok(()); // the check below reports it
            }
            let (gs, ge) = (b * FACES_PER_BLOCK, ((b + 1) * FACES_PER_BLOCK).min(nfo));
            // c: the corner within the block
            each_exported_corner(out, gs..ge, |c, hc| {
                let p = out.he_vert[hc as usize] as usize;
                if held[p] {
                    for (d, (m, &(_, k))) in dst.iter_mut().zip(memo.iter().zip(&ins)) {
                        d[c * k..(c + 1) * k].copy_from_slice(&m[p * k..(p + 1) * k]);
                    }
                } else {
                    ctx.terms(hc, terms, sc);
                    if terms.is_empty() {
                        return Err(MeshError::Precondition(NO_HOME.into()));
                    }
                    for (d, &(a, k)) in dst.iter_mut().zip(&ins) {
                        accumulate(&mut d[c * k..(c + 1) * k], terms, a, k);
                    }
                }
                Ok(())
            })
        },
    )?;
    crate::cancel::check()?;
    for ((a, _), v) in arrays.iter_mut().zip(outs) {
        *a = v;
    }
    Ok(())
}

/// `o += Σ w · a[c]` over the terms, in their order (as `Stencils::apply`).
#[inline]
fn accumulate(o: &mut [f64], terms: &[(u32, f64)], a: &[f64], k: usize) {
    for &(ci, w) in terms {
        let src = &a[ci as usize * k..(ci as usize + 1) * k];
        for (o, s) in o.iter_mut().zip(src) {
            *o += w * s;
        }
    }
}

/// The corner transfer of one level as a matrix (see the module docs):
/// row = exported output corner, column = exported input corner, so
/// `T @ values` carries any `(C, k)` corner array through the level;
/// [`transfer`] applies it without building it.
pub fn corner_stencils(input: &Mesh, out: &Mesh, s: &Stencils, o: &Origins) -> Result<Stencils> {
    let ctx = Ctx::new(input, out, s, o)?;
    let (_, n_in) = export_offsets(input)?;
    let ocorners: Vec<u32> = (0..out.n_faces())
        .filter(|&g| !out.f_hole[g] && out.f_start[g] & POINT == 0)
        .flat_map(|g| {
            let st = out.f_start[g];
            let mut h = st;
            let mut first = true;
            std::iter::from_fn(move || {
                if !first && h == st {
                    return None;
                }
                first = false;
                let r = h;
                h = out.he_next[h as usize];
                Some(r)
            })
        })
        .collect();
    let t = Stencils::build(ocorners.len(), n_in, |c, row| {
        let (mut terms, mut sc) = (Vec::new(), Scratch::default());
        ctx.terms(ocorners[c], &mut terms, &mut sc);
        for (ci, w) in terms {
            row.add(ci, w);
        }
    })?;
    if t.off.windows(2).any(|w| w[0] == w[1]) {
        return Err(MeshError::Precondition(NO_HOME.into()));
    }
    Ok(t)
}

/// Whether an open input without point-spheres (whose levels run without
/// them, renumbered) has a real face of more than `above` corners: where a
/// scheme writes a large face's corners itself after the transfer
/// (`doo_sabin::open_large_corners`, `honeycomb::large_corners`).
pub(crate) fn has_large_real_face(m: &Mesh, above: usize) -> bool {
    m.f_hole.iter().any(|&h| h) && !m.v_out.iter().any(|&o| o & POINT != 0) && m.faces().any(|f| !m.is_hole(f) && m.face_degree(f) > above)
}

/// The row of `rows` (`k` per exported input corner, checked against the
/// input; `call` names the scheme) that layout corner `c` (half-edge `h`)
/// reads, for a scheme's face masks over corner data; a hole's corners read
/// row 0 (their masks are computed and never read).
pub(crate) fn layout_rows<'a>(m: &'a Mesh, fl: &'a super::hosts::FaceLayout, rows: &[f64], k: usize, call: &str) -> Result<impl Fn(usize, u32) -> usize + Sync + 'a> {
    let (ioff, at) = export_offsets(m)?;
    if rows.len() != at * k || at == 0 {
        return Err(MeshError::InvalidArgument(format!("{call}: corner data of {} numbers for {at} corners of {k}", rows.len())));
    }
    Ok(move |c: usize, h: u32| {
        let f = m.he_face[h as usize] as usize;
        if m.f_hole[f] { 0 } else { ioff[f] as usize + c - fl.off[f] as usize }
    })
}

/// Writes `pv` (a row of `k` per output vertex) over the exported output
/// corners (`out_rows`, faces in order, holes and point-spheres skipped) at
/// the vertices `take` accepts: a scheme's own values for the corners at
/// points its masks give directly (`doo_sabin::open_large_corners`,
/// `honeycomb::large_corners`).
pub(crate) fn write_vertex_rows(out: &Mesh, pv: &[f64], k: usize, take: impl Fn(usize) -> bool, out_rows: &mut [f64]) -> Result<()> {
    each_exported_corner(out, 0..out.n_faces(), |c, h| {
        let v = out.he_vert[h as usize] as usize;
        if take(v) {
            out_rows[c * k..(c + 1) * k].copy_from_slice(&pv[v * k..(v + 1) * k]);
        }
        Ok(())
    })
}

/// Calls `each(c, h)` for the exported corners `h` of output faces `faces`
/// (holes and point-spheres own none), `c` counting them from 0.
fn each_exported_corner(out: &Mesh, faces: std::ops::Range<usize>, mut each: impl FnMut(usize, u32) -> Result<()>) -> Result<()> {
    let mut c = 0usize;
    for g in faces {
        let st = out.f_start[g];
        if out.f_hole[g] || st & POINT != 0 {
            continue;
        }
        let mut h = st;
        loop {
            each(c, h)?;
            c += 1;
            h = out.he_next[h as usize];
            if h == st {
                break;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "corner_transfer_tests.rs"]
mod tests;

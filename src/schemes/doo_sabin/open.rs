//! Doo-Sabin's step on open meshes: the Chaikin boundary of the module docs
//! (`super`), its corners and half-edge ids in closed form, written straight
//! into the output's columns (issue 19: no corner lists at the peak).

use super::*;

/// The output corners of an open level, each with its tail vertex and twin
/// corner in closed form. Corner blocks: `[F-faces and holes (2 per hole
/// corner) in face order | E-faces, 4 per edge | V-faces, per rotation slot
/// (2 per hole slot)]`. Output vertices: `p(h)`, the corner point of input
/// half-edge `h` (its face layout index), then `qb(h)`, the Chaikin point
/// near the head of hole half-edge `h`.
struct Corners<'a> {
    m: &'a Mesh,
    fl: &'a FaceLayout,
    vl: VertexLayout,
    /// `qb(h)` is vertex `nh + hidx[h]`.
    hidx: Vec<u32>,
    /// First corner of each F-face (and hole).
    fb: Vec<u32>,
    /// First corner of each V-face rotation slot.
    vb: Vec<u32>,
    /// First E-face corner.
    eb: u32,
}

impl Corners<'_> {
    #[inline]
    fn hole(&self, h: usize) -> bool {
        self.m.f_hole[self.m.he_face[h] as usize]
    }
    #[inline]
    fn qb(&self, h: usize) -> u32 {
        self.m.n_halfedges() as u32 + self.hidx[h]
    }
    /// The corner of half-edge `h` in its F-face (or the first of its two in its hole).
    #[inline]
    fn fcorner(&self, h: usize) -> u32 {
        let f = self.m.he_face[h];
        let k = self.fl.local(h as u32, f) as u32;
        self.fb[f as usize] + if self.m.f_hole[f as usize] { 2 * k } else { k }
    }
    #[inline]
    fn vfirst(&self, x: usize) -> u32 {
        self.vb[self.vl.vidx[x] as usize]
    }
    #[inline]
    fn vlast(&self, x: usize) -> u32 {
        self.vb[self.vl.vidx[x] as usize + 1] - 1
    }
    #[inline]
    fn e_side(&self, h: usize) -> u32 {
        self.eb + 4 * (h >> 1) as u32 + 2 * (h & 1) as u32
    }
    fn n_corners(&self) -> usize {
        self.vb[self.m.n_halfedges()] as usize
    }
    fn n_faces(&self) -> usize {
        self.m.n_faces() + self.m.n_edges() + self.m.n_vertices()
    }

    /// Output face `f`'s corners in cycle order, as `(corner, vertex, twin
    /// corner, origin)`.
    fn corners(&self, f: usize, mut emit: impl FnMut(u32, u32, u32, (u8, u32))) {
        let m = self.m;
        let (nf, ne) = (m.n_faces(), m.n_edges());
        let (next, vert, face) = m.halfedge_columns();
        let (prev, cidx) = (&m.he_prev, &self.fl.cidx);
        if f < nf {
            for &h in self.fl.corners(f) {
                let (h, c) = (h as usize, self.fcorner(h as usize));
                if self.hole(h) {
                    // Chaikin points of boundary edge h, then the cut at head(h)
                    emit(c, cidx[h], self.e_side(h), (EDGE, (h >> 1) as u32));
                    emit(c + 1, self.qb(h), self.vfirst(next[h] as usize), (VERTEX, vert[h ^ 1]));
                } else {
                    emit(c, cidx[h], self.e_side(h), (FACE, face[h]));
                }
            }
        } else if f < nf + ne {
            // [p(na), p(a), p(nb), p(b)], a hole side's p(n·) replaced by its qb
            let e = f - nf;
            let (a, b) = (2 * e, 2 * e + 1);
            let (na, nb) = (next[a] as usize, next[b] as usize);
            let c = self.eb + 4 * e as u32;
            let eo = (EDGE, e as u32);
            let side = |x: usize, nx: usize| if self.hole(x) { (self.qb(x), eo) } else { (cidx[nx], (FACE, face[x])) };
            let (va, oa) = side(a, na);
            let (vb, ob) = side(b, nb);
            emit(c, va, self.fcorner(a), oa);
            emit(c + 1, cidx[a], self.vlast(nb), eo);
            emit(c + 2, vb, self.fcorner(b), ob);
            emit(c + 3, cidx[b], self.vlast(na), eo);
        } else {
            // V-face slot of h: p(h), or for a hole corner qa(h) then qb(prev h)
            let v = f - nf - ne;
            for h in super::super::creases::ring(m, m.v_out[v]) {
                let h = h as usize;
                let s = self.vfirst(h);
                let r = (prev[h] ^ 1) as usize;
                let to_e = self.eb + 4 * (r >> 1) as u32 + 1 + 2 * (r & 1) as u32;
                if self.hole(h) {
                    let p = prev[h] as usize;
                    emit(s, cidx[h], self.fcorner(p) + 1, (VERTEX, vert[h]));
                    emit(s + 1, self.qb(p), to_e, (EDGE, (r >> 1) as u32));
                } else {
                    emit(s, cidx[h], to_e, (EDGE, (r >> 1) as u32));
                }
            }
        }
    }

    /// Corner `c`'s half-edge id given its twin `t`: the numbering
    /// `from_corner_twins` gave these corners (edges by first corner, whose
    /// twin comes later). Every F-block corner is first (its twin lies in the
    /// E or V block), so corner c < eb gets 2c; an E-face's sides 1 and 3
    /// (towards the V block) are first, ranked 2e and 2e + 1 after the F
    /// block; every other corner's twin comes earlier, and it gets that
    /// twin's id + 1.
    #[inline]
    fn id(&self, c: u32, t: u32) -> u32 {
        let first = |c: u32| {
            if c < self.eb {
                2 * c
            } else {
                let (e, j) = ((c - self.eb) / 4, (c - self.eb) % 4);
                2 * (self.eb + 2 * e + (j == 3) as u32)
            }
        };
        if t > c {
            first(c)
        } else {
            first(t) + 1
        }
    }
}

/// Doo-Sabin on a mesh with holes, with the Chaikin boundary of the module
/// docs. Positions are `S · P`.
/// Real faces with more corners than this get their corner points from the
/// face's sums (`face_corner_points`, O(n)) instead of their dense rows.
const DENSE_MAX: usize = 64;

pub(super) fn open_step(m: &Mesh, req: &Request) -> Result<Level> {
    let fl = FaceLayout::new(m)?;
    let (k, holes_he) = corners(m, &fl)?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (_, vert, face) = m.halfedge_columns();
    let (nc, n_out) = (k.n_corners(), k.n_faces());
    let b = holes_he.len();
    let mut cols = Columns::unfilled(Vec::new(), nc, n_out);
    cols.v_out = vec![0; nh + b];
    cols.f_hole[..nf].copy_from_slice(&m.f_hole);
    let mut co = if req.origins { vec![(EDGE, 0u32); nc] } else { Vec::new() };
    {
        let cp = |c: &mut Vec<u32>| SyncPtr(c.as_mut_ptr());
        let (pn, pp, pv, pf, ps, po) =
            (cp(&mut cols.he_next), cp(&mut cols.he_prev), cp(&mut cols.he_vert), cp(&mut cols.he_face), cp(&mut cols.f_start), cp(&mut cols.v_out));
        let pco = SyncPtr(co.as_mut_ptr());
        let k = &k;
        (0..n_out).into_par_iter().with_min_len(MIN_LEN).for_each_init(Vec::new, |buf: &mut Vec<(u32, u32)>, f| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            buf.clear();
            k.corners(f, |c, v, t, o| {
                let id = k.id(c, t);
                buf.push((id, v));
                // SAFETY: every corner belongs to one face, written by one task
                if req.origins {
                    unsafe { *pco.get().add(c as usize) = o };
                }
                // every output vertex first shows up in the F block (p(h) at
                // h's corner, qb(h) right after it), where `from_corner_ids`
                // took its v_out; the F-block corners are all first-of-edge
                if f < nf {
                    unsafe { *po.get().add(v as usize) = id };
                }
            });
            // SAFETY: the ids are a bijection from the output corners onto
            // 0..nc (`Corners::id`), each face is written by one task, so
            // every entry is written once.
            unsafe {
                *ps.get().add(f) = buf[0].0;
                for (i, &(id, v)) in buf.iter().enumerate() {
                    let idn = buf[if i + 1 == buf.len() { 0 } else { i + 1 }].0;
                    *pn.get().add(id as usize) = idn;
                    *pp.get().add(idn as usize) = id;
                    *pv.get().add(id as usize) = v;
                    *pf.get().add(id as usize) = f as u32;
                }
            }
        });
    }
    crate::cancel::check()?;
    // SAFETY: not cancelled, and the ids are a bijection onto 0..nc (above)
    unsafe { cols.assume_filled(nc) };
    // the rotation slots, bases and corner index are done with before the
    // positions (issue 19: the level's peak)
    drop(k);
    let FaceLayout { fh, off, cidx } = fl;
    drop(cidx);
    // rows: corner points of real faces (Doo-Sabin), qa of hole corners, then qb
    // the rows are stored only when asked for (issue 19: peak memory); the
    // positions are the same bits either way
    let hole = |h: usize| m.f_hole[face[h] as usize];
    let (pos, stencils) = Stencils::points_and_rows(nh + b, nv, &m.pos, req.stencils, |i, row| {
        if i >= nh {
            let h = holes_he[i - nh] as usize;
            row.add(vert[h], 0.25);
            row.add(vert[h ^ 1], 0.75);
            return;
        }
        let h = fh[i] as usize;
        if hole(h) {
            row.add(vert[h], 0.75);
            row.add(vert[h ^ 1], 0.25);
            return;
        }
        let f = face[h] as usize;
        let hs = &fh[off[f] as usize..off[f + 1] as usize];
        let (n, k) = (hs.len(), i - off[f] as usize);
        if n > DENSE_MAX && !req.stencils {
            return; // written below in O(n)
        }
        if n > DENSE_MAX && req.skip_large_face_rows {
            // a placeholder the caller's corner data replaces
            // (`open_large_corners`); the position is written below
            row.add(vert[h], 1.0);
            return;
        }
        for (j, &g) in hs.iter().enumerate() {
            row.add(vert[g as usize], if n == 1 { 1.0 } else { doo_sabin_weight(n, (j + n - k) % n) });
        }
    })?;
    // corner points of large real faces from the face's sums, as the closed
    // step computes them: the dense rows cost n² per n-gon (a 32,000-gon
    // took 15 s); written whether or not the rows are kept, so the
    // positions are the same bits either way
    let mut pos = pos;
    for f in (0..nf).filter(|&f| !m.f_hole[f] && (off[f + 1] - off[f]) as usize > DENSE_MAX) {
        crate::cancel::poll(f)?;
        let (a, b) = (off[f] as usize, off[f + 1] as usize);
        super::face_corner_points(&m.pos, vert, &fh[a..b], |k, x| pos[a + k] = x);
    }
    cols.pos = pos;
    let mesh = Mesh::from_columns(cols)?;
    let origins = if req.origins {
        let mut o = Origins::with_capacity(nh + b, mesh.n_edges(), nf + ne + nv);
        o.vertex_kind.extend(fh.iter().map(|&h| if hole(h as usize) { EDGE } else { FACE }));
        o.vertex.extend(fh.iter().map(|&h| if hole(h as usize) { h >> 1 } else { face[h as usize] }));
        o.vertex_kind.extend(std::iter::repeat(EDGE).take(b));
        o.vertex.extend(holes_he.iter().map(|&h| h >> 1));
        o.face_kind.extend(std::iter::repeat(FACE).take(nf).chain(std::iter::repeat(EDGE).take(ne)).chain(std::iter::repeat(VERTEX).take(nv)));
        o.face.extend((0..nf as u32).chain(0..ne as u32).chain(0..nv as u32));
        edge_origins_by_corner(&mesh, &mut o, |c| co[c])?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils, origins, creases: None })
}

/// The level's corners, and the hole half-edges in order (their `qb` points
/// follow the corner points). Refuses an edge with holes on both sides.
fn corners<'a>(m: &'a Mesh, fl: &'a FaceLayout) -> Result<(Corners<'a>, Vec<u32>)> {
    let (nf, nh) = (m.n_faces(), m.n_halfedges());
    let face = &m.he_face;
    let hole = |h: usize| m.f_hole[face[h] as usize];
    let mut hidx = vec![u32::MAX; nh];
    let mut holes_he = Vec::new();
    for h in 0..nh {
        crate::cancel::poll(h)?;
        if hole(h) {
            if hole(h ^ 1) {
                return Err(crate::error::MeshError::Precondition(format!(
                    "doo_sabin: edge {} has hole faces on both sides, so its boundary rule is undefined",
                    h >> 1
                )));
            }
            hidx[h] = holes_he.len() as u32;
            holes_he.push(h as u32);
        }
    }
    let b = holes_he.len();
    check_output_size("doo_sabin", 4 * nh + 4 * b, nh + b)?;
    let vl = VertexLayout::new(m)?;
    let mut fb = Vec::with_capacity(nf + 1);
    fb.push(0u32);
    for f in 0..nf {
        let d = fl.degree(f) as u32;
        fb.push(fb[f] + if m.f_hole[f] { 2 * d } else { d });
    }
    let eb = fb[nf];
    let mut vb = vec![0u32; nh + 1];
    for h in 0..nh {
        vb[vl.vidx[h] as usize + 1] = if hole(h) { 2 } else { 1 };
    }
    vb[0] = eb + 4 * m.n_edges() as u32;
    for s in 0..nh {
        vb[s + 1] += vb[s];
    }
    Ok((Corners { m, fl, vl, hidx, fb, vb, eb }, holes_he))
}

/// The level's corner lists (face sizes, tail vertices, twin corners, hole
/// flags), for the test that builds them with the general builder.
#[cfg(test)]
pub(super) fn corner_lists(m: &Mesh) -> (Vec<u32>, Vec<u32>, Vec<u32>, Vec<bool>) {
    let fl = FaceLayout::new(m).unwrap();
    let (k, _) = corners(m, &fl).unwrap();
    let (mut sizes, mut cv, mut tw) = (Vec::new(), vec![0u32; k.n_corners()], vec![0u32; k.n_corners()]);
    for f in 0..k.n_faces() {
        let mut n = 0;
        k.corners(f, |c, v, t, _| {
            cv[c as usize] = v;
            tw[c as usize] = t;
            n += 1;
        });
        sizes.push(n);
    }
    let mut holes = vec![false; sizes.len()];
    holes[..m.n_faces()].copy_from_slice(&m.f_hole);
    (sizes, cv, tw, holes)
}

/// Corner data at the corner points of an open level's real faces of more
/// than [`DENSE_MAX`] corners, written over `out_rows` (the transfer's
/// rows, exported output corners by `k`) from the input's (`rows`,
/// exported input corners): Doo & Sabin's mask of the face's corner values,
/// the value the generic transfer gives them (its rule 1, the corner point
/// read in its own face), in O(n) per face ([`super::face_masks`]) where
/// the transfer would read a dense row of n per corner point. With
/// `Request::skip_large_face_rows` those rows are placeholders and this is
/// what gives those corners their values. A closed input is left alone (its
/// corner data take `corner_direct`).
pub fn open_large_corners(m: &Mesh, out: &Mesh, rows: &[f64], out_rows: &mut [f64], k: usize) -> Result<()> {
    if k == 0 || !open_large_corners_apply(m) {
        return Ok(());
    }
    let fl = FaceLayout::new(m)?;
    let nf = m.n_faces();
    let big: Vec<bool> = (0..nf).map(|f| !m.f_hole[f] && fl.degree(f) > DENSE_MAX).collect();
    let at = crate::schemes::corner_transfer::layout_rows(m, &fl, rows, k, "doo_sabin")?;
    let pv = super::face_masks(m, &fl, rows, k, at)?;
    let face = &m.he_face;
    // output vertex i < nh is the corner point of layout corner i
    let nh = fl.fh.len();
    let from_big = |v: usize| v < nh && big[face[fl.fh[v] as usize] as usize];
    crate::schemes::corner_transfer::write_vertex_rows(out, &pv, k, from_big, out_rows)
}

/// Whether [`open_large_corners`] writes anything for this input (and a
/// level may take `Request::skip_large_face_rows`): open, no point-spheres
/// (their level runs without them, renumbered), a real face of more than
/// [`DENSE_MAX`] corners.
pub fn open_large_corners_apply(m: &Mesh) -> bool {
    crate::schemes::corner_transfer::has_large_real_face(m, DENSE_MAX)
}

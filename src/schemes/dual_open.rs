//! The dual of an open mesh, or of any mesh whose level asks for stencils
//! or origins ([`super::dual::dual_level`]'s convention, counts in
//! `dual.rs`'s module docs), written by one walk round the input's vertices
//! straight into the output's columns (issue 19: a level's peak at most
//! twice the exported arrays).
//!
//! It replaced a corner list and its closed-form twins handed to
//! `Mesh::from_trusted_twins`, which held the lists, two layouts and the
//! new columns at once: 1.95–2.12× the export at the first level, and
//! 3.4–4.1× from the second on, where the previous level was held whole
//! beside the next (`examples/peak_levels.rs`, every 997th face removed
//! from the sphere and the torus). Now 1.52–1.53× at the first level and
//! 1.64–1.86× after; one thread, 1.4–1.9× faster (the builder's corner
//! lists and layouts are gone). A level the caller gives up ([`Given::Owned`], a multi-level
//! call) now lends its columns to the output as the closed in-place dual's
//! (`dual_in_place.rs`) do:
//!
//! | output column | written into |
//! | --- | --- |
//! | `he_vert` | a new column |
//! | `he_next` | input `he_vert` |
//! | `f_start` | input `v_out` (each vertex's start is read before its face's is written) |
//! | `v_out` | input `f_start` (the holes' starts are kept aside first) |
//! | `he_face`, `he_prev` | input `he_face`, `he_next`, after the walk |
//!
//! The numbering is the one that builder gave (its outputs' hashes are in
//! `output_hashes.rs`): output face v lists the rotation slots of v from
//! `v_out[v]`, one corner per real face, three per hole corner h
//! (`m(edge h), v, m(edge prev h)`), then each hole's image lists two
//! corners per hole corner; edges are numbered by first corner in that
//! order and each output vertex's `v_out` is its first corner. The first
//! two corners of a hole corner open new edges (their twins are in the
//! hole's image, after every vertex face); every other corner's side
//! crosses the input edge `edge(prev h)`, keyed as the closed walk keys it
//! ([`super::dual_walk::crossing`]).

use super::dual_walk::{all_crossed, crossing, faces_and_prev};
use super::hosts::check_output_size;
use super::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, NONE};
use glam::DVec3;

/// The input of a level: borrowed (the output gets new columns) or given
/// up by the caller (its columns become the output's).
pub(crate) enum Given<'a> {
    Borrowed(&'a Mesh),
    Owned(Mesh),
}

impl Given<'_> {
    fn mesh(&self) -> &Mesh {
        match self {
            Given::Borrowed(m) => m,
            Given::Owned(m) => m,
        }
    }

    /// `len` entries over the owned input's column `pick` (its contents
    /// kept up to `len`), or a zeroed new column.
    fn column(&mut self, pick: fn(&mut Mesh) -> &mut Vec<u32>, len: usize) -> Vec<u32> {
        match self {
            Given::Borrowed(_) => vec![0; len],
            Given::Owned(m) => {
                let mut c = std::mem::take(pick(m));
                resize_exact(&mut c, len, 0);
                c
            }
        }
    }
}

/// `Vec::resize` without its amortized growth: a reused column grows by the
/// boundary's few entries, not to twice its length.
fn resize_exact(c: &mut Vec<u32>, len: usize, fill: u32) {
    c.truncate(len);
    c.reserve_exact(len - c.len());
    c.resize(len, fill);
}

/// Which of `n` items are marked, and how many marked ones come before
/// each (1 bit per item and 4 bytes per 64: a boundary is usually a small
/// part of the mesh, but need not be).
struct Marks {
    words: Vec<u64>,
    before: Vec<u32>,
}

impl Marks {
    fn new(n: usize) -> Marks {
        Marks { words: vec![0; n.div_ceil(64)], before: Vec::new() }
    }
    fn mark(&mut self, i: usize) {
        self.words[i / 64] |= 1 << (i % 64);
    }
    /// Counts the marks before every word; call once marking is done.
    fn ranked(mut self) -> Marks {
        let mut acc = 0u32;
        self.before = Vec::with_capacity(self.words.len() + 1);
        for w in &self.words {
            self.before.push(acc);
            acc += w.count_ones();
        }
        self.before.push(acc);
        self
    }
    fn has(&self, i: usize) -> bool {
        self.words[i / 64] >> (i % 64) & 1 == 1
    }
    /// Marked items before `i`.
    fn rank(&self, i: usize) -> u32 {
        self.before[i / 64] + (self.words[i / 64] & ((1u64 << (i % 64)) - 1)).count_ones()
    }
    fn count(&self) -> u32 {
        *self.before.last().unwrap_or(&0)
    }
    fn marked(&self) -> impl Iterator<Item = u32> + '_ {
        self.words.iter().enumerate().flat_map(|(k, &w)| (0..64).filter(move |i| w >> i & 1 == 1).map(move |i| (64 * k + i) as u32))
    }
}

/// The output's vertex numbering: real faces' centroids, boundary edges'
/// midpoints, boundary vertices, each in input order.
struct Numbering {
    holes: Marks,
    bedges: Marks,
    bverts: Marks,
    n_real: u32,
}

impl Numbering {
    fn new(m: &Mesh) -> Result<Numbering> {
        let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
        let mut holes = Marks::new(nf);
        for (f, _) in m.f_hole.iter().enumerate().filter(|(_, &h)| h) {
            holes.mark(f);
        }
        let holes = holes.ranked();
        let (mut bedges, mut bverts) = (Marks::new(ne), Marks::new(nv));
        if holes.count() > 0 {
            let hole = |h: usize| m.f_hole[m.he_face[h] as usize];
            for e in 0..ne {
                crate::cancel::poll(e)?;
                match (hole(2 * e), hole(2 * e + 1)) {
                    (true, true) => {
                        return Err(MeshError::Precondition(format!("dual: edge {e} has hole faces on both sides, so it has no dual edge")));
                    }
                    (false, false) => {}
                    _ => bedges.mark(e),
                }
            }
            for h in 0..m.n_halfedges() {
                crate::cancel::poll(h)?;
                if hole(h) {
                    bverts.mark(m.he_vert[h] as usize);
                }
            }
        }
        let n_real = nf as u32 - holes.count();
        Ok(Numbering { holes, bedges: bedges.ranked(), bverts: bverts.ranked(), n_real })
    }
    fn real(&self, f: u32) -> u32 {
        f - self.holes.rank(f as usize)
    }
    fn bedge(&self, e: u32) -> u32 {
        self.n_real + self.bedges.rank(e as usize)
    }
    fn bvert(&self, v: u32) -> u32 {
        self.n_real + self.bedges.count() + self.bverts.rank(v as usize)
    }
    fn n_out(&self) -> usize {
        (self.n_real + self.bedges.count() + self.bverts.count()) as usize
    }
}

/// The output columns the walk writes.
struct Out {
    vert: Vec<u32>,
    next: Vec<u32>,
    v_out: Vec<u32>,
    /// In: the input's `v_out`; out: the output's `f_start`.
    starts: Vec<u32>,
    /// Per boundary edge (by rank): the id of the first corner its hole
    /// side's corner opens (the second is this + 2).
    hole_id: Vec<u32>,
    /// Per output edge, the input edge it comes from (when asked for).
    edge_of: Vec<u32>,
}

/// [`super::dual::dual_level`] on a mesh without point-spheres: open, or
/// asked for stencils or origins.
pub(crate) fn open_dual_level(mut given: Given<'_>, req: &Request) -> Result<Level> {
    crate::cancel::check()?;
    let m = given.mesh();
    let (nv, nh) = (m.n_vertices(), m.n_halfedges());
    let num = Numbering::new(m)?;
    let nb = num.bedges.count() as usize;
    let (nc, n_out) = (nh + 4 * nb, num.n_out());
    check_output_size("dual", nc, n_out)?;
    let hole_starts: Vec<u32> = num.holes.marked().map(|f| m.f_start[f as usize]).collect();
    // the walk rotates with `he_next` alone
    if let Given::Owned(m) = &mut given {
        drop(std::mem::take(&mut m.he_prev));
    }
    let (pos, stencils) = points(given.mesh(), &num, nv, req)?;
    if let Given::Owned(m) = &mut given {
        drop(std::mem::take(&mut m.pos));
    }
    let mut o = Out {
        vert: vec![0; nc],
        next: given.column(|m| &mut m.he_vert, nc),
        starts: match &mut given {
            Given::Borrowed(m) => m.v_out.clone(),
            Given::Owned(m) => std::mem::take(&mut m.v_out),
        },
        v_out: given.column(|m| &mut m.f_start, 0),
        hole_id: vec![0; nb],
        edge_of: if req.origins { vec![0; nc / 2] } else { Vec::new() },
    };
    resize_exact(&mut o.starts, nv + hole_starts.len(), 0);
    resize_exact(&mut o.v_out, n_out, NONE);
    walk(given.mesh(), &num, nv, &mut o)?;
    link_holes(given.mesh(), &num, &hole_starts, nv, &mut o);
    drop(hole_starts);
    let mut face = given.column(|m| &mut m.he_face, nc);
    let mut prev = given.column(|m| &mut m.he_next, nc);
    drop(given);
    faces_and_prev(&o.next, &o.starts, &mut face, &mut prev)?;
    let n_holes = o.starts.len() - nv;
    let origins = req.origins.then(|| {
        let mut g = Origins::with_capacity(n_out, nc / 2, nv + n_holes);
        let (nr, nb, nvb) = (num.n_real as usize, nb, num.bverts.count() as usize);
        g.vertex_kind.extend(std::iter::repeat_n(FACE, nr).chain(std::iter::repeat_n(EDGE, nb)).chain(std::iter::repeat_n(VERTEX, nvb)));
        g.vertex.extend(real_faces(&num, nr).chain(num.bedges.marked()).chain(num.bverts.marked()));
        g.face_kind.extend(std::iter::repeat_n(VERTEX, nv).chain(std::iter::repeat_n(FACE, n_holes)));
        g.face.extend((0..nv as u32).chain(num.holes.marked()));
        g.edge_kind = vec![EDGE; nc / 2];
        g.edge = std::mem::take(&mut o.edge_of);
        g
    });
    let f_hole = (0..nv + n_holes).map(|f| f >= nv).collect();
    let mesh = Mesh::from_columns(Columns { pos, v_out: o.v_out, he_next: o.next, he_prev: prev, he_vert: o.vert, he_face: face, f_start: o.starts, f_hole })?;
    Ok(Level { mesh, stencils, origins, creases: None })
}

/// The real faces in order (the first `n_real` output vertices' faces).
fn real_faces(num: &Numbering, n_real: usize) -> impl Iterator<Item = u32> + '_ {
    (0u32..).filter(|&f| !num.holes.has(f as usize)).take(n_real)
}

/// The output's positions (and its rows when asked for): a real face's
/// corner mean, a boundary edge's midpoint, a boundary vertex itself.
fn points(m: &Mesh, num: &Numbering, nv: usize, req: &Request) -> Result<(Vec<DVec3>, Option<Stencils>)> {
    let n_out = num.n_out();
    let closed = num.holes.count() == 0;
    // closed: the centroids exactly as the plain path sums them (along each
    // cycle from its first corner: the same bits), rows only when asked for
    let centroids = || {
        let mut p = crate::mesh::zeroed_points(m.n_faces());
        super::hosts::face_centroids_walk(m, &mut p);
        crate::cancel::check().map(|_| p)
    };
    if closed && !req.stencils {
        return Ok((centroids()?, None));
    }
    // the rows' sources, in output order (freed before the walk)
    let real: Vec<u32> = real_faces(num, num.n_real as usize).collect();
    let bedges: Vec<u32> = num.bedges.marked().collect();
    let bverts: Vec<u32> = num.bverts.marked().collect();
    let vert = &m.he_vert;
    let fill = |i: usize, row: &mut super::stencil::Row| {
        if i < real.len() {
            super::hosts::face_mean_row(m, real[i] as usize, 1.0, row);
        } else if i < real.len() + bedges.len() {
            let e = bedges[i - real.len()] as usize;
            row.add(vert[2 * e], 0.5);
            row.add(vert[2 * e + 1], 0.5);
        } else {
            row.add(bverts[i - real.len() - bedges.len()], 1.0);
        }
    };
    if closed {
        Ok((centroids()?, Some(Stencils::build(n_out, nv, fill)?)))
    } else {
        Stencils::points_and_rows(n_out, nv, &m.pos, req.stencils, fill)
    }
}

/// Every vertex face, and the hole images' corners that one hole corner
/// alone determines. Reads the input's `he_next`, `he_face`, `f_hole`.
fn walk(m: &Mesh, num: &Numbering, nv: usize, o: &mut Out) -> Result<()> {
    let (next, face, hole) = (&m.he_next, &m.he_face, &m.f_hole);
    let mut slot = vec![0u32; next.len() / 2];
    let origins = !o.edge_of.is_empty();
    let (mut n_out, mut cyc, mut ids) = (0u32, Vec::new(), Vec::new());
    // corner `i` of output vertex `w`, its side from input edge `e`
    let put = |o: &mut Out, ids: &mut Vec<u32>, i: u32, w: u32, e: usize| {
        o.vert[i as usize] = w;
        let first = &mut o.v_out[w as usize];
        if *first == NONE {
            *first = i;
        }
        if origins && i & 1 == 0 {
            o.edge_of[(i >> 1) as usize] = e as u32;
        }
        ids.push(i);
    };
    for v in 0..nv {
        crate::cancel::poll(v)?;
        super::dual_walk::rotation(next, o.starts[v], &mut cyc);
        ids.clear();
        let k = cyc.len();
        for j in 0..k {
            let h = cyc[j] as usize;
            // edge(prev h): prev h = h_{j+1} ^ 1
            let key = (cyc[(j + 1) % k] >> 1) as usize;
            if hole[face[h] as usize] {
                // m(edge h), v, m(edge prev h); the first two open edges
                // whose twins are in the hole's image
                let (i0, i1) = (2 * n_out, 2 * n_out + 2);
                n_out += 2;
                let (bh, bv, bp) = (num.bedge((h >> 1) as u32), num.bvert(v as u32), num.bedge(key as u32));
                put(o, &mut ids, i0, bh, h >> 1);
                put(o, &mut ids, i1, bv, key);
                let i2 = crossing(&mut slot[key], &mut n_out);
                put(o, &mut ids, i2, bp, key);
                o.hole_id[num.bedges.rank(h >> 1) as usize] = i0;
                // the hole image's corner of h (twin of i0) and the one of
                // prev h before it (twin of i1), which leads to it
                o.vert[i0 as usize + 1] = bv;
                o.vert[i1 as usize + 1] = bp;
                o.next[i1 as usize + 1] = i0 + 1;
            } else {
                let i = crossing(&mut slot[key], &mut n_out);
                put(o, &mut ids, i, num.real(face[h]), key);
            }
        }
        for j in 1..ids.len() {
            o.next[ids[j - 1] as usize] = ids[j];
        }
        o.next[ids[ids.len() - 1] as usize] = ids[0];
        o.starts[v] = ids[0];
    }
    all_crossed(o.vert.len(), n_out)
}

/// The links the walk could not make (a hole corner's image leads to its
/// successor's) and the hole images' starts.
fn link_holes(m: &Mesh, num: &Numbering, hole_starts: &[u32], nv: usize, o: &mut Out) {
    let hole = |h: usize| m.f_hole[m.he_face[h] as usize];
    let hole_id = &o.hole_id;
    let id = |h: u32| hole_id[num.bedges.rank((h >> 1) as usize) as usize];
    for (i, e) in num.bedges.marked().enumerate() {
        let p = if hole(2 * e as usize) { 2 * e } else { 2 * e + 1 };
        o.next[hole_id[i] as usize + 1] = id(m.he_next[p as usize]) + 3;
    }
    for (j, &s) in hole_starts.iter().enumerate() {
        o.starts[nv + j] = id(s) + 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::{corpus, full_request, open_meshes, same_bits};

    /// `m` without the faces `drop` picks, its boundaries closed by holes.
    fn without(m: &Mesh, drop: impl Fn(usize) -> bool) -> Mesh {
        let p = m.to_polygons();
        let (mut sizes, mut idx, mut at) = (Vec::new(), Vec::new(), 0usize);
        for (f, &n) in p.sizes.iter().enumerate() {
            if !drop(f) {
                sizes.push(n as i64);
                idx.extend(p.indices[at..at + n as usize].iter().map(|&i| i as i64));
            }
            at += n as usize;
        }
        // the vertices left, in order
        let mut map = vec![-1i64; m.n_vertices()];
        let mut pos = Vec::new();
        for i in idx.iter_mut() {
            if map[*i as usize] < 0 {
                map[*i as usize] = pos.len() as i64;
                pos.push(m.positions()[*i as usize]);
            }
            *i = map[*i as usize];
        }
        let opts = crate::BuildOptions { close_boundaries: true, ..Default::default() };
        Mesh::from_polygons(pos, &sizes, &idx, opts).unwrap()
    }

    /// Open inputs of every kind the walk meets: the test corpus's, holes
    /// of one face and of several, bands whose every vertex is on the
    /// boundary, and closed inputs (the walk also serves requests there).
    fn cases() -> Vec<(String, Mesh)> {
        let mut cases: Vec<(String, Mesh)> = open_meshes().into_iter().chain(corpus()).map(|(n, m)| (n.to_string(), m)).collect();
        let t = crate::primitives::torus(12, 8, 3.0, 1.0).unwrap();
        // faces (i, j), i and j 1 mod 3: apart (the builder refuses
        // faces meeting at a corner only: a pinched vertex)
        cases.push(("torus, isolated holes".into(), without(&t, |f| f / 8 % 3 == 1 && f % 8 % 3 == 1)));
        cases.push(("torus, one ring left open".into(), without(&t, |f| f / 8 == 3)));
        cases.push(("torus, one ring of faces".into(), without(&t, |f| f / 8 != 5)));
        cases.push(("torus".into(), t));
        let sphere = crate::schemes::loop_subdivision::loop_subdivision(&crate::primitives::icosahedron()).unwrap();
        cases.push(("sphere, two holes".into(), without(&sphere, |f| f == 2 || f == 41)));
        cases.push(("sierpinski".into(), crate::schemes::sierpinski::sierpinski_iterated(&crate::primitives::cube(), 2).unwrap()));
        cases
    }

    /// The walk gives the builder's level (`dual_open_reference.rs`) bit for
    /// bit, with and without stencils and origins, borrowed and given up,
    /// and the second level too.
    #[test]
    fn walk_equals_the_builder() {
        let requests = [Request::plain(), Request { stencils: true, ..Request::plain() }, Request { origins: true, ..Request::plain() }, full_request()];
        let mut open = 0;
        for (name, m) in cases() {
            if m.has_point_spheres() {
                continue;
            }
            open += (m.n_holes() > 0) as usize;
            for (k, req) in requests.iter().enumerate() {
                let want = crate::schemes::dual_open_reference::level_step_reference(&m, req);
                let got = open_dual_level(Given::Borrowed(&m), req);
                let given = open_dual_level(Given::Owned(m.clone()), req);
                let (want, got, given) = match (want, got, given) {
                    (Err(a), Err(b), Err(c)) => {
                        assert_eq!((a.to_string(), a.to_string()), (b.to_string(), c.to_string()), "{name} request {k}");
                        continue;
                    }
                    (a, b, c) => (a.unwrap(), b.unwrap(), c.unwrap()),
                };
                for (what, lv) in [("borrowed", &got), ("given up", &given)] {
                    assert!(same_bits(&lv.mesh, &want.mesh), "{name} request {k} {what}");
                    assert_eq!(lv.stencils, want.stencils, "{name} request {k} {what}");
                    assert_eq!(lv.origins, want.origins, "{name} request {k} {what}");
                }
                lv2(&name, k, &want.mesh, req);
            }
        }
        assert!(open >= 8, "open cases: {open}");
    }

    /// Second level: the first level's output (twice the boundary) again.
    fn lv2(name: &str, k: usize, m: &Mesh, req: &Request) {
        let want = crate::schemes::dual_open_reference::level_step_reference(m, req).unwrap();
        let given = open_dual_level(Given::Owned(m.clone()), req).unwrap();
        assert!(same_bits(&given.mesh, &want.mesh), "{name} request {k} level 2");
        assert_eq!(given.origins, want.origins, "{name} request {k} level 2");
    }

    /// An edge with holes on both sides has no dual: refused, naming it,
    /// borrowed or given up.
    #[test]
    fn an_edge_between_two_holes_is_refused() {
        // a real face next to a hole marked as a hole too
        let mut m2 = crate::schemes::hosts::test_meshes::open_grid(2);
        let e = (0..m2.n_edges()).find(|&e| m2.f_hole[m2.he_face[2 * e] as usize] != m2.f_hole[m2.he_face[2 * e + 1] as usize]).unwrap();
        let real = if m2.f_hole[m2.he_face[2 * e] as usize] { m2.he_face[2 * e + 1] } else { m2.he_face[2 * e] };
        m2.f_hole[real as usize] = true;
        let both = |e: usize| m2.f_hole[m2.he_face[2 * e] as usize] && m2.f_hole[m2.he_face[2 * e + 1] as usize];
        let e = (0..m2.n_edges()).find(|&e| both(e)).unwrap();
        for given in [Given::Borrowed(&m2), Given::Owned(m2.clone())] {
            let err = open_dual_level(given, &Request::plain()).unwrap_err().to_string();
            assert!(err.contains(&format!("edge {e}")) && err.contains("hole faces on both sides"), "{err}");
        }
    }
}

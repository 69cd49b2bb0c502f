//! √3 subdivision on open meshes: Kobbelt's boundary rule (L. Kobbelt,
//! "√3-subdivision", SIGGRAPH 2000, §4 "Boundaries"), with the topology and
//! masks of CGAL's `Subdivision_method_3::Sqrt3_subdivision`
//! (`Sqrt3_1step`, `Sqrt3_mask_3::border_node`), which implements it.
//!
//! The boundary is refined every *second* step, so that two steps trisect
//! every boundary edge as they trisect every interior one:
//!
//! - **odd steps** (the 1st, 3rd, … level of one call): every real face gets
//!   its centroid and interior edges are flipped as on closed meshes;
//!   a boundary edge `a → b` is kept, and its face's piece is the triangle
//!   `[a, b, c_f]`; boundary vertices do not move; interior vertices use
//!   Kobbelt's rule over all their neighbours. Holes keep their corners.
//!   Any polygon faces are accepted.
//! - **even steps**: the input is an odd step's output, so every face with a
//!   boundary edge is a triangle `(s, t, x)` with exactly one boundary edge
//!   `s → t` (checked). That edge gets two points, `n₁ = (16s + 10t + u)/27`
//!   next to `s` and `n₂ = (10s + 16t + w)/27` next to `t` (`u`, `w` the
//!   boundary neighbours beyond `s` and `t`: the ternary cubic B-spline
//!   rule); the face gets no centroid but the middle triangle `[n₁, n₂, x]`,
//!   and its two interior edges flip onto `n₁` (edge `x s`) and `n₂` (edge
//!   `t x`). A boundary vertex moves to `(4u + 19v + 4w)/27` (a vertex on
//!   more than one boundary loop stays put).
//!
//! Counts (E_b boundary edges, F_r real faces, h holes; H = 2E counts the
//! half-edges of real and hole faces alike):
//! - odd:  V' = V + F_r, E' = 3E − E_b, F' = H − E_b + h (a triangle per
//!   real half-edge, the holes);
//! - even: V' = V + F_r + E_b (faces with a boundary side trade their
//!   centroid for two edge points), E' = 3E, F' = H − E_b + h, and 3E_b
//!   boundary edges.
//!
//! Both are checked against the mesh in the tests. χ and the boundary loops
//! are kept.
//!
//! The level index within a call decides the parity (`Request::level`), as
//! in CGAL, so `sqrt3(iterations=2)` on an open mesh is not two calls of
//! `sqrt3(iterations=1)` (each of those is an odd step).

use super::boundary_columns::{self, Group};
use super::kobbelt_row;
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, NONE};
use crate::schemes::level::{Level, Origins, Request, EDGE, FACE, VERTEX};
use crate::schemes::stencil::Stencils;
use std::borrow::Cow;

/// One level of √3 on a mesh with hole faces (no point-spheres: the caller
/// splits them off). See the module docs.
///
/// An input given up by the caller (`Cow::Owned`: a previous level of the
/// same call) loses its face column and hole flags once the connectivity is
/// written, before the points are computed (issue 19).
pub(super) fn open_level(m: Cow<'_, Mesh>, req: &Request) -> Result<Level> {
    if req.level % 2 == 0 {
        odd(m, req)
    } else {
        even(m, req)
    }
}

/// What the points no longer need of an input the call owns: they walk
/// rings and face cycles, and the hole tests were made before.
fn shed(m: Cow<'_, Mesh>) -> Cow<'_, Mesh> {
    match m {
        Cow::Owned(mut m) => {
            (m.he_face, m.f_hole) = (Vec::new(), Vec::new());
            Cow::Owned(m)
        }
        b => b,
    }
}

pub(super) struct Ctx<'a> {
    pub m: &'a Mesh,
    next: &'a [u32],
    prev: &'a [u32],
    vert: &'a [u32],
    face: &'a [u32],
    /// Output triangle of every real half-edge (`NONE` for hole ones).
    tri: Vec<u32>,
    /// The hole half-edges, one bit each (one cached read instead of the
    /// face and hole-flag reads the closed forms would repeat), and how many
    /// come before each word.
    holes: Vec<u64>,
    hole_rank: Vec<u32>,
    /// First output corner of every hole half-edge, by its rank among them
    /// (issue 19: a boundary's worth, not a table per half-edge).
    hole_corner: Vec<u32>,
    pub n_tri: usize,
}

impl<'a> Ctx<'a> {
    /// `per_hole`: output corners of every hole half-edge (1 odd, 3 even).
    fn new(m: &'a Mesh, per_hole: u32) -> Result<Ctx<'a>> {
        let (next, vert, face) = m.halfedge_columns();
        let nh = m.n_halfedges();
        let mut holes = vec![0u64; nh.div_ceil(64)];
        let mut tri = vec![NONE; nh];
        let mut n_tri = 0u32;
        for h in 0..nh {
            if m.f_hole[face[h] as usize] {
                holes[h / 64] |= 1 << (h % 64);
            } else {
                tri[h] = n_tri;
                n_tri += 1;
            }
        }
        let mut hole_rank = Vec::with_capacity(holes.len());
        let mut acc = 0u32;
        for w in &holes {
            hole_rank.push(acc);
            acc += w.count_ones();
        }
        let mut x = Ctx { m, next, prev: &m.he_prev, vert, face, tri, holes, hole_rank, hole_corner: vec![NONE; acc as usize], n_tri: n_tri as usize };
        let mut c = 3 * n_tri;
        for f in 0..m.n_faces() {
            crate::cancel::poll(f)?;
            if !m.f_hole[f] {
                continue;
            }
            let s = m.f_start[f];
            let mut h = s;
            loop {
                let r = x.hole_rank_of(h) as usize;
                x.hole_corner[r] = c;
                c += per_hole;
                h = next[h as usize];
                if h == s {
                    break;
                }
            }
        }
        Ok(x)
    }

    /// Hole half-edges before `h`.
    #[inline]
    fn hole_rank_of(&self, h: u32) -> u32 {
        let w = h as usize / 64;
        self.hole_rank[w] + (self.holes[w] & ((1u64 << (h % 64)) - 1)).count_ones()
    }

    #[inline]
    pub fn hole(&self, h: u32) -> bool {
        self.holes[h as usize / 64] >> (h % 64) & 1 == 1
    }

    /// The output triangle of real half-edge `h` (`NONE` for a hole one).
    #[inline]
    pub fn tri(&self, h: u32) -> u32 {
        self.tri[h as usize]
    }

    /// The first output corner of hole half-edge `h`.
    #[inline]
    fn hole_corner(&self, h: u32) -> u32 {
        self.hole_corner[self.hole_rank_of(h) as usize]
    }

    /// Output sizes and hole flags: a triangle per real half-edge, then the
    /// holes with `per_hole` corners per side (the list build's input).
    #[cfg(test)]
    fn faces(&self, per_hole: u32) -> (Vec<u32>, Vec<bool>) {
        let mut sizes = vec![3u32; self.n_tri];
        let mut holes = vec![false; self.n_tri];
        for f in 0..self.m.n_faces() {
            if self.m.f_hole[f] {
                sizes.push(per_hole * self.m.face_degree(crate::mesh::FaceId(f as u32)) as u32);
                holes.push(true);
            }
        }
        (sizes, holes)
    }

    /// The hole faces of the input in output face order.
    pub fn hole_faces(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.m.n_faces() as u32).filter(|&f| self.m.f_hole[f as usize])
    }


}

/// The one hole half-edge leaving `v`, `None` when `v` is interior,
/// `Some(NONE)` when it lies on more than one boundary loop.
fn hole_out(m: &Mesh, v: usize) -> Option<u32> {
    let mut found = None;
    for h in crate::schemes::creases::ring(m, m.v_out[v]) {
        if m.f_hole[m.he_face[h as usize] as usize] {
            found = Some(if found.is_some() { NONE } else { h });
        }
    }
    found
}

/// The neighbours `(u, w)` along the boundary of a vertex `v` with one
/// hole corner `k` (k leaves v): `k` runs `v → u`, its predecessor `w → v`.
#[inline]
fn boundary_neighbours(m: &Mesh, k: u32) -> (u32, u32) {
    (m.he_vert[(k ^ 1) as usize], m.he_vert[m.he_prev[k as usize] as usize])
}


/// The correspondence's face origins (triangles in order, then the holes)
/// and corner origins, read off the groups.
fn group_origins(x: &Ctx, per_hole: u32, group: &impl Fn(usize, bool) -> Group) -> (Vec<(u8, u32)>, Vec<(u8, u32)>) {
    let nh = x.m.n_halfedges();
    let mut corner_origin = vec![(0u8, 0u32); 3 * x.n_tri + per_hole as usize * (nh - x.n_tri)];
    let mut face_origin = Vec::with_capacity(x.n_tri);
    for h in 0..nh {
        let g = group(h, false);
        if !x.hole(h as u32) {
            face_origin.push(g.face_origin);
        }
        corner_origin[g.c as usize..(g.c + g.n) as usize].copy_from_slice(&g.origin[..g.n as usize]);
    }
    face_origin.extend(x.hole_faces().map(|f| (FACE, f)));
    (face_origin, corner_origin)
}

#[cfg(test)]
thread_local! {
    /// Tests: build through the corner lists and `Mesh::from_trusted_twins`
    /// instead of [`boundary_columns::columns`].
    pub(super) static LIST_BUILD: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// The level's columns from its groups (positions left to [`finish`]).
fn build(x: &Ctx, per_hole: u32, n_points: usize, group: impl Fn(usize, bool) -> Group + Sync) -> Result<Columns> {
    #[cfg(test)]
    if LIST_BUILD.with(|b| b.get()) {
        let (cv, tw) = boundary_columns::lists(x, per_hole, group);
        let (sizes, holes) = x.faces(per_hole);
        let (m, ()) = Mesh::from_trusted_twins(n_points, sizes, cv, tw, holes, || Ok((vec![glam::DVec3::ZERO; n_points], ())))?;
        let mut c = m.into_columns();
        c.pos = Vec::new();
        return Ok(c);
    }
    boundary_columns::columns(x, per_hole, n_points, group)
}

/// The level from its columns, then its `n_points` points and the rows when
/// asked for (`points`, [`Stencils::points_and_rows`]), and the per-corner
/// edge origins.
fn finish(
    req: &Request,
    m: &Mesh,
    (n_points, points): (usize, impl FnOnce(&Mesh) -> Result<(Vec<glam::DVec3>, Option<Stencils>)>),
    mut cols: Columns,
    vertex_origin: Vec<(u8, u32)>,
    face_origin: Vec<(u8, u32)>,
    corner_origin: Vec<(u8, u32)>,
) -> Result<Level> {
    // the positions after the connectivity, once the step's tables are freed (issue 19)
    let st;
    (cols.pos, st) = points(m)?;
    if cols.pos.len() != n_points {
        return Err(MeshError::Invariant(format!("sqrt3: {} points for {n_points} vertices", cols.pos.len())));
    }
    let mesh = Mesh::from_columns(cols)?;
    let origins = if req.origins {
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        (o.vertex_kind, o.vertex) = vertex_origin.into_iter().unzip();
        (o.face_kind, o.face) = face_origin.into_iter().unzip();
        crate::schemes::corner_origins::edge_origins_by_corner(&mesh, &mut o, |c| corner_origin[c])?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils: st, origins, creases: None })
}

fn odd(src: Cow<'_, Mesh>, req: &Request) -> Result<Level> {
    let m: &Mesh = &src;
    let x = Ctx::new(m, 1)?;
    let (nv, nf) = (m.n_vertices(), m.n_faces());
    let (next, prev, vert, face) = (x.next, x.prev, x.vert, x.face);
    // face points of the real faces
    let mut fpt = vec![NONE; nf];
    // (u32, exactly sized: it lives until the points are computed)
    let mut real: Vec<u32> = Vec::with_capacity(nf - m.n_holes());
    for f in 0..nf {
        if !m.f_hole[f] {
            fpt[f] = (nv + real.len()) as u32;
            real.push(f as u32);
        }
    }
    let n_points = nv + real.len();
    let xr = &x;
    let fpt_r = &fpt;
    let group = move |h: usize, with_cv: bool| -> Group {
        let hu = h as u32;
        if xr.hole(hu) {
            // a hole side keeps its corner
            return Group { c: xr.hole_corner(hu), n: 1, cv: [if with_cv { vert[h] } else { 0 }, 0, 0], tw: [3 * xr.tri(hu ^ 1), 0, 0], origin: [(EDGE, hu >> 1); 3], face_origin: (0, 0) };
        }
        let b = 3 * xr.tri(hu);
        let (t, f) = (hu ^ 1, face[h]);
        // the spoke c_f → a: its other side is in the piece of prev(h)'s
        // twin, or in prev(h)'s own boundary piece when prev(h) is a boundary side
        let p = prev[h];
        let tw2 = if xr.hole(p ^ 1) { 3 * xr.tri(p) + 1 } else { 3 * xr.tri(p ^ 1) };
        if xr.hole(t) {
            // boundary side a → b kept: [a, b, c_f]
            Group {
                c: b,
                n: 3,
                cv: if with_cv { [vert[h], vert[t as usize], fpt_r[f as usize]] } else { [0; 3] },
                tw: [xr.hole_corner(t), 3 * xr.tri(next[h]) + 2, tw2],
                origin: [(EDGE, hu >> 1), (FACE, f), (FACE, f)],
                face_origin: (FACE, f),
            }
        } else {
            let g = face[t as usize];
            Group {
                c: b,
                n: 3,
                cv: if with_cv { [vert[h], fpt_r[g as usize], fpt_r[f as usize]] } else { [0; 3] },
                tw: [3 * xr.tri(next[t as usize]) + 2, 3 * xr.tri(t) + 1, tw2],
                origin: [(FACE, g), (EDGE, hu >> 1), (FACE, f)],
                face_origin: (EDGE, hu >> 1),
            }
        }
    };
    let (face_origin, corner_origin, vertex_origin) = if req.origins {
        let (fo, co) = group_origins(xr, 1, &group);
        (fo, co, (0..nv as u32).map(|v| (VERTEX, v)).chain(real.iter().map(|&f| (FACE, f))).collect())
    } else {
        (vec![], vec![], vec![])
    };
    let cols = build(xr, 1, n_points, group)?;
    drop((fpt, x));
    let boundary: Vec<bool> = (0..nv).map(|v| hole_out(m, v).is_some()).collect();
    // the rows are stored only when asked for (issue 19: peak memory); the
    // points are computed after the connectivity (`finish`)
    let points = |m: &Mesh| Stencils::points_and_rows(n_points, nv, &m.pos, req.stencils, |i, row| {
        if i < nv {
            if boundary[i] {
                row.add(i as u32, 1.0);
            } else {
                kobbelt_row(m, &m.he_vert, i, row);
            }
        } else {
            crate::schemes::hosts::face_mean_row(m, real[i - nv] as usize, 1.0, row);
        }
    });
    let src = shed(src);
    finish(req, &src, (n_points, points), cols, vertex_origin, face_origin, corner_origin)
}

fn even(src: Cow<'_, Mesh>, req: &Request) -> Result<Level> {
    let m: &Mesh = &src;
    let x = Ctx::new(m, 3)?;
    let (nv, nf, nh) = (m.n_vertices(), m.n_faces(), m.n_halfedges());
    let (next, prev, vert, face) = (x.next, x.prev, x.vert, x.face);
    // the boundary side of every face that has one (at most one, and only triangles)
    let mut bside = vec![NONE; nf];
    for h in 0..nh {
        let hu = h as u32;
        if !x.hole(hu) && x.hole(hu ^ 1) {
            let f = face[h] as usize;
            let deg = m.face_degree(crate::mesh::FaceId(f as u32));
            if bside[f] != NONE || deg != 3 {
                return Err(MeshError::Precondition(format!(
                    "sqrt3: face {f} ({deg} corners) has {} boundary edges; the boundary-refining (even) step of √3 needs \
                     every face at a boundary to be a triangle with one boundary edge, as an odd step outputs \
                     (run sqrt3 with iterations=2 on the original mesh instead of one level at a time)",
                    if bside[f] != NONE { "more than one" } else { "a" }
                )));
            }
            bside[f] = hu;
        }
    }
    // output vertices: old | centroids of the faces without a boundary side | two per boundary side
    let mut fpt = vec![NONE; nf];
    // (u32, exactly sized: it lives until the points are computed)
    let mut centred: Vec<u32> = Vec::with_capacity((0..nf).filter(|&f| !m.f_hole[f] && bside[f] == NONE).count());
    for f in 0..nf {
        if !m.f_hole[f] && bside[f] == NONE {
            fpt[f] = (nv + centred.len()) as u32;
            centred.push(f as u32);
        }
    }
    let base = (nv + centred.len()) as u32;
    // the boundary sides in face order: a side's index by binary search on its face
    let sides: Vec<u32> = (0..nf).filter_map(|f| (bside[f] != NONE).then_some(bside[f])).collect();
    let side_index = |b: u32| sides.partition_point(|&s| face[s as usize] < face[b as usize]) as u32;
    let n1 = |b: u32| base + 2 * side_index(b);
    let n2 = |b: u32| base + 2 * side_index(b) + 1;
    let n_points = base as usize + 2 * sides.len();
    // P(f, h): the point of face f that the flipped edge of h reaches
    let point = |h: u32| -> u32 {
        let f = face[h as usize] as usize;
        let b = bside[f];
        if b == NONE {
            fpt[f]
        } else if h == prev[b as usize] {
            n1(b)
        } else {
            n2(b)
        }
    };
    let xr = &x;
    let tri = |h: u32| 3 * xr.tri(h);
    let group = |h: usize, with_cv: bool| -> Group {
        let hu = h as u32;
        let f = face[h];
        if xr.hole(hu) {
            // hole side k = b^1 (t → s) becomes t → n₂ → n₁ → s
            let b = hu ^ 1;
            return Group {
                c: xr.hole_corner(hu),
                n: 3,
                cv: if with_cv { [vert[h], n2(b), n1(b)] } else { [0; 3] },
                tw: [tri(next[b as usize]) + 2, tri(b), tri(prev[b as usize] ^ 1)],
                origin: [(EDGE, hu >> 1); 3],
                face_origin: (0, 0),
            };
        }
        let c = tri(hu);
        let t = hu ^ 1;
        if xr.hole(t) {
            // the middle triangle [n₁, n₂, x] of the boundary face
            let (p, n) = (prev[h], next[h]);
            return Group {
                c,
                n: 3,
                cv: if with_cv { [n1(hu), n2(hu), vert[p as usize]] } else { [0; 3] },
                tw: [xr.hole_corner(t) + 1, tri(n ^ 1), tri(p) + 2],
                origin: [(EDGE, hu >> 1), (FACE, f), (FACE, f)],
                face_origin: (FACE, f),
            };
        }
        // interior side a → b: [a, P(g, t), P(f, h)]
        let g = face[t as usize];
        let bg = bside[g as usize];
        let (tw0, o0) = if bg != NONE && t == prev[bg as usize] {
            (xr.hole_corner(bg ^ 1) + 2, (EDGE, bg >> 1)) // s → n₁ on the boundary
        } else if bg != NONE && t == next[bg as usize] {
            (tri(bg) + 1, (FACE, g)) // x → n₂, the middle triangle's side
        } else {
            (tri(next[t as usize]) + 2, (FACE, g))
        };
        let bf = bside[f as usize];
        let (tw2, o2) = if bf != NONE && hu == prev[bf as usize] {
            (tri(bf) + 2, (FACE, f)) // n₁ → x
        } else if bf != NONE && hu == next[bf as usize] {
            (xr.hole_corner(bf ^ 1), (EDGE, bf >> 1)) // n₂ → t on the boundary
        } else {
            (tri(prev[h] ^ 1), (FACE, f))
        };
        Group {
            c,
            n: 3,
            cv: if with_cv { [vert[h], point(t), point(hu)] } else { [0; 3] },
            tw: [tw0, tri(t) + 1, tw2],
            origin: [o0, (EDGE, hu >> 1), o2],
            face_origin: (EDGE, hu >> 1),
        }
    };
    let (face_origin, corner_origin, vertex_origin) = if req.origins {
        let (fo, co) = group_origins(xr, 3, &group);
        let vo = (0..nv as u32)
            .map(|v| (VERTEX, v))
            .chain(centred.iter().map(|&f| (FACE, f)))
            .chain(sides.iter().flat_map(|&b| [(EDGE, b >> 1), (EDGE, b >> 1)]))
            .collect();
        (fo, co, vo)
    } else {
        (vec![], vec![], vec![])
    };
    let cols = build(xr, 3, n_points, group)?;
    drop((fpt, bside, x));
    let hole_out: Vec<Option<u32>> = (0..nv).map(|v| hole_out(m, v)).collect();
    let points = |m: &Mesh| {
        let (next, prev, vert) = (&m.he_next, &m.he_prev, &m.he_vert);
        Stencils::points_and_rows(n_points, nv, &m.pos, req.stencils, |i, row| {
            if i < nv {
                match hole_out[i] {
                    None => kobbelt_row(m, vert, i, row),
                    Some(NONE) => row.add(i as u32, 1.0),
                    Some(k) => {
                        let (u, w) = boundary_neighbours(m, k);
                        row.add(u, 4.0 / 27.0);
                        row.add(i as u32, 19.0 / 27.0);
                        row.add(w, 4.0 / 27.0);
                    }
                }
            } else if i < base as usize {
                crate::schemes::hosts::face_mean_row(m, centred[i - nv] as usize, 1.0, row);
            } else {
                let j = i - base as usize;
                let b = sides[j / 2];
                let k = b ^ 1;
                let (s, t) = (vert[b as usize], vert[k as usize]);
                if j % 2 == 0 {
                    let u = vert[(next[k as usize] ^ 1) as usize];
                    row.add(s, 16.0 / 27.0);
                    row.add(t, 10.0 / 27.0);
                    row.add(u, 1.0 / 27.0);
                } else {
                    let w = vert[prev[k as usize] as usize];
                    row.add(s, 10.0 / 27.0);
                    row.add(t, 16.0 / 27.0);
                    row.add(w, 1.0 / 27.0);
                }
            }
        })
    };
    let src = shed(src);
    finish(req, &src, (n_points, points), cols, vertex_origin, face_origin, corner_origin)
}

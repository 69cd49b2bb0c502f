//! Steps 4–5 (VII.3 steps 4–5): the outer remeshing (trisected edges,
//! corner and edge quads), the pipes between remeshing and offset faces,
//! the inner surface's strips, miter quads and vertex faces, assembled
//! into polygons; non-planar ones split into planar pieces.

use super::connect::{inner_points, split_cycle, Inner};
use super::offset::{plan, Plan};
use super::pipe::window_corners;
use super::{EdgeKind, MengerOptions, Reduction};
use crate::error::Result;
use crate::mesh::{HalfedgeId, Mesh};
use glam::DVec3;

/// Corners of every output face, with vertices as: `0..V` old, then
/// `tri(e, end)`, `qv(h)` and `inner(i)` (raw inner point ids, see [`Inner`]).
/// Faces left with fewer than three distinct corners are dropped. Also
/// returns each face's kind: 0 corner quad, 1 edge quad, 2 pipe quad,
/// 3 strip, 4 miter quad, 5 vertex face.
/// Polygons with a tag (which step made them) and their origin (the input
/// element they belong to, as in [`crate::schemes::level::Origins`]).
type Emitted = (Vec<i64>, Vec<i64>, Vec<u8>, Vec<(u8, u32)>);

fn emit_faces(m: &Mesh, pl: &Plan, inner: &Inner, tri: &dyn Fn(usize) -> u32, qv: &dyn Fn(usize) -> u32, iv: &dyn Fn(u32) -> u32) -> Emitted {
    use crate::schemes::level::{EDGE, FACE, VERTEX};
    let ng = pl.group_pos.len();
    let r = |h: HalfedgeId| iv(inner.rep[pl.group[h.idx()] as usize]);
    let mid = |e: usize, end: usize| iv(inner.rep[ng + 2 * e + end]);
    let mut sizes: Vec<i64> = Vec::new();
    let mut idx: Vec<i64> = Vec::new();
    let mut tags: Vec<u8> = Vec::new();
    let mut origin: Vec<(u8, u32)> = Vec::new();
    let mut push = |poly: &[u32], tag: u8, from: (u8, u32)| {
        for d in split_cycle(poly) {
            if d.len() >= 3 {
                sizes.push(d.len() as i64);
                idx.extend(d.iter().map(|&x| x as i64));
                tags.push(tag);
                origin.push(from);
            }
        }
    };
    // outer remeshing (corner and edge quads) and the pipes
    for f in m.faces() {
        for h in m.face_halfedges(f) {
            let nx = m.next(h);
            let of = (FACE, f.0);
            let [corner, edge] = outer_quads(m, h, tri, qv);
            push(&corner, 0, of);
            push(&edge, 1, of);
            push(&[qv(h.idx()), qv(nx.idx()), r(nx), r(h)], 2, of);
        }
    }
    // inner surface: strips, miter quad pairs, vertex faces
    for e in m.edges() {
        let h = e.halfedge();
        let t = h.twin();
        match pl.kind[e.idx()] {
            // merged corners: the offset faces meet along the edge; per-face
            // corners (module docs): a strip between the two offset edges,
            // both parallel to the edge, so planar (none where both ends
            // were welded, as at the cube's right angles)
            EdgeKind::Collapse => {
                if r(h) != r(m.next(t)) || r(m.next(h)) != r(t) {
                    push(&[r(h), r(m.next(h)), r(t), r(m.next(t))], 3, (EDGE, e.0));
                }
            }
            EdgeKind::Strip => push(&[r(h), r(m.next(h)), r(t), r(m.next(t))], 3, (EDGE, e.0)),
            EdgeKind::Miter => {
                if r(h) == r(m.next(t)) && r(m.next(h)) == r(t) {
                    // both ends already one offset corner (every other edge
                    // around collapsed): the offset faces meet, no strip
                    continue;
                }
                let (m0, m1) = (mid(e.idx(), 0), mid(e.idx(), 1));
                push(&[r(h), r(m.next(h)), m1, m0], 4, (EDGE, e.0));
                push(&[m0, m1, r(t), r(m.next(t))], 4, (EDGE, e.0));
            }
        }
    }
    let mut poly = Vec::new();
    for v in m.vertices() {
        let Some(h0) = m.vertex_halfedge(v) else { continue };
        poly.clear();
        let mut h = h0;
        loop {
            poly.push(r(h));
            if pl.kind[h.edge().idx()] == EdgeKind::Miter {
                poly.push(mid(h.edge().idx(), (h.0 & 1) as usize));
            }
            h = m.next(h.twin());
            if h == h0 {
                break;
            }
        }
        push(&poly, 5, (VERTEX, v.0));
    }
    (sizes, idx, tags, origin)
}

/// The outer remeshing's corner quad and edge quad of the corner at the
/// tail of `h` (step 4), with `tri` numbering the trisection points (two
/// per edge, the one near the tail of its even half-edge first) and `qv`
/// the inset corners by half-edge.
fn outer_quads(m: &Mesh, h: HalfedgeId, tri: &dyn Fn(usize) -> u32, qv: &dyn Fn(usize) -> u32) -> [[u32; 4]; 2] {
    let t_near = |h: HalfedgeId, near_tail: bool| -> u32 {
        let near_tail_of_2e = (h.0 & 1 == 0) == near_tail;
        tri(2 * h.edge().idx() + if near_tail_of_2e { 0 } else { 1 })
    };
    let (pr, nx) = (m.prev(h), m.next(h));
    [[m.vertex(h).0, t_near(h, true), qv(h.idx()), t_near(pr, false)], [t_near(h, true), t_near(h, false), qv(nx.idx()), qv(h.idx())]]
}

/// Positions and polygon faces of one iteration, with the number of inner
/// points used and of faces added by splitting non-planar faces.
pub(crate) struct Built {
    pub(super) pos: Vec<DVec3>,
    pub(super) sizes: Vec<i64>,
    pub(super) idx: Vec<i64>,
    pub(super) inner_vertices: usize,
    pub(super) split_extra: usize,
    /// Output vertices from here on are inner points (offset corners, miter
    /// vertices, cone apices); below are the outer remeshing's.
    pub(super) first_inner: u32,
    /// Input vertices whose vertex face became a cone.
    pub(super) coned: Vec<u32>,
    /// The input vertex whose local rule placed each output vertex
    /// (`u32::MAX` for the input's vertices and the trisection points).
    pub(crate) owner: Vec<u32>,
    /// The input element every output face belongs to (`Origins` kinds).
    pub(crate) face_origin: Vec<(u8, u32)>,
    /// Per input face, its offset depth over its inset `D` (below 1 where
    /// reduced or bounded at a sharp edge).
    pub(super) depth_factor: Vec<f64>,
}

pub(super) fn build_polygons(m: &Mesh, o: &MengerOptions, refined: bool, full: &[bool], red: Option<&Reduction>) -> Result<Built> {
    let pl = plan(m, o, full, red)?;
    let inner = inner_points(m, &pl, refined, full)?;
    let pos = m.positions();
    let (nv, ne, nh) = (m.n_vertices(), m.n_edges(), m.n_halfedges());
    // vertex layout: [old | trisection 2 per edge | inset corner per half-edge | used welded inner points]
    let t0 = nv;
    let q0 = t0 + 2 * ne;
    let i0 = q0 + nh;
    let mut out_pos: Vec<DVec3> = Vec::with_capacity(i0 + pl.group_pos.len());
    out_pos.extend_from_slice(pos);
    for e in m.edges() {
        crate::cancel::poll(e.0 as usize)?;
        let h = e.halfedge();
        let (a, b) = (pos[m.vertex(h).idx()], pos[m.head(h).idx()]);
        let len = (b - a).length();
        let d = (0.5 * (pl.face_d[m.face(h).idx()] + pl.face_d[m.face(h.twin()).idx()])).min(0.4 * len);
        let u = (b - a) / len;
        out_pos.push(a + d * u);
        out_pos.push(b - d * u);
    }
    out_pos.extend(window_corners(m, &pl, &inner));
    // inner points get ids in order of first use
    let base = u32::MAX / 2;
    let (sizes, mut idx, tags, origin) = emit_faces(m, &pl, &inner, &|i| (t0 + i) as u32, &|h| (q0 + h) as u32, &|i| base + i);
    let mut inner_id = vec![u32::MAX; inner.pos.len()];
    for x in idx.iter_mut() {
        if *x >= base as i64 {
            let i = (*x - base as i64) as usize;
            if inner_id[i] == u32::MAX {
                inner_id[i] = out_pos.len() as u32;
                out_pos.push(inner.pos[i]);
            }
            *x = inner_id[i] as i64;
        }
    }
    let inner_vertices = out_pos.len() - i0;
    let ng = pl.group_pos.len();
    let mut group_vertex = vec![u32::MAX; ng];
    for h in m.halfedges() {
        crate::cancel::poll(h.0 as usize)?;
        group_vertex[pl.group[h.idx()] as usize] = m.vertex(h).0;
    }
    let mut owner = vec![u32::MAX; q0];
    owner.extend(m.halfedges().map(|h| m.vertex(h).0));
    owner.resize(out_pos.len(), u32::MAX);
    for (i, &id) in inner_id.iter().enumerate() {
        if id != u32::MAX {
            owner[id as usize] = if i < ng {
                group_vertex[i]
            } else {
                let e = crate::mesh::EdgeId(((i - ng) / 2) as u32);
                let h = e.halfedge();
                if (i - ng) % 2 == 0 { m.vertex(h).0 } else { m.head(h).0 }
            };
        }
    }
    // non-planar faces (vertex faces at saddle-like vertices, faces of a
    // non-planar input) are split into planar pieces; the merged
    // construction keeps its tolerance relative to the mesh's smallest `D`,
    // so that its outputs and the figures recorded for it stay as they are
    // (with 1e-9 of each polygon's size its tetrahedron 3 gained 12 faces
    // and its fourth iteration 4,860 crossing pairs instead of 4,646)
    let mesh_tol = (!pl.per_face).then(|| 1e-9 * pl.face_d.iter().cloned().fold(f64::INFINITY, f64::min).max(1e-300));
    let (mut sz2, mut idx2) = (Vec::with_capacity(sizes.len()), Vec::with_capacity(idx.len()));
    let mut face_origin = Vec::with_capacity(sizes.len());
    let mut k = 0;
    let mut pieces = Vec::new();
    let mut coned: Vec<u32> = Vec::new();
    let cone_all = pl.per_face && !super::offset::right_angled(m, &pl.face_n);
    for (fi, &n) in sizes.iter().enumerate() {
        let poly: Vec<u32> = idx[k..k + n as usize].iter().map(|&x| x as u32).collect();
        k += n as usize;
        pieces.clear();
        // per-face corners off right angles (module docs, "Per-face
        // corners", invariant 5): every vertex face with more than three
        // corners is a cone from below, planar or not (a planar one spanning
        // the collar cut through the outer surface at the tetrahedron's
        // vertices of 60°, 270° and 270°: 276 pairs in its fourth iteration,
        // 48 as cones); on the cube's right angles they stay as built
        let vertex_face = tags[fi] == 5 && poly.len() > 3;
        if !(vertex_face && cone_all) {
            split_planar(&poly, &out_pos, mesh_tol, &mut pieces);
        }
        if vertex_face && (cone_all || pieces.len() == poly.len() - 2) {
            // a vertex face with no planar split: a cone from its centroid
            // (a fan from a corner can fold through the outer surface)
            pieces.clear();
            let c = out_pos.len() as u32;
            let centroid = poly.iter().map(|&i| out_pos[i as usize]).sum::<DVec3>() / poly.len() as f64;
            // per-face corners (module docs, "Per-face corners"): the apex
            // below every face around the vertex, by the smallest depth
            // there, so the cone lies under the vertex's faces (the vertex's
            // neighbourhood is star-shaped from it) as the depth shrinks,
            // where the centroid of a saddle's collar can lie outside; where
            // no point is below every face (normals in no hemisphere), that
            // depth along the sum of the normals (inward), still not the
            // centroid (tetrahedron 4: 2,760 pairs with it, 276 without)
            let apex = if pl.per_face {
                let v = crate::mesh::VertexId(origin[fi].1);
                let normals: Vec<DVec3> = m.vertex_halfedges(v).map(|h| pl.face_n[m.face(h).idx()]).collect();
                let dmin = m.vertex_halfedges(v).map(|h| pl.face_depth[m.face(h).idx()]).fold(f64::INFINITY, f64::min);
                super::offset::below_every_face(pos[v.idx()], &normals, dmin).unwrap_or_else(|| {
                    let u = normals.iter().sum::<DVec3>().normalize_or_zero();
                    if u == DVec3::ZERO {
                        return centroid;
                    }
                    // the first of these whose cone misses the outer corner
                    // and edge quads around the vertex (12 vertices of the
                    // tetrahedron's fourth iteration, edges of 306°, 135°,
                    // 161°, 241°, 180°, 90°, put the first above the 306°
                    // edge's corner)
                    let pv = pos[v.idx()];
                    let cands = [pv - u * dmin, pv - u * (0.5 * dmin), pv - u * (0.25 * dmin), pv - u * (2.0 * dmin), centroid];
                    let (t0, q0) = (m.n_vertices(), m.n_vertices() + 2 * m.n_edges());
                    cands.iter().copied().find(|&c| !cone_meets_frame(m, v, c, &poly, &out_pos, t0, q0)).unwrap_or(cands[0])
                })
            } else {
                centroid
            };
            out_pos.push(apex);
            for i in 0..poly.len() {
                pieces.push(vec![c, poly[i], poly[(i + 1) % poly.len()]]);
            }
            owner.push(owner[poly[0] as usize]);
            coned.push(owner[poly[0] as usize]);
        }
        for p in &pieces {
            sz2.push(p.len() as i64);
            idx2.extend(p.iter().map(|&x| x as i64));
            face_origin.push(origin[fi]);
        }
    }
    let split_extra = sz2.len() - sizes.len();
    let depth_factor = pl.face_depth.iter().zip(&pl.face_d).map(|(a, b)| a / b).collect();
    Ok(Built { pos: out_pos, sizes: sz2, idx: idx2, inner_vertices: inner_vertices + coned.len(), split_extra, owner, first_inner: i0 as u32, coned, face_origin, depth_factor })
}

/// Largest distance of the polygon's points from its best-fit plane through
/// the centroid along the Newell normal.
fn planarity(poly: &[u32], pos: &[DVec3]) -> f64 {
    let pts: Vec<DVec3> = poly.iter().map(|&i| pos[i as usize]).collect();
    let c = pts.iter().sum::<DVec3>() / pts.len() as f64;
    let mut n = DVec3::ZERO;
    for i in 0..pts.len() {
        n += pts[i].cross(pts[(i + 1) % pts.len()]);
    }
    let n = n.normalize_or_zero();
    pts.iter().map(|p| (p - c).dot(n).abs()).fold(0.0, f64::max)
}

/// Planarity tolerance of a polygon of the per-face construction, relative
/// to its own size (its farthest corner from its first). A tolerance
/// relative to the mesh's smallest `D` read the rounding of the inset
/// points of faces a thousand times larger as bends and split them: 1,142
/// quads of the tetrahedron's fourth iteration (residuals 2e-13 to 6e-12
/// against 2.2e-13: corner quads, pipe walls, strips), so its counts
/// followed rounding, not the formulas (module docs, "Counts"). At 1e-9 of
/// the size, 8 corner quads at its sharpest corners (where the inset point's
/// `1/(1 + w₁·w₂)` amplifies rounding) still read 1.07e-9; real folds (a
/// saddle's vertex face, a bent pipe wall) are of the order of the depth.
const PLANAR_REL: f64 = 1e-8;

/// Largest polygon [`split_planar`] searches for a planar split: the search
/// tries every diagonal and measures both parts, O(n³) (the 2,000-gon vertex
/// face of the apex of `conway("Y2000")` in the merged construction took 3 s
/// of its 10); a larger one is fanned (or coned, as a vertex face).
const SPLIT_SEARCH_MAX: usize = 64;

/// Splits a non-planar polygon along a diagonal into planar parts when one
/// exists (a saddle vertex face folds into squares; searched up to
/// [`SPLIT_SEARCH_MAX`] corners), else fans it into triangles from its first
/// corner. `mesh_tol`: an absolute tolerance (the merged construction's),
/// else [`PLANAR_REL`] of the polygon's size.
fn split_planar(poly: &[u32], pos: &[DVec3], mesh_tol: Option<f64>, out: &mut Vec<Vec<u32>>) {
    let n = poly.len();
    let p0 = pos[poly[0] as usize];
    let tol = mesh_tol.unwrap_or_else(|| PLANAR_REL * poly.iter().map(|&i| (pos[i as usize] - p0).length()).fold(0.0, f64::max));
    if n <= 3 || planarity(poly, pos) <= tol {
        out.push(poly.to_vec());
        return;
    }
    for i in 0..if n <= SPLIT_SEARCH_MAX { n } else { 0 } {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let a: Vec<u32> = poly[i..=j].to_vec();
            let b: Vec<u32> = poly[j..].iter().chain(&poly[..=i]).copied().collect();
            if planarity(&a, pos) <= tol && planarity(&b, pos) <= tol {
                out.push(a);
                out.push(b);
                return;
            }
        }
    }
    for i in 1..n - 1 {
        out.push(vec![poly[0], poly[i], poly[i + 1]]);
    }
}

/// Whether the cone from `apex` over the collar `poly` (output vertex ids)
/// meets the outer remeshing around input vertex `v` (its corner and edge
/// quads, two triangles each; contacts included): the check of the apex
/// candidates where no point lies below every face.
fn cone_meets_frame(m: &Mesh, v: crate::mesh::VertexId, apex: DVec3, poly: &[u32], out_pos: &[DVec3], t0: usize, q0: usize) -> bool {
    use crate::geometry::crossing::triangles_meet;
    let mut frame: Vec<[u32; 3]> = Vec::new();
    for h in m.vertex_halfedges(v) {
        for q in outer_quads(m, h, &|i| (t0 + i) as u32, &|h| (q0 + h) as u32) {
            frame.push([q[0], q[1], q[2]]);
            frame.push([q[0], q[2], q[3]]);
        }
    }
    let apex_id = u32::MAX;
    let at = |i: u32| if i == apex_id { apex } else { out_pos[i as usize] };
    let k = poly.len();
    (0..k).any(|i| {
        let t = [apex_id, poly[i], poly[(i + 1) % k]];
        frame.iter().any(|f| triangles_meet(t, t.map(at), *f, f.map(at), true))
    })
}

//! Triangulation of a polygon mesh that stays a closed 2-manifold.
//!
//! **Contract.** On a mesh without self-loops, one- or two-gons and vertices
//! repeated in a face, every edge of the triangle mesh is shared by exactly
//! two triangles, with opposite directions: no diagonal is an edge of the
//! mesh, and no two faces choose the same diagonal. This holds for
//! non-planar and non-convex faces too. Points are added where needed (see
//! [`Triangulation`]): first the middle of every multi-edge copy after the
//! first (lowest edge id) between the same two vertices, which both faces
//! beside that copy take as a corner; then, in face order, points inside
//! faces that no diagonal-only triangulation fits.
//!
//! **Per face** (in parallel): the vertex cycle, consecutive repeats dropped,
//! is projected into the plane of its Newell normal. Faces of five or more
//! corners bent out of that plane by more than [`BENT`] are fanned around their centroid (an added
//! point): diagonals of their projection can fold the surface through itself
//! (one Doo-Sabin step of a Sierpinski tetrahedron: manifold3d then sees genus
//! 0 instead of 3). Convex faces are fanned
//! from their first corner, strictly convex ones of more than
//! [`HALVING_MIN`] corners cut by [`halving`] (ears of every other corner,
//! repeatedly: a fan's boxes all overlap at its first corner); faces star-shaped from their corners' mean are
//! ear-clipped in linear time ([`star_clip`]); other non-convex faces go to
//! `earcut` (z-order hashed; near-linear on most polygons, quadratic on
//! stars, noisy outlines and spirals), or past [`MONOTONE_MIN`] corners
//! are cut into monotone pieces ([`monotone`], O(n log n)). **Global pass**:
//! every diagonal is tested against the mesh edges (walking the rotation of
//! its endpoint of smaller valence) and against every other face's diagonals
//! (one parallel sort). **Retry** of each face with a collision, in face
//! order, with the edges and the diagonals already accepted forbidden: its
//! first choice if that no longer collides, else other fans (convex faces),
//! else an exact O(n³) search over the face's triangulations for faces of up
//! to [`EXACT_LIMIT`] corners; failing that, one point, the corners' mean,
//! with the face fanned around it (when the face is small, or star-shaped
//! from there); failing that (large faces star-shaped from no such point), past
//! [`MONOTONE_MIN`] corners the monotone sweep along x and earcut are tried,
//! and each forbidden diagonal of the candidate with the fewest is split at a
//! point beside its middle. Total
//! work is near-linear in corners; the output depends only on the mesh
//! (deterministic at any thread count).
//!
//! Meshes with self-loops, one- or two-gons or repeated face vertices keep
//! the legacy behaviour: self-loop repeats dropped, faces left with fewer
//! than three corners give no triangle (the triangle mesh pinches there).
//! Holes are left out.

use crate::mesh::{EdgeId, FaceId, Mesh, VertexId};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// The triangles of a mesh.
///
/// Vertex indices below `mesh.n_vertices()` are mesh vertices; an index `i`
/// at or above it is the added point `points[i - n_vertices]`, so the
/// triangle mesh's vertex array is the mesh's positions followed by `points`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Triangulation {
    /// Points added inside faces that no diagonal-only triangulation fits, in face order.
    pub points: Vec<DVec3>,
    /// Counter-clockwise (seen from outside) triangles, grouped by face in face order.
    pub tris: Vec<[u32; 3]>,
    /// The face each triangle came from.
    pub tri_face: Vec<u32>,
}

impl Mesh {
    /// Triangulates every non-hole face; see the [module docs](crate::geometry::triangulate).
    pub fn triangulate(&self) -> Triangulation {
        triangulate(self)
    }
}

/// Faces of up to this many corners are retried by the exact search.
pub const EXACT_LIMIT: usize = 40;
/// Larger faces than this are never given to earcut (its node offsets are 32-bit).
const EARCUT_LIMIT: usize = 1 << 25;
/// Non-convex faces of more corners than this, not star-shaped from their
/// mean, are cut into monotone pieces ([`monotone`]) rather than given to
/// earcut, which is quadratic on noisy outlines; below it earcut's
/// quadratic cases cost at most milliseconds.
const MONOTONE_MIN: usize = 4096;
/// Faces per parallel task.
const BLOCK: usize = 2048;

/// How a face's projection looks.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Shape {
    /// zero Newell normal: no plane to work in
    Degenerate,
    Convex,
    NonConvex,
}

/// Per-thread buffers.
#[derive(Default)]
struct Scratch {
    cyc: Vec<u32>,
    p: Vec<DVec2>,
    local: Vec<[u32; 3]>,
    ear: earcut::Earcut<f64>,
    ear_out: Vec<u32>,
}

fn cross2(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Key of the unordered vertex pair {a, b}.
fn pair(a: u32, b: u32) -> u64 {
    ((a.min(b) as u64) << 32) | a.max(b) as u64
}

/// Whether `a` and `b` are joined by an edge, in O(min(valence)).
fn is_edge(m: &Mesh, a: u32, b: u32) -> bool {
    // added points (beyond the mesh's vertices) lie on no edge
    let nv = m.n_vertices() as u32;
    if a >= nv || b >= nv {
        return false;
    }
    let (Some(ha), Some(hb)) = (m.vertex_halfedge(VertexId(a)), m.vertex_halfedge(VertexId(b))) else { return false };
    let (mut x, mut y) = (ha, hb);
    loop {
        if m.head(x).0 == b || m.head(y).0 == a {
            return true;
        }
        x = m.rotate(x);
        y = m.rotate(y);
        // one rotation complete: every neighbour of that endpoint seen
        if x == ha || y == hb {
            return false;
        }
    }
}

/// The face's vertex cycle with consecutive repeats dropped, cyclically,
/// and the point of every split multi-edge copy between its two ends.
fn face_cycle(m: &Mesh, f: FaceId, split: &[u32], cyc: &mut Vec<u32>) {
    cyc.clear();
    if split.is_empty() {
        cyc.extend(m.face_vertices(f).map(|v| v.0));
    } else {
        for h in m.face_halfedges(f) {
            cyc.push(m.vertex(h).0);
            let p = split[h.edge().idx()];
            if p != u32::MAX {
                cyc.push(p);
            }
        }
    }
    cyc.dedup();
    while cyc.len() > 1 && cyc.first() == cyc.last() {
        cyc.pop();
    }
}

/// The Newell normal of the cycle (twice its vector area) and its corners' mean.
fn newell(cyc: &[u32], pos: &[DVec3]) -> (DVec3, DVec3) {
    let n = cyc.len();
    let at = |i: usize| pos[cyc[i] as usize];
    let (mut normal, mut c) = (DVec3::ZERO, DVec3::ZERO);
    for i in 0..n {
        normal += at(i).cross(at((i + 1) % n));
        c += at(i);
    }
    (normal, c / n as f64)
}

/// Projects the cycle into its Newell plane, counter-clockwise seen from the
/// normal; the frame's origin is the corners' mean.
fn project(cyc: &[u32], pos: &[DVec3], p: &mut Vec<DVec2>) -> Shape {
    let n = cyc.len();
    let at = |i: usize| pos[cyc[i] as usize];
    let (normal, c) = newell(cyc, pos);
    p.clear();
    let Some(nz) = normal.try_normalize() else { return Shape::Degenerate };
    let u = nz.any_orthonormal_vector();
    let w = nz.cross(u);
    p.extend((0..n).map(|i| {
        let q = at(i) - c;
        DVec2::new(q.dot(u), q.dot(w))
    }));
    if (0..n).all(|i| cross2(p[i], p[(i + 1) % n], p[(i + 2) % n]) >= 0.0) {
        Shape::Convex
    } else {
        Shape::NonConvex
    }
}

fn fan(n: usize, from: usize, out: &mut Vec<[u32; 3]>) {
    out.clear();
    out.extend((1..n - 1).map(|i| [from, from + i, from + i + 1].map(|k| (k % n) as u32)));
}

/// Strictly convex faces of more corners than this are triangulated by
/// [`halving`], not fanned: every triangle of a fan holds its first corner,
/// so their bounding boxes all overlap, and the crossing scan's broad phase
/// (`geometry::crossing`) tested every pair of a large fan and every pair of
/// it with the faces along the rim (`self_intersections` of
/// `conway("P8000")`'s two 8,000-gons took 3.9 s).
pub const HALVING_MIN: usize = 32;

/// Ears of every other corner, then of every other remaining corner, until
/// a triangle is left: triangles of ⌈log₂ n⌉ sizes, each spanning a run of
/// the boundary about as long as its size, so a triangle's box overlaps
/// O(log n) others of the face and O(1) of each level along the rim instead
/// of the whole fan (O(n log n) box pairs for the face, not n²/2).
/// Counter-clockwise like the cycle; on a strictly convex polygon every
/// triangle has positive area (corners of a strictly convex polygon are in
/// strictly convex position).
fn halving(n: usize, out: &mut Vec<[u32; 3]>) {
    out.clear();
    let mut ring: Vec<u32> = (0..n as u32).collect();
    let mut next = Vec::with_capacity(n / 2 + 2);
    while ring.len() > 3 {
        let m = ring.len();
        next.clear();
        let mut k = 0;
        while k + 2 < m {
            out.push([ring[k], ring[k + 1], ring[k + 2]]);
            next.push(ring[k]);
            k += 2;
        }
        // k is m − 2 (m even: the last corner stays) or m − 1 (m odd)
        next.extend_from_slice(&ring[k..]);
        std::mem::swap(&mut ring, &mut next);
    }
    out.push([ring[0], ring[1], ring[2]]);
}

/// Whether every corner of the projected polygon turns strictly left.
fn strictly_convex(p: &[DVec2]) -> bool {
    let n = p.len();
    (0..n).all(|i| cross2(p[i], p[(i + 1) % n], p[(i + 2) % n]) > 0.0)
}

/// Whether `t` (local indices) is a triangulation of the n-gon as a disk:
/// n − 2 triangles, every boundary edge once in its own direction, every
/// other edge once each way.
fn is_disk_triangulation(n: usize, t: &[[u32; 3]]) -> bool {
    if t.len() != n - 2 {
        return false;
    }
    let mut e: Vec<u64> = t.iter().flat_map(|t| (0..3).map(move |k| ((t[k] as u64) << 32) | t[(k + 1) % 3] as u64)).collect();
    e.sort_unstable();
    if e.windows(2).any(|w| w[0] == w[1]) {
        return false;
    }
    let mut boundary = 0;
    for &k in &e {
        let (i, j) = ((k >> 32) as usize, (k & 0xffff_ffff) as usize);
        if i >= n || j >= n || i == j {
            return false;
        }
        if j == (i + 1) % n {
            boundary += 1;
        } else if e.binary_search(&(((j as u64) << 32) | i as u64)).is_err() {
            return false;
        }
    }
    boundary == n
}

/// Ear clipping of a simple counter-clockwise polygon, O(n²); cuts the most
/// convex corner when no strict ear exists (degenerate input), so the result
/// is always a disk triangulation. The fallback for earcut's rare refusals.
fn ear_clip_quadratic(p: &[DVec2], out: &mut Vec<[u32; 3]>) {
    out.clear();
    let mut idx: Vec<usize> = (0..p.len()).collect();
    while idx.len() > 3 {
        let m = idx.len();
        let mut best: Option<(usize, f64)> = None;
        let mut ear = None;
        for i in 0..m {
            let (a, b, c) = (idx[(i + m - 1) % m], idx[i], idx[(i + 1) % m]);
            let turn = cross2(p[a], p[b], p[c]);
            if best.is_none_or(|(_, t)| turn > t) {
                best = Some((i, turn));
            }
            if turn <= 0.0 {
                continue;
            }
            let inside = idx.iter().any(|&k| {
                k != a && k != b && k != c && p[k] != p[a] && p[k] != p[b] && p[k] != p[c] && {
                    cross2(p[a], p[b], p[k]) >= 0.0 && cross2(p[b], p[c], p[k]) >= 0.0 && cross2(p[c], p[a], p[k]) >= 0.0
                }
            });
            if !inside {
                ear = Some(i);
                break;
            }
        }
        let i = ear.unwrap_or_else(|| best.unwrap().0);
        let (a, b, c) = (idx[(i + m - 1) % m], idx[i], idx[(i + 1) % m]);
        out.push([a as u32, b as u32, c as u32]);
        idx.remove(i);
    }
    out.push([idx[0] as u32, idx[1] as u32, idx[2] as u32]);
}

/// Ear clipping of a polygon star-shaped from the origin (every edge sees it
/// strictly on its left), in O(n) like a Graham scan: a convex corner whose
/// chord keeps the origin on its left is an ear, since the triangle lies in
/// the corner's angular sector, which holds no other corner, and what is left
/// stays star-shaped. Returns false (output unusable) if it gets stuck.
fn star_clip(p: &[DVec2], out: &mut Vec<[u32; 3]>) -> bool {
    let n = p.len();
    out.clear();
    let mut next: Vec<u32> = (0..n as u32).map(|i| ((i as usize + 1) % n) as u32).collect();
    let mut prev: Vec<u32> = (0..n as u32).map(|i| ((i as usize + n - 1) % n) as u32).collect();
    let (mut i, mut left, mut idle) = (0usize, n, 0usize);
    while left > 3 {
        let (a, c) = (prev[i] as usize, next[i] as usize);
        if cross2(p[a], p[i], p[c]) > 0.0 && cross2(p[a], p[c], DVec2::ZERO) >= 0.0 {
            out.push([a as u32, i as u32, c as u32]);
            next[a] = c as u32;
            prev[c] = a as u32;
            left -= 1;
            idle = 0;
            // the previous corner may have become an ear
            i = a;
        } else {
            i = c;
            idle += 1;
            if idle > left {
                return false;
            }
        }
    }
    let (a, c) = (prev[i], next[i]);
    out.push([a, i as u32, c]);
    true
}

/// A face of five or more corners that leave its Newell plane by more than this fraction of
/// their distance from its mean is fanned around its centroid: diagonals of
/// its projection can fold the surface through itself.
pub const BENT: f64 = 0.25;

/// Whether the face is bent (see [`BENT`]). Quads never are: either
/// diagonal makes a faithful two-triangle surface of a folded quad.
fn is_bent(cyc: &[u32], pos: &[DVec3]) -> bool {
    let n = cyc.len();
    if n < 5 {
        return false;
    }
    let at = |i: usize| pos[cyc[i] as usize];
    let (normal, c) = newell(cyc, pos);
    let Some(nz) = normal.try_normalize() else { return false };
    let (mut off, mut r) = (0.0f64, 0.0f64);
    for i in 0..n {
        let d = at(i) - c;
        off = off.max(d.dot(nz).abs());
        r = r.max(d.length());
    }
    off > BENT * r
}

/// Whether the projected polygon is star-shaped from the corners' mean (the
/// frame's origin).
fn star_from_mean(p: &[DVec2]) -> bool {
    let n = p.len();
    (0..n).all(|i| p[i].perp_dot(p[(i + 1) % n]) > 0.0)
}

/// The first choice for one face (local indices into its cycle, n ≥ 3).
fn first_choice(s: &mut Scratch, shape: Shape) {
    let n = s.cyc.len();
    if shape == Shape::Convex && n > HALVING_MIN && strictly_convex(&s.p) {
        halving(n, &mut s.local);
        return;
    }
    if n == 3 || shape != Shape::NonConvex || n > EARCUT_LIMIT {
        fan(n, 0, &mut s.local);
        return;
    }
    // earcut is quadratic on stars (long thin ears have large bounding
    // boxes); a face star-shaped from its mean is clipped in linear time
    if star_from_mean(&s.p) && star_clip(&s.p, &mut s.local) && is_disk_triangulation(n, &s.local) {
        return;
    }
    // and on noisy outlines and spirals: large faces take the monotone
    // partition, O(n log n), when it covers the face
    if n > MONOTONE_MIN && monotone::triangulate(&s.p, &mut s.local) && is_disk_triangulation(n, &s.local) && monotone::covers(&s.p, &s.local) {
        return;
    }
    // cancelled (the monotone sweep polls and gives up): not earcut, which
    // can be quadratic here; the caller checks before using the result
    if n > MONOTONE_MIN && crate::cancel::requested() {
        fan(n, 0, &mut s.local);
        return;
    }
    earcut_into(&mut s.ear, &mut s.ear_out, &s.p, &mut s.local);
    // earcut drops collinear and coincident corners: such output is no disk
    if !is_disk_triangulation(n, &s.local) {
        if n <= 4096 {
            ear_clip_quadratic(&s.p, &mut s.local);
        } else {
            fan(n, 0, &mut s.local);
        }
    }
}

/// earcut's triangles of the polygon `p`, in its orientation (unchecked).
fn earcut_into(ear: &mut earcut::Earcut<f64>, ear_out: &mut Vec<u32>, p: &[DVec2], out: &mut Vec<[u32; 3]>) {
    ear.earcut(p.iter().map(|q| q.to_array()), &[] as &[u32], ear_out);
    out.clear();
    out.extend(ear_out.chunks_exact(3).map(|t| [t[0], t[1], t[2]]));
    // earcut emits its own ring orientation: match the face's
    let reversed = out.iter().any(|t| (0..3).any(|k| t[k] == 1 && t[(k + 1) % 3] == 0));
    if reversed {
        out.iter_mut().for_each(|t| t.swap(1, 2));
    }
}

/// The copies of multi-edges after the first (lowest id) of each vertex
/// pair, in edge order. Each is split at its middle so that the triangle
/// mesh has one edge per vertex pair. Self-loops are left alone.
fn multi_edge_copies(m: &Mesh) -> Vec<u32> {
    // bucket the edges by their lower end (counting sort over the tail
    // column, read in order), then look for repeated upper ends per bucket
    let (_, vert, _) = m.halfedge_columns();
    let ends = |e: usize| {
        let (a, b) = (vert[2 * e], vert[2 * e + 1]);
        (a.min(b), a.max(b))
    };
    let nv = m.n_vertices();
    let mut start = vec![0u32; nv + 1];
    for e in 0..m.n_edges() {
        let (a, b) = ends(e);
        if a != b {
            start[a as usize + 1] += 1;
        }
    }
    for k in 0..nv {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut upper = vec![(0u32, 0u32); start[nv] as usize];
    for e in 0..m.n_edges() {
        let (a, b) = ends(e);
        if a != b {
            upper[fill[a as usize] as usize] = (b, e as u32);
            fill[a as usize] += 1;
        }
    }
    let mut copies = Vec::new();
    for v in 0..nv {
        let list = &mut upper[start[v] as usize..start[v + 1] as usize];
        if list.len() > 1 {
            list.sort_unstable();
            copies.extend(list.windows(2).filter(|w| w[0].0 == w[1].0).map(|w| w[1].1));
        }
    }
    copies.sort_unstable();
    copies
}

/// [`multi_edge_copies`] among the sides of the listed faces: the same
/// copies wherever every face around those sides' ends is listed.
fn multi_edge_copies_among(m: &Mesh, faces: &[u32]) -> Vec<u32> {
    let (_, vert, _) = m.halfedge_columns();
    let mut ends: Vec<(u32, u32, u32)> = faces
        .iter()
        .flat_map(|&f| m.face_halfedges(FaceId(f)))
        .map(|h| {
            let e = h.edge().idx();
            let (a, b) = (vert[2 * e], vert[2 * e + 1]);
            (a.min(b), a.max(b), e as u32)
        })
        .filter(|&(a, b, _)| a != b)
        .collect();
    ends.sort_unstable();
    ends.dedup();
    let mut copies: Vec<u32> = ends.windows(2).filter(|w| (w[0].0, w[0].1) == (w[1].0, w[1].1)).map(|w| w[1].2).collect();
    copies.sort_unstable();
    copies
}

/// The diagonal key that marks a bent face (no vertex pair has it).
const BENT_KEY: u64 = u64::MAX;

/// One block's first choices: triangles (global ids), their faces, and every
/// diagonal as (pair key, face).
type BlockOut = (Vec<[u32; 3]>, Vec<u32>, Vec<(u64, u32)>);

fn first_block(m: &Mesh, pos: &[DVec3], split: &[u32], faces: impl Iterator<Item = usize>) -> BlockOut {
    let mut s = Scratch::default();
    let (mut tris, mut tri_face, mut diags) = (Vec::new(), Vec::new(), Vec::new());
    for f in faces {
        if m.is_hole(FaceId(f as u32)) {
            continue;
        }
        face_cycle(m, FaceId(f as u32), split, &mut s.cyc);
        let n = s.cyc.len();
        if n < 3 {
            continue;
        }
        if n == 3 {
            tris.push([s.cyc[0], s.cyc[1], s.cyc[2]]);
            tri_face.push(f as u32);
            continue;
        }
        let shape = project(&s.cyc, pos, &mut s.p);
        first_choice(&mut s, shape);
        // bent faces are redone around their centroid (no diagonals)
        let bent = is_bent(&s.cyc, pos);
        if bent {
            diags.push((BENT_KEY, f as u32));
        }
        for t in &s.local {
            tris.push(t.map(|k| s.cyc[k as usize]));
            tri_face.push(f as u32);
            if bent {
                continue;
            }
            for k in 0..3 {
                let (i, j) = (t[k] as usize, t[(k + 1) % 3] as usize);
                if i < j && j != i + 1 && !(i == 0 && j == n - 1) {
                    diags.push((pair(s.cyc[i], s.cyc[j]), f as u32));
                }
            }
        }
    }
    (tris, tri_face, diags)
}

/// See the module docs.
///
/// Cancellable ([`crate::cancel`]): once cancellation is requested it returns
/// early with an incomplete triangulation, so a caller that may be cancelled
/// calls [`crate::cancel::check`] before using the result.
pub fn triangulate(m: &Mesh) -> Triangulation {
    triangulate_with(m, true, None)
}

/// The triangles of the listed faces only (ascending ids; holes skipped),
/// in time proportional to them: what a check after a local change needs
/// (`crossing::crossings_of_new_faces`). Each face is triangulated as in
/// [`triangulate`] with the collisions among the listed faces resolved, so
/// a face's triangles are those of the whole mesh's triangulation when
/// every face around its vertices is listed too (the faces that can share
/// a diagonal or a multi-edge with it), but for the order in which
/// colliding faces farther away were retried. Added points are numbered
/// from `n_vertices()` as in [`Triangulation`].
pub fn triangulate_faces(m: &Mesh, faces: &[u32]) -> Triangulation {
    debug_assert!(faces.windows(2).all(|w| w[0] < w[1]) && faces.last().is_none_or(|&f| (f as usize) < m.n_faces()));
    triangulate_with(m, true, Some(faces))
}

/// Marks in `near` every face around a vertex of `faces`: what
/// [`triangulate_faces`] is given besides a patch of faces so that it
/// triangulates them as [`triangulate`] does.
pub fn mark_faces_around(m: &Mesh, faces: impl IntoIterator<Item = FaceId>, near: &mut [bool]) {
    for f in faces {
        for h in m.face_halfedges(f) {
            let mut g = h;
            loop {
                near[m.face(g).idx()] = true;
                g = m.rotate(g);
                if g == h {
                    break;
                }
            }
        }
    }
}

/// [`triangulate`] (of the listed faces only, with `faces`), with the retry
/// pass grouped (parallel) or sequential.
fn triangulate_with(m: &Mesh, grouped: bool, faces: Option<&[u32]>) -> Triangulation {
    let nf = m.n_faces();
    let nv = m.n_vertices() as u32;
    // multi-edge copies get a point each: the first added points
    let copies = match faces {
        None => multi_edge_copies(m),
        Some(list) => multi_edge_copies_among(m, list),
    };
    let mut points: Vec<DVec3> = Vec::with_capacity(copies.len());
    let mut split = Vec::new();
    if !copies.is_empty() {
        split = vec![u32::MAX; m.n_edges()];
        for &e in &copies {
            split[e as usize] = nv + points.len() as u32;
            let h = EdgeId(e).halfedge();
            points.push((m.position(m.vertex(h)) + m.position(m.head(h))) / 2.0);
        }
    }
    let pos: std::borrow::Cow<[DVec3]> =
        if points.is_empty() { m.positions().into() } else { [m.positions(), &points[..]].concat().into() };
    let pos = &pos[..];
    let split = &split[..];
    let n_listed = faces.map_or(nf, <[u32]>::len);
    let blocks: Vec<BlockOut> = (0..n_listed.div_ceil(BLOCK))
        .into_par_iter()
        // cancelled: empty blocks, see `triangulate`'s docs
        .map(|b| {
            let r = b * BLOCK..n_listed.min((b + 1) * BLOCK);
            match faces {
                _ if crate::cancel::requested() => Default::default(),
                None => first_block(m, pos, split, r),
                Some(list) => first_block(m, pos, split, list[r].iter().map(|&f| f as usize)),
            }
        })
        .collect();
    let nt = blocks.iter().map(|b| b.0.len()).sum();
    let nd = blocks.iter().map(|b| b.2.len()).sum();
    let (mut tris, mut tri_face, mut diags) = (Vec::with_capacity(nt), Vec::with_capacity(nt), Vec::with_capacity(nd));
    for (t, f, d) in blocks {
        tris.extend(t);
        tri_face.extend(f);
        diags.extend(d);
    }

    // collisions: a diagonal that is a mesh edge, or that two faces chose
    let mut bad: Vec<u32> = diags
        .par_iter()
        .filter(|&&(k, _)| k == BENT_KEY || is_edge(m, (k >> 32) as u32, k as u32))
        .map(|&(_, f)| f)
        .collect();
    diags.par_sort_unstable();
    let mut i = 0;
    while i < diags.len() {
        let mut j = i + 1;
        while j < diags.len() && diags[j].0 == diags[i].0 {
            j += 1;
        }
        if j - i > 1 && diags[i].0 != BENT_KEY {
            bad.extend(diags[i..j].iter().map(|d| d.1));
        }
        i = j;
    }
    if bad.is_empty() || crate::cancel::requested() {
        return Triangulation { points, tris, tri_face };
    }
    bad.sort_unstable();
    bad.dedup();

    let base = nv + points.len() as u32;
    let (redone, added) = redo::redo(m, pos, split, &bad, &diags, base, grouped);
    drop(diags);
    points.extend(added);

    // splice the retried faces' triangles in, keeping face order
    let extra: usize = redone.iter().map(|r| r.1.len()).sum();
    let (mut t2, mut f2) = (Vec::with_capacity(tris.len() + extra), Vec::with_capacity(tris.len() + extra));
    let mut next = redone.into_iter().peekable();
    let mut k = 0;
    while k < tris.len() {
        let f = tri_face[k];
        let mut e = k + 1;
        while e < tris.len() && tri_face[e] == f {
            e += 1;
        }
        if next.peek().is_some_and(|r| r.0 == f) {
            let (_, t) = next.next().unwrap();
            f2.extend(std::iter::repeat(f).take(t.len()));
            t2.extend(t);
        } else {
            t2.extend_from_slice(&tris[k..e]);
            f2.extend_from_slice(&tri_face[k..e]);
        }
        k = e;
    }
    Triangulation { points, tris: t2, tri_face: f2 }
}

mod monotone;
mod plain;
mod redo;

#[cfg(test)]
mod tests;

//! Shared machinery of the smoothing and refinement schemes (CGAL's
//! Subdivision_method_3 calls the connectivity part a *refinement host*).
//!
//! Every scheme here builds its output in one pass: new points go into one
//! buffer laid out by index arithmetic (e.g. `[vertex points | edge points |
//! face points]`), the output faces and the twin of every output corner are
//! computed from the half-edge columns of the input, and
//! [`Mesh::from_corner_twins`] assembles the result; the primal host,
//! Doo-Sabin, the dual, simplest, closed √3, honeycomb, vertex truncation
//! and the fan triangulation go one step further and write the half-edge
//! columns themselves ([`Mesh::from_columns`], see `primal_columns.rs`,
//! `face_vertex_columns.rs`, `fan_columns.rs`). Nothing is ever paired by
//! vertex ids, so self-loops, multi-edges, one-gons, two-gons and repeated
//! vertices in a face are handled like any other element: a self-loop's two
//! sides are two half-edges with their own corners and new points.
//!
//! Point-spheres (a vertex with one face and no edge) carry through every
//! scheme unchanged ([`with_point_spheres`]). Hole faces (the boundary
//! loops of an open mesh) are kept: honeycomb and vertex truncation keep
//! them as holes, and the `*_level` functions of Catmull-Clark, Loop,
//! midpoint, dual, Doo-Sabin, √3 and simplest apply boundary rules (the
//! Python methods call those; the plain Rust `midpoint`, `dual`,
//! `doo_sabin`, `sqrt3` and `simplest` refuse holes: [`refuse_holes`]).

use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use glam::DVec3;
use rayon::prelude::*;

/// Fails when a scheme's output would need more corners (or vertices) than
/// 31-bit ids allow; schemes call it before any index arithmetic.
pub(crate) fn check_output_size(scheme: &str, n_corners: usize, n_vertices: usize) -> Result<()> {
    if n_corners > crate::mesh::MAX_ELEMENTS / 2 || n_vertices > crate::mesh::MAX_ELEMENTS {
        return Err(crate::error::MeshError::InvalidArgument(format!(
            "{scheme}: the output would have {n_corners} corners and {n_vertices} vertices, more than 31-bit ids allow"
        )));
    }
    Ok(())
}

/// A raw pointer shared by parallel writers of disjoint slots.
#[derive(Clone, Copy)]
pub(crate) struct SyncPtr<T>(pub *mut T);
unsafe impl<T> Send for SyncPtr<T> {}
unsafe impl<T> Sync for SyncPtr<T> {}
impl<T> SyncPtr<T> {
    #[inline]
    pub fn get(self) -> *mut T {
        self.0
    }
}

/// Below this many elements a parallel loop runs on one thread.
pub(crate) const MIN_LEN: usize = 2048;

/// `cos(2πk/n)`, from a table for n ≤ 16 (the same expression, so the
/// same bits): a cosine per stencil term was a sixth to an eighth of a
/// level with stencils (honeycomb, Doo-Sabin).
pub(crate) fn turn_cos(k: usize, n: usize) -> f64 {
    const TABLED: usize = 16;
    let of = |k: usize, n: usize| (std::f64::consts::TAU * k as f64 / n as f64).cos();
    static TABLE: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    if n <= TABLED && k < n {
        let t = TABLE.get_or_init(|| (1..=TABLED).flat_map(|n| (0..n).map(move |k| of(k, n))).collect());
        return t[n * (n - 1) / 2 + k];
    }
    of(k, n)
}

/// `(cos θ, sin θ)` for `θ = 2πk/n`, from a table for n ≤ 16 filled with
/// the same expression, so the same bits: honeycomb's positions spent a
/// fifth of a level in `sincos` (two calls per corner).
#[inline]
pub(crate) fn turn_cos_sin(k: usize, n: usize) -> (f64, f64) {
    const TABLED: usize = 16;
    #[inline]
    fn of(k: usize, n: usize) -> (f64, f64) {
        let th = std::f64::consts::TAU * k as f64 / n as f64;
        (th.cos(), th.sin())
    }
    static TABLE: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    if n <= TABLED && k < n {
        let t = TABLE.get_or_init(|| (1..=TABLED).flat_map(|n| (0..n).map(move |k| of(k, n))).collect());
        return t[n * (n - 1) / 2 + k];
    }
    of(k, n)
}

/// The corners of every face in cycle order, laid out face after face.
///
/// Built in O(H + F). A point-sphere face has no half-edge and owns no
/// corner here (`degree` 0).
pub(crate) struct FaceLayout {
    /// Half-edge of each corner: face `f` owns `fh[off[f]..off[f + 1]]`,
    /// starting at its first corner.
    pub fh: Vec<u32>,
    /// Prefix of face degrees.
    pub off: Vec<u32>,
    /// Inverse of `fh`: the corner index of each half-edge.
    pub cidx: Vec<u32>,
}

impl FaceLayout {
    /// Fails only when cancelled ([`crate::cancel`]), polled every 64 Ki faces.
    pub fn new(m: &Mesh) -> Result<Self> {
        let mut fh = Vec::with_capacity(m.n_halfedges());
        let (cidx, off) = Self::walk(m, |h| fh.push(h))?;
        Ok(FaceLayout { fh, off, cidx })
    }

    /// [`FaceLayout::new`]'s ranks and face starts alone (`cidx`, `off`),
    /// without the corner list: for fills that run over the half-edges.
    pub fn ranks(m: &Mesh) -> Result<(Vec<u32>, Vec<u32>)> {
        Self::walk(m, |_| ())
    }

    /// Every face cycle from its first corner, in face order: each corner's
    /// rank and each face's first, with `corner` called on every corner in
    /// that order.
    fn walk(m: &Mesh, mut corner: impl FnMut(u32)) -> Result<(Vec<u32>, Vec<u32>)> {
        let next = &m.he_next;
        let nf = m.n_faces();
        let mut off = Vec::with_capacity(nf + 1);
        let mut cidx = vec![0u32; m.n_halfedges()];
        let mut c = 0u32;
        for f in 0..nf {
            if f % 65536 == 0 {
                crate::cancel::check()?;
            }
            off.push(c);
            let s = m.f_start[f];
            if s & POINT != 0 {
                continue;
            }
            let mut h = s;
            loop {
                cidx[h as usize] = c;
                corner(h);
                c += 1;
                h = next[h as usize];
                if h == s {
                    break;
                }
            }
        }
        off.push(c);
        Ok((cidx, off))
    }

    /// The half-edges of face `f`'s corners, in cycle order.
    #[inline]
    pub fn corners(&self, f: usize) -> &[u32] {
        &self.fh[self.off[f] as usize..self.off[f + 1] as usize]
    }
    #[inline]
    pub fn degree(&self, f: usize) -> usize {
        (self.off[f + 1] - self.off[f]) as usize
    }
    /// Position of half-edge `h` in its face's cycle.
    #[inline]
    pub fn local(&self, h: u32, f: u32) -> usize {
        (self.cidx[h as usize] - self.off[f as usize]) as usize
    }
}

/// The outgoing half-edges of every vertex in rotation order
/// (`h, rotate(h), ...`, counter-clockwise seen from outside), vertex after vertex.
///
/// Built in O(H + V). A point-sphere vertex has no half-edge and owns no
/// slot here (`valence` 0).
pub(crate) struct VertexLayout {
    /// Prefix of valences: vertex `v` owns slots `off[v]..off[v + 1]`.
    pub off: Vec<u32>,
    /// Inverse: the rotation slot of each half-edge (index into the layout).
    pub vidx: Vec<u32>,
}

impl VertexLayout {
    /// Fails only when cancelled, polled every 64 Ki vertices.
    pub fn new(m: &Mesh) -> Result<Self> {
        let nv = m.n_vertices();
        let nh = m.n_halfedges();
        let mut off = Vec::with_capacity(nv + 1);
        let mut vidx = vec![0u32; nh];
        off.push(0u32);
        let mut k = 0u32;
        for v in 0..nv {
            crate::cancel::poll(v)?;
            let s = m.v_out[v];
            if s & POINT != 0 {
                off.push(k);
                continue;
            }
            let mut h = s;
            loop {
                vidx[h as usize] = k;
                k += 1;
                h = m.he_prev[h as usize] ^ 1;
                if h == s {
                    break;
                }
            }
            off.push(k);
        }
        Ok(VertexLayout { off, vidx })
    }

    /// Number of outgoing half-edges of `v` (0 for a point-sphere).
    #[inline]
    pub fn valence(&self, v: usize) -> u32 {
        self.off[v + 1] - self.off[v]
    }
}

/// The smoothing schemes whose `*_level` functions carry boundary rules
/// (the open-mesh issue); every other user of [`refuse_holes`] (TopMod's
/// remeshing menu, the extrusions, Conway's operators) has none.
const WITH_BOUNDARY_RULES: [&str; 9] = ["catmull_clark", "loop", "doo_sabin", "sqrt3", "simplest", "midpoint", "dual", "honeycomb", "vertex_truncation"];

/// Refuses a mesh with hole faces (boundary loops) in the plain closed-mesh
/// scheme functions, which would refine a hole like a real face and
/// silently close it. The message says where boundary rules are, if any:
/// in the smoothing schemes' `*_level` functions; the rest have none.
pub(crate) fn refuse_holes(scheme: &str, m: &Mesh) -> Result<()> {
    let holes = m.n_holes();
    if holes == 0 {
        return Ok(());
    }
    let (s, them) = if holes == 1 { ("", "it") } else { ("s", "them") };
    Err(crate::error::MeshError::Precondition(if WITH_BOUNDARY_RULES.contains(&scheme) {
        format!(
            "{scheme}: the mesh has {holes} boundary loop{s} (it is open); the plain {scheme} takes closed meshes only \
             and would fill {them}; its boundary rules are in {scheme}_level (which the Python methods call)"
        )
    } else {
        format!(
            "{scheme}: the mesh has {holes} boundary loop{s} (it is open); {scheme} takes closed meshes only: it has no \
             boundary rule and would refine each hole like a face, filling {them} (the smoothing schemes {} refine open meshes)",
            WITH_BOUNDARY_RULES.join(", ")
        )
    }))
}

/// Whether a composition's one-pass build applies to `m`: a closed mesh
/// with faces, no point-spheres, and no face parents being traced (those
/// take the composition, which records them step by step).
pub(crate) fn fusable(m: &Mesh) -> bool {
    m.n_faces() > 0 && m.n_holes() == 0 && m.v_out.iter().all(|&o| o & crate::mesh::POINT == 0) && !super::face_parents::recording()
}

/// Runs `scheme` on `m` with its point-spheres set aside, then appends them
/// unchanged (same position, one vertex and one face each). Meshes with hole
/// faces are refused ([`refuse_holes`]): the closed-mesh scheme functions (boundary rules are in their levels).
pub(crate) fn with_point_spheres(name: &str, m: &Mesh, scheme: impl Fn(&Mesh) -> Result<Mesh>) -> Result<Mesh> {
    refuse_holes(name, m)?;
    crate::cancel::check()?;
    let n_points = m.v_out.iter().filter(|&&o| o & POINT != 0).count();
    if n_points == 0 {
        return scheme(m);
    }
    // strip: renumber the other vertices and faces, half-edges keep their ids
    let mut vmap = vec![NONE; m.n_vertices()];
    let mut fmap = vec![NONE; m.n_faces()];
    let mut points = Vec::with_capacity(n_points);
    let mut rest = Mesh::new();
    for (v, &o) in m.v_out.iter().enumerate() {
        if o & POINT != 0 {
            points.push(m.pos[v]);
        } else {
            vmap[v] = rest.pos.len() as u32;
            rest.pos.push(m.pos[v]);
            rest.v_out.push(o);
        }
    }
    for (f, &s) in m.f_start.iter().enumerate() {
        if s & POINT == 0 {
            fmap[f] = rest.f_start.len() as u32;
            rest.f_start.push(s);
            rest.f_hole.push(false);
        }
    }
    crate::cancel::check()?;
    rest.he_next = m.he_next.clone();
    rest.he_prev = m.he_prev.clone();
    rest.he_vert = m.he_vert.iter().map(|&v| vmap[v as usize]).collect();
    rest.he_face = m.he_face.iter().map(|&f| fmap[f as usize]).collect();
    crate::cancel::check()?;
    let mark = super::face_parents::mark();
    let mut out = if rest.n_faces() == 0 { Mesh::new() } else { scheme(&rest)? };
    if super::face_parents::recording() {
        record_around_points(m, &rest, &vmap, &fmap, mark, out.n_vertices(), out.n_faces());
    }
    for p in points {
        let (v, f) = (out.pos.len() as u32, out.f_start.len() as u32);
        out.pos.push(p);
        out.v_out.push(POINT | f);
        out.f_start.push(POINT | v);
        out.f_hole.push(false);
    }
    Ok(out)
}

/// The face parents step of [`with_point_spheres`]: the steps `scheme`
/// recorded on `rest` since `mark`, composed, renumbered to `m`'s ids, with
/// the point-spheres (appended after `n_v` vertices and `n_f` faces) their
/// own origins.
fn record_around_points(m: &Mesh, rest: &Mesh, vmap: &[u32], fmap: &[u32], mark: usize, n_v: usize, n_f: usize) {
    use super::face_parents::{chain, record, take_since, Step, VERT};
    let steps = take_since(mark);
    let inner = if rest.n_faces() == 0 { Some(Step { in_v: 0, in_f: 0, face: vec![], vertex: vec![] }) } else { chain(steps) };
    let step = inner.filter(|s| s.in_v == rest.n_vertices() && s.in_f == rest.n_faces() && s.face.len() == n_f && s.vertex.len() == n_v).map(|s| {
        let mut vback = vec![0u32; rest.n_vertices()];
        for (v, &r) in vmap.iter().enumerate() {
            if r != NONE {
                vback[r as usize] = v as u32;
            }
        }
        let mut fback = vec![0u32; rest.n_faces()];
        for (f, &r) in fmap.iter().enumerate() {
            if r != NONE {
                fback[r as usize] = f as u32;
            }
        }
        let back = |x: u32| if x & VERT != 0 { VERT | vback[(x & !VERT) as usize] } else { fback[x as usize] };
        let mut face: Vec<u32> = s.face.iter().map(|&x| back(x)).collect();
        let mut vertex: Vec<u32> = s.vertex.iter().map(|&x| back(x)).collect();
        // appended in vertex order, as the caller appends them
        for (v, &o) in m.v_out.iter().enumerate() {
            if o & POINT != 0 {
                face.push(o & !POINT);
                vertex.push(VERT | v as u32);
            }
        }
        Step { in_v: m.n_vertices(), in_f: m.n_faces(), face, vertex }
    });
    record(step);
}

/// Mean of the corner positions of every face (a repeated vertex counts once
/// per corner).
pub(crate) fn face_centroids(m: &Mesh, fl: &FaceLayout, out: &mut [DVec3]) {
    let (_, vert, _) = m.halfedge_columns();
    out.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(f, c)| {
        // cancelled: leave the rest, callers poll right after
        if crate::cancel::requested() {
            return;
        }
        let hs = fl.corners(f);
        let s: DVec3 = hs.iter().map(|&h| m.pos[vert[h as usize] as usize]).sum();
        *c = s / hs.len() as f64;
    });
}

/// [`face_centroids`] without a [`FaceLayout`]: each face's cycle walked
/// through `next` from its first half-edge, the same sums in the same
/// order (so the same bits). Point-sphere faces are not allowed.
pub(crate) fn face_centroids_walk(m: &Mesh, out: &mut [DVec3]) {
    // SAFETY: only initialized values are written through the view
    face_centroids_into(m, unsafe { &mut *(out as *mut [DVec3] as *mut [std::mem::MaybeUninit<DVec3>]) });
}

/// [`face_centroids_walk`] into room not yet written
/// ([`crate::mesh::unfilled_points`]): every element is written unless
/// cancelled.
pub(crate) fn face_centroids_into(m: &Mesh, out: &mut [std::mem::MaybeUninit<DVec3>]) {
    out.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(f, c)| {
        // cancelled: leave the rest, callers poll right after
        if crate::cancel::requested() {
            return;
        }
        let (s, n) = face_vertex_sum(m, f);
        c.write(s / n as f64);
    });
}

/// The stencil terms of face `f`'s corner mean, scaled by `w`: each
/// corner's vertex with `w / n`, along the cycle from its first half-edge
/// (the order of a face layout's corners). Not for point-sphere faces.
#[inline]
pub(crate) fn face_mean_row(m: &Mesh, f: usize, w: f64, row: &mut super::stencil::Row) {
    let (next, vert, _) = m.halfedge_columns();
    let k = w / m.face_degree(crate::mesh::FaceId(f as u32)) as f64;
    let s = m.f_start[f];
    let mut h = s;
    loop {
        row.add(vert[h as usize], k);
        h = next[h as usize];
        if h == s {
            break;
        }
    }
}

/// The sum of face `f`'s vertex positions along its cycle from its first
/// half-edge, and its number of corners. Not for point-sphere faces.
#[inline]
pub(crate) fn face_vertex_sum(m: &Mesh, f: usize) -> (DVec3, usize) {
    let (next, vert, _) = m.halfedge_columns();
    let s0 = m.f_start[f];
    debug_assert!(s0 & POINT == 0, "face_vertex_sum: point-sphere face {f}");
    let (mut h, mut s, mut n) = (s0, DVec3::ZERO, 0usize);
    loop {
        s += m.pos[vert[h as usize] as usize];
        n += 1;
        h = next[h as usize];
        if h == s0 {
            break;
        }
    }
    (s, n)
}

/// Every face with other than three corners fanned into triangles around a
/// new vertex at its centroid (the "extended" triangle schemes' first step).
///
/// Triangles and hole faces are kept; an n-gon (n ≠ 3, one-gons and two-gons included)
/// becomes the n triangles `[tail(h), head(h), c]`, one per corner, so its
/// edges keep their twins and the n spokes are new edges. New vertices
/// follow the input ones, in face order. Returns `None` when every face is
/// already a triangle.
///
/// Counts: V' = V + F_≠3, E' = E + Σ_≠3 n, F' = F_3 + Σ_≠3 n.
/// Written straight into the mesh columns (`fan_columns.rs`).
pub(crate) fn fan_triangulate(m: &Mesh) -> Result<Option<Mesh>> {
    super::fan_columns::fan_columns(m)
}

/// `face_point` marker of a hole face in [`primal_host`].
pub(crate) const HOLE: u32 = NONE - 1;

/// Output connectivity of the primal splits with edge points.
///
/// Output vertices are laid out `[V vertex points | E edge points | face
/// points]`; `face_point[f]` is the index of face `f`'s point within the
/// face-point block, `NONE` if the face has none, or [`HOLE`] for a hole.
///
/// A face with a face point becomes n quads `[v, e(h), f, e(prev h)]`, one
/// per corner `h` (Catmull-Clark's host). A face without one must be a
/// triangle and becomes four: `[v, e(h), e(prev h)]` per corner and the
/// middle `[e(h0), e(h1), e(h2)]` (Loop's host). A hole face of n corners
/// stays one hole face of 2n corners `[v0, e(h0), v1, e(h1), …]`, so the
/// boundary stays open.
///
/// Returns the output mesh with the new points `pos` laid out as above.
pub(crate) fn primal_host(m: &Mesh, fl: &FaceLayout, face_point: &[u32], pos: Vec<DVec3>) -> Result<Mesh> {
    primal_host_sides(m, fl, face_point, pos, false).map(|r| r.0)
}

/// [`primal_host`] with the positions computed last, by `pos` (which must
/// return `n_points` points), after `fl`, `face_point` and the builder's
/// temporaries are freed: a lower peak (see
/// [`super::primal_columns::primal_columns_late`]), the same mesh.
pub(crate) fn primal_host_late(m: &Mesh, fl: FaceLayout, face_point: Vec<u32>, n_points: usize, pos: impl FnOnce() -> Result<Vec<DVec3>>) -> Result<Mesh> {
    super::primal_columns::primal_columns_late(m, fl, face_point, n_points, false, pos).map(|r| r.0)
}

/// [`primal_host`], and on request, per output edge, the input half-edge
/// `h` such that the edge is the child of edge `h >> 1` at the tail of `h`
/// (`NONE` for edges inside an input face).
///
/// Written straight into the mesh columns ([`super::primal_columns`]); the
/// corner-and-twin build below is kept for faces too large for its packed
/// ranks (and as the reference its tests compare with).
pub(crate) fn primal_host_sides(m: &Mesh, fl: &FaceLayout, face_point: &[u32], pos: Vec<DVec3>, want_sides: bool) -> Result<(Mesh, Option<Vec<u32>>)> {
    super::primal_columns::primal_columns(m, fl, face_point, pos, want_sides)
}

/// [`primal_host_sides`] through [`Mesh::from_corner_twins`].
pub(crate) fn primal_host_twins(m: &Mesh, fl: &FaceLayout, face_point: &[u32], pos: Vec<DVec3>, want_sides: bool) -> Result<(Mesh, Option<Vec<u32>>)> {
    let (next, vert, face) = m.halfedge_columns();
    let (nv, ne, nf) = (m.n_vertices() as u32, m.n_edges() as u32, m.n_faces());
    let prev = &m.he_prev;
    // output corner base per face
    let mut base = Vec::with_capacity(nf + 1);
    let mut b = 0u32;
    let mut n_out_faces = 0usize;
    for f in 0..nf {
        if f % 65536 == 0 {
            crate::cancel::check()?;
        }
        base.push(b);
        let n = fl.degree(f) as u32;
        if face_point[f] == NONE {
            debug_assert_eq!(n, 3);
            b += 12;
            n_out_faces += 4;
        } else if face_point[f] == HOLE {
            b += 2 * n;
            n_out_faces += 1;
        } else {
            b += 4 * n;
            n_out_faces += n as usize;
        }
    }
    base.push(b);
    crate::cancel::check()?;
    let nc = b as usize;
    // the output corners of the two outer sides at corner h: v -> e(h) and e(prev h) -> v
    let outer = |h: u32| -> (u32, u32) {
        let f = face[h as usize];
        let k = fl.local(h, f) as u32;
        let fp = face_point[f as usize];
        if fp == NONE {
            let c = base[f as usize] + 3 * k;
            (c, c + 2)
        } else if fp == HOLE {
            let n = fl.degree(f as usize) as u32;
            (base[f as usize] + 2 * k, base[f as usize] + (2 * k + 2 * n - 1) % (2 * n))
        } else {
            let c = base[f as usize] + 4 * k;
            (c, c + 3)
        }
    };
    let mut sizes = Vec::with_capacity(n_out_faces);
    let mut holes = Vec::new();
    for f in 0..nf {
        if f % 65536 == 0 {
            crate::cancel::check()?;
        }
        if face_point[f] == NONE {
            sizes.extend_from_slice(&[3, 3, 3, 3]);
        } else if face_point[f] == HOLE {
            holes.push(sizes.len());
            sizes.push(2 * fl.degree(f) as u32);
        } else {
            sizes.extend(std::iter::repeat(4).take(fl.degree(f)));
        }
    }
    crate::cancel::check()?;
    let mut cv = vec![0u32; nc];
    let mut tw = vec![0u32; nc];
    // per output corner: the input half-edge whose tail-end child its side is
    let mut side = if want_sides { vec![NONE; nc] } else { Vec::new() };
    let (pc, pt, ps) = (SyncPtr(cv.as_mut_ptr()), SyncPtr(tw.as_mut_ptr()), SyncPtr(side.as_mut_ptr()));
    (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each(|f| {
        // cancelled: skip the rest, the check after the loop reports it
        if crate::cancel::requested() {
            return;
        }
        let hs = fl.corners(f);
        let n = hs.len();
        let b = base[f] as usize;
        let len = (base[f + 1] - base[f]) as usize;
        // SAFETY: face f writes only its own range base[f]..base[f + 1].
        let (cv, tw) = unsafe { (std::slice::from_raw_parts_mut(pc.get().add(b), len), std::slice::from_raw_parts_mut(pt.get().add(b), len)) };
        let mut sd = if want_sides { Some(unsafe { std::slice::from_raw_parts_mut(ps.get().add(b), len) }) } else { None };
        if face_point[f] == NONE {
            for (k, &h) in hs.iter().enumerate() {
                let p = prev[h as usize];
                let c = 3 * k;
                cv[c] = vert[h as usize];
                cv[c + 1] = nv + (h >> 1);
                cv[c + 2] = nv + (p >> 1);
                tw[c] = outer(next[(h ^ 1) as usize]).1;
                tw[c + 1] = (b + 9 + (k + 2) % 3) as u32;
                tw[c + 2] = outer(p ^ 1).0;
                // middle triangle side e(h_k) -> e(h_k+1)
                cv[9 + k] = nv + (h >> 1);
                tw[9 + k] = (b + 3 * ((k + 1) % 3) + 1) as u32;
                if let Some(sd) = sd.as_mut() {
                    sd[c] = h;
                    sd[c + 2] = p ^ 1;
                }
            }
        } else if face_point[f] == HOLE {
            for (k, &h) in hs.iter().enumerate() {
                let c = 2 * k;
                cv[c] = vert[h as usize];
                cv[c + 1] = nv + (h >> 1);
                tw[c] = outer(next[(h ^ 1) as usize]).1;
                tw[c + 1] = outer(h ^ 1).0;
                if let Some(sd) = sd.as_mut() {
                    sd[c] = h;
                    sd[c + 1] = h ^ 1;
                }
            }
        } else {
            let fp = nv + ne + face_point[f];
            for (k, &h) in hs.iter().enumerate() {
                let p = prev[h as usize];
                let c = 4 * k;
                cv[c] = vert[h as usize];
                cv[c + 1] = nv + (h >> 1);
                cv[c + 2] = fp;
                cv[c + 3] = nv + (p >> 1);
                tw[c] = outer(next[(h ^ 1) as usize]).1;
                tw[c + 1] = (b + 4 * ((k + 1) % n) + 2) as u32;
                tw[c + 2] = (b + 4 * ((k + n - 1) % n) + 1) as u32;
                tw[c + 3] = outer(p ^ 1).0;
                if let Some(sd) = sd.as_mut() {
                    sd[c] = h;
                    sd[c + 3] = p ^ 1;
                }
            }
        }
    });
    crate::cancel::check()?;
    let mut out = Mesh::from_corner_twins(pos, &sizes, &cv, &tw)?;
    for f in holes {
        out.f_hole[f] = true;
    }
    let sides = if want_sides {
        // output half-edge of every corner: faces were built from their first corner, in order
        let ofl = FaceLayout::new(&out)?;
        let mut es = vec![NONE; out.n_edges()];
        for (c, &h) in ofl.fh.iter().enumerate() {
            if h & 1 == 0 {
                es[(h >> 1) as usize] = side[c];
            }
        }
        Some(es)
    } else {
        None
    };
    Ok((out, sides))
}

/// Sum of `pos[head(h)]` over the outgoing half-edges of `v` and their count.
#[inline]
pub(crate) fn neighbor_sum(m: &Mesh, v: usize) -> (DVec3, usize) {
    let (_, vert, _) = m.halfedge_columns();
    let s = m.v_out[v];
    let mut h = s;
    let mut sum = DVec3::ZERO;
    let mut n = 0;
    loop {
        sum += m.pos[vert[(h ^ 1) as usize] as usize];
        n += 1;
        h = m.he_prev[h as usize] ^ 1;
        if h == s {
            break;
        }
    }
    (sum, n)
}

#[cfg(test)]
#[path = "hosts_test_meshes.rs"]
pub(crate) mod test_meshes;

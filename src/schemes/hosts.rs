//! Shared machinery of the smoothing and refinement schemes (CGAL's
//! Subdivision_method_3 calls the connectivity part a *refinement host*).
//!
//! Every scheme here builds its output in one pass: new points go into one
//! buffer laid out by index arithmetic (e.g. `[vertex points | edge points |
//! face points]`), the output faces and the twin of every output corner are
//! computed from the half-edge columns of the input, and
//! [`Mesh::from_corner_twins`] assembles the result. Nothing is ever paired by
//! vertex ids, so self-loops, multi-edges, one-gons, two-gons and repeated
//! vertices in a face are handled like any other element: a self-loop's two
//! sides are two half-edges with their own corners and new points.
//!
//! Point-spheres (a vertex with one face and no edge) carry through every
//! scheme unchanged ([`with_point_spheres`]). Hole faces (from
//! `close_boundaries`) are refused by the schemes without boundary rules
//! ([`refuse_holes`]) instead of being refined into real faces; honeycomb
//! and vertex truncation keep them as holes.

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
        let (next, _, _) = m.halfedge_columns();
        let nf = m.n_faces();
        let nh = m.n_halfedges();
        let mut fh = Vec::with_capacity(nh);
        let mut off = Vec::with_capacity(nf + 1);
        let mut cidx = vec![0u32; nh];
        off.push(0u32);
        for f in 0..nf {
            if f % 65536 == 0 {
                crate::cancel::check()?;
            }
            let s = m.f_start[f];
            if s & POINT != 0 {
                off.push(fh.len() as u32);
                continue;
            }
            let mut h = s;
            loop {
                cidx[h as usize] = fh.len() as u32;
                fh.push(h);
                h = next[h as usize];
                if h == s {
                    break;
                }
            }
            off.push(fh.len() as u32);
        }
        Ok(FaceLayout { fh, off, cidx })
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

/// Output faces of the schemes that keep every old face as one new face (in
/// old face order) and add one face per vertex after them (in old vertex
/// order): honeycomb and vertex truncation. Point-spheres are carried
/// through (a point-sphere face keeps its one corner), and so are hole marks.
pub(crate) struct FaceThenVertexFaces {
    /// Sizes of the output faces.
    pub sizes: Vec<u32>,
    /// `off[f]` is the first output corner of old face `f`'s image;
    /// `off[nf]` the first corner of the vertex faces.
    pub off: Vec<u32>,
    /// The output vertex of each point-sphere vertex (`NONE` for the others).
    point_id: Vec<u32>,
}

impl FaceThenVertexFaces {
    /// Old face `f` gets `per_corner · degree(f)` corners, vertex `v`
    /// `per_slot · valence(v)`. Appends the point-sphere vertices to `pos`,
    /// in vertex order. Fails only when cancelled.
    pub fn new(m: &Mesh, fl: &FaceLayout, vl: &VertexLayout, per_corner: u32, per_slot: u32, pos: &mut Vec<DVec3>) -> Result<Self> {
        let (nf, nv) = (m.n_faces(), m.n_vertices());
        let mut point_id = vec![NONE; nv];
        let n_points = m.v_out.iter().filter(|&&o| o & POINT != 0).count();
        if n_points > 0 {
            pos.reserve_exact(n_points);
            for v in 0..nv {
                if m.v_out[v] & POINT != 0 {
                    point_id[v] = pos.len() as u32;
                    pos.push(m.pos[v]);
                }
            }
        }
        let mut sizes: Vec<u32> = Vec::with_capacity(nf + nv);
        let mut off: Vec<u32> = Vec::with_capacity(nf + 1);
        off.push(0);
        for f in 0..nf {
            crate::cancel::poll(f)?;
            let d = (per_corner * fl.degree(f) as u32).max(1); // a point-sphere face keeps its one corner
            sizes.push(d);
            off.push(off[f] + d);
        }
        for v in 0..nv {
            crate::cancel::poll(v)?;
            let k = vl.valence(v);
            if k > 0 {
                sizes.push(per_slot * k);
            }
        }
        Ok(FaceThenVertexFaces { sizes, off, point_id })
    }

    /// The first corner of the vertex faces.
    #[inline]
    pub fn vertex_base(&self) -> u32 {
        self.off[self.off.len() - 1]
    }

    /// Fills the corners of the point-sphere faces, builds the mesh and
    /// copies the hole marks of the old faces to their images.
    pub fn build(&self, m: &Mesh, pos: Vec<DVec3>, mut cv: Vec<u32>, tw: &[u32]) -> Result<Mesh> {
        for (f, &s) in m.f_start.iter().enumerate() {
            if s & POINT != 0 {
                cv[self.off[f] as usize] = self.point_id[(s & !POINT) as usize];
            }
        }
        let mut out = Mesh::from_corner_twins(pos, &self.sizes, &cv, tw)?;
        out.f_hole[..m.n_faces()].copy_from_slice(&m.f_hole);
        Ok(out)
    }
}

/// Refuses a mesh with hole faces (boundary loops capped by
/// `close_boundaries`): a scheme without boundary rules would refine the cap
/// like a real face and silently close the hole.
pub(crate) fn refuse_holes(scheme: &str, m: &Mesh) -> Result<()> {
    let holes = m.n_holes();
    if holes == 0 {
        return Ok(());
    }
    Err(crate::error::MeshError::Precondition(format!(
        "{scheme}: the mesh has {holes} boundary loop{} (hole faces from close_boundaries); {scheme} has no boundary rules \
         and would fill {}, so it refuses open meshes (honeycomb and vertex_truncation keep holes open)",
        if holes == 1 { "" } else { "s" },
        if holes == 1 { "it" } else { "them" }
    )))
}

/// Runs `scheme` on `m` with its point-spheres set aside, then appends them
/// unchanged (same position, one vertex and one face each). Meshes with hole
/// faces are refused ([`refuse_holes`]): these schemes have no boundary rules.
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
    let mut out = if rest.n_faces() == 0 { Mesh::new() } else { scheme(&rest)? };
    for p in points {
        let (v, f) = (out.pos.len() as u32, out.f_start.len() as u32);
        out.pos.push(p);
        out.v_out.push(POINT | f);
        out.f_start.push(POINT | v);
        out.f_hole.push(false);
    }
    Ok(out)
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

/// Every face with other than three corners fanned into triangles around a
/// new vertex at its centroid (the "extended" triangle schemes' first step).
///
/// Triangles are kept; an n-gon (n ≠ 3, one-gons and two-gons included)
/// becomes the n triangles `[tail(h), head(h), c]`, one per corner, so its
/// edges keep their twins and the n spokes are new edges. New vertices
/// follow the input ones, in face order. Returns `None` when every face is
/// already a triangle.
///
/// Counts: V' = V + F_≠3, E' = E + Σ_≠3 n, F' = F_3 + Σ_≠3 n.
pub(crate) fn fan_triangulate(m: &Mesh) -> Result<Option<Mesh>> {
    let nf = m.n_faces();
    let (next, _, _) = m.halfedge_columns();
    let all_triangles = m.f_start.par_iter().with_min_len(MIN_LEN).all(|&s| {
        let h1 = next[s as usize];
        let h2 = next[h1 as usize];
        h1 != s && h2 != s && next[h2 as usize] == s
    });
    if all_triangles {
        return Ok(None);
    }
    check_output_size("loop", 3 * m.n_halfedges(), m.n_vertices() + nf)?;
    let fl = FaceLayout::new(m)?;
    let (next, vert, face) = m.halfedge_columns();
    let nv = m.n_vertices();
    // output corner base per face and centroid vertex per n-gon
    let mut base = Vec::with_capacity(nf + 1);
    let mut cvert = vec![NONE; nf];
    let mut pos = m.pos.clone();
    let mut n_faces = 0usize;
    let mut b = 0u32;
    for f in 0..nf {
        if f % 65536 == 0 {
            crate::cancel::check()?;
        }
        base.push(b);
        let n = fl.degree(f);
        if n == 3 {
            b += 3;
            n_faces += 1;
        } else {
            b += 3 * n as u32;
            n_faces += n;
            cvert[f] = pos.len() as u32;
            let hs = fl.corners(f);
            let s: DVec3 = hs.iter().map(|&h| m.pos[vert[h as usize] as usize]).sum();
            pos.push(s / n as f64);
        }
    }
    let nc = b as usize;
    debug_assert!(pos.len() >= nv);
    let mut sizes = Vec::with_capacity(n_faces);
    let mut cv = vec![0u32; nc];
    let mut tw = vec![0u32; nc];
    // the output corner of the side along input half-edge h
    let side = |h: u32| -> u32 {
        let f = face[h as usize];
        let k = fl.local(h, f) as u32;
        if cvert[f as usize] == NONE {
            base[f as usize] + k
        } else {
            base[f as usize] + 3 * k
        }
    };
    for f in 0..nf {
        let hs = fl.corners(f);
        let b = base[f] as usize;
        if cvert[f] == NONE {
            sizes.push(3);
            for (k, &h) in hs.iter().enumerate() {
                cv[b + k] = vert[h as usize];
                tw[b + k] = side(h ^ 1);
            }
        } else {
            let n = hs.len();
            for (k, &h) in hs.iter().enumerate() {
                sizes.push(3);
                let c = b + 3 * k;
                cv[c] = vert[h as usize];
                cv[c + 1] = vert[next[h as usize] as usize];
                cv[c + 2] = cvert[f];
                tw[c] = side(h ^ 1);
                // spoke head(h) -> centroid pairs with centroid -> tail(next h)
                tw[c + 1] = (b + 3 * ((k + 1) % n) + 2) as u32;
                tw[c + 2] = (b + 3 * ((k + n - 1) % n) + 1) as u32;
            }
        }
    }
    Mesh::from_corner_twins(pos, &sizes, &cv, &tw).map(Some)
}

/// Output connectivity of the primal splits with edge points.
///
/// Output vertices are laid out `[V vertex points | E edge points | face
/// points]`; `face_point[f]` is the index of face `f`'s point within the
/// face-point block, or `NONE` if the face has none.
///
/// A face with a face point becomes n quads `[v, e(h), f, e(prev h)]`, one
/// per corner `h` (Catmull-Clark's host). A face without one must be a
/// triangle and becomes four: `[v, e(h), e(prev h)]` per corner and the
/// middle `[e(h0), e(h1), e(h2)]` (Loop's host).
///
/// Returns the output mesh with the new points `pos` laid out as above.
pub(crate) fn primal_host(m: &Mesh, fl: &FaceLayout, face_point: &[u32], pos: Vec<DVec3>) -> Result<Mesh> {
    let (next, vert, face) = m.halfedge_columns();
    let (nv, ne, nf) = (m.n_vertices() as u32, m.n_edges() as u32, m.n_faces());
    let prev = &m.he_prev;
    // output corner base per face
    let mut base = Vec::with_capacity(nf);
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
        } else {
            b += 4 * n;
            n_out_faces += n as usize;
        }
    }
    crate::cancel::check()?;
    let nc = b as usize;
    // the output corners of the two outer sides at corner h: v -> e(h) and e(prev h) -> v
    let outer = |h: u32| -> (u32, u32) {
        let f = face[h as usize];
        let k = fl.local(h, f) as u32;
        if face_point[f as usize] == NONE {
            let c = base[f as usize] + 3 * k;
            (c, c + 2)
        } else {
            let c = base[f as usize] + 4 * k;
            (c, c + 3)
        }
    };
    let mut sizes = Vec::with_capacity(n_out_faces);
    for f in 0..nf {
        if f % 65536 == 0 {
            crate::cancel::check()?;
        }
        if face_point[f] == NONE {
            sizes.extend_from_slice(&[3, 3, 3, 3]);
        } else {
            sizes.extend(std::iter::repeat(4).take(fl.degree(f)));
        }
    }
    crate::cancel::check()?;
    let mut cv = vec![0u32; nc];
    let mut tw = vec![0u32; nc];
    let (pc, pt) = (SyncPtr(cv.as_mut_ptr()), SyncPtr(tw.as_mut_ptr()));
    (0..nf).into_par_iter().with_min_len(MIN_LEN).for_each(|f| {
        // cancelled: skip the rest, the check after the loop reports it
        if crate::cancel::requested() {
            return;
        }
        let hs = fl.corners(f);
        let n = hs.len();
        let b = base[f] as usize;
        // SAFETY: face f writes only its own range base[f]..base[f + 1].
        let (cv, tw) = unsafe {
            let len = if face_point[f] == NONE { 12 } else { 4 * n };
            (
                std::slice::from_raw_parts_mut(pc.get().add(b), len),
                std::slice::from_raw_parts_mut(pt.get().add(b), len),
            )
        };
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
            }
        }
    });
    crate::cancel::check()?;
    Mesh::from_corner_twins(pos, &sizes, &cv, &tw)
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
pub(crate) mod test_meshes {
    //! The corpus every scheme's unit tests run over.

    /// Schemes without boundary rules refuse a capped hole instead of
    /// refining the cap into a real face (the hole would close silently).
    #[test]
    fn schemes_without_boundary_rules_refuse_holes() {
        use crate::error::MeshError;
        use crate::schemes::*;
        let open = cube_with_hole();
        let o = menger::MengerOptions::default();
        let runs: [(&str, crate::error::Result<Mesh>); 9] = [
            ("catmull_clark", catmull_clark::catmull_clark(&open)),
            ("doo_sabin", doo_sabin::doo_sabin(&open)),
            ("dual", dual::dual(&open)),
            ("loop", loop_subdivision::loop_subdivision(&open)),
            ("midpoint", midpoint::midpoint(&open)),
            ("simplest", simplest::simplest(&open)),
            ("sqrt3", sqrt3::sqrt3(&open)),
            ("sierpinski", sierpinski::sierpinski(&open)),
            ("menger", menger::menger(&open, &o)),
        ];
        for (name, r) in runs {
            match r {
                Err(MeshError::Precondition(msg)) => assert!(msg.starts_with(name) && msg.contains("1 boundary loop"), "{msg}"),
                other => panic!("{name} on an open cube: {other:?}"),
            }
        }
        // the closed cube still goes through
        assert!(catmull_clark::catmull_clark(&primitives::cube()).is_ok());
    }

    #[test]
    fn sierpinski_counts() {
        let s = sierpinski_tetrahedron();
        s.validate().unwrap();
        assert_eq!((s.n_vertices(), s.n_edges(), s.n_faces(), s.genus(), s.n_self_loops()), (10, 30, 16, 3, 6));
    }
    use crate::mesh::{BuildOptions, Corner, Mesh};
    use crate::primitives;
    use crate::FaceId;
    use glam::DVec3;

    /// A cube with a self-loop splitting one face into a one-gon and a
    /// 5-corner face (the loop's vertex repeated in it).
    pub fn cube_with_self_loop() -> Mesh {
        let mut m = primitives::cube();
        let c = m.corner(FaceId(0), 0).unwrap();
        m.insert_edge(c, c).unwrap();
        m
    }
    /// A cube with a second edge beside an existing one (a multi-edge),
    /// splitting a two-gon off a face.
    pub fn cube_with_two_gon() -> Mesh {
        let mut m = primitives::cube();
        // corners 0 and 1 of face 0 are joined by an edge already; a second
        // edge between them splits off a two-gon.
        let c0 = m.corner(FaceId(0), 0).unwrap();
        let c1 = m.corner(FaceId(0), 1).unwrap();
        m.insert_edge(c0, c1).unwrap();
        m
    }
    /// Self-loop joining two different faces at one vertex (Sierpinski's
    /// kind): merges them, genus +1.
    pub fn cube_with_handle_loop() -> Mesh {
        let mut m = primitives::cube();
        let v = m.corner_vertex(m.corner(FaceId(0), 0).unwrap());
        // another face around the same vertex
        let mut other = None;
        for f in m.faces() {
            if f == FaceId(0) {
                continue;
            }
            for (k, x) in m.face_vertices(f).enumerate() {
                if x == v && other.is_none() {
                    other = Some((f, k));
                }
            }
        }
        let (f, k) = other.unwrap();
        let c0 = m.corner(FaceId(0), 0).unwrap();
        let c1 = m.corner(f, k).unwrap();
        m.insert_edge(c0, c1).unwrap();
        m
    }
    pub fn with_point_sphere() -> Mesh {
        let mut m = primitives::tetrahedron();
        m.create_vertex(DVec3::new(5.0, 0.0, 0.0)).unwrap();
        m
    }
    /// Level 1 of the Sierpinski paper's scheme on a tetrahedron: four corner
    /// tetrahedra whose back faces are hexagons `[x, x, y, y, z, z]` with a
    /// zero-length self-loop at every edge midpoint; each loop joins the back
    /// faces of two corner pyramids. V = 10, E = 30, F = 16, genus 3.
    pub fn sierpinski_tetrahedron() -> Mesh {
        let t = primitives::tetrahedron();
        let tp = t.positions().to_vec();
        let mut pos = tp.clone();
        let mut mid = std::collections::HashMap::new();
        let mut m = |a: u32, b: u32, pos: &mut Vec<DVec3>| -> i64 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                pos.push((tp[a as usize] + tp[b as usize]) * 0.5);
                pos.len() as i64 - 1
            })
        };
        let (mut sizes, mut idx) = (Vec::new(), Vec::new());
        for f in t.faces() {
            let v: Vec<u32> = t.face_vertices(f).map(|x| x.0).collect();
            let (a, b, c) = (v[0], v[1], v[2]);
            let (ab, bc, ca) = (m(a, b, &mut pos), m(b, c, &mut pos), m(c, a, &mut pos));
            idx.extend([a as i64, ab, ca, b as i64, bc, ab, c as i64, ca, bc]);
            sizes.extend([3, 3, 3]);
        }
        for a in 0..4u32 {
            let o: Vec<i64> = (0..4u32).filter(|&o| o != a).map(|o| m(a, o, &mut pos)).collect();
            let (x, mut y, mut z) = (o[0], o[1], o[2]);
            let n = (pos[y as usize] - pos[x as usize]).cross(pos[z as usize] - pos[x as usize]);
            if n.dot(pos[x as usize] - tp[a as usize]) < 0.0 {
                std::mem::swap(&mut y, &mut z);
            }
            idx.extend([x, x, y, y, z, z]);
            sizes.push(6);
        }
        Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap()
    }

    pub fn corpus() -> Vec<(&'static str, Mesh)> {
        vec![
            ("tetrahedron", primitives::tetrahedron()),
            ("cube", primitives::cube()),
            ("octahedron", primitives::octahedron()),
            ("dodecahedron", primitives::dodecahedron()),
            ("icosahedron", primitives::icosahedron()),
            ("torus", primitives::torus(8, 5, 1.0, 0.4).unwrap()),
            ("genus3", primitives::genus_surface(3).unwrap()),
            ("self_loop", cube_with_self_loop()),
            ("two_gon", cube_with_two_gon()),
            ("handle_loop", cube_with_handle_loop()),
            ("point_sphere", with_point_sphere()),
            ("sierpinski", sierpinski_tetrahedron()),
        ]
    }

    /// The degree of every face, in face order.
    pub fn face_sizes(m: &Mesh) -> Vec<usize> {
        m.faces().map(|f| m.face_degree(f)).collect()
    }
    pub fn n_point_spheres(m: &Mesh) -> usize {
        m.vertices().filter(|&v| m.point_sphere_face(v).is_some()).count()
    }

    /// Whether every face of `m` other than a one-gon has `n` corners.
    pub fn all_faces_but_one_gons_have(m: &Mesh, n: usize) -> bool {
        face_sizes(m).iter().filter(|&&s| s != 1).all(|&s| s == n)
    }

    /// The checks every scheme's output `r` of input `m` must pass: it
    /// validates, keeps the point-spheres, the genus and the number of
    /// components, and has `(V', E', F')` = `want` with the point-spheres left
    /// out of V' and F'.
    pub fn check_output(name: &str, m: &Mesh, r: &Mesh, want: (usize, usize, usize)) {
        let ps = n_point_spheres(m);
        r.validate().unwrap_or_else(|err| panic!("{name}: {err}"));
        assert_eq!(n_point_spheres(r), ps, "{name} point-spheres");
        assert_eq!(r.n_vertices() - ps, want.0, "{name} V'");
        assert_eq!(r.n_edges(), want.1, "{name} E'");
        assert_eq!(r.n_faces() - ps, want.2, "{name} F'");
        assert_eq!(r.genus(), m.genus(), "{name} genus");
        assert_eq!(r.n_components(), m.n_components(), "{name} components");
    }

    /// Runs `scheme` on every mesh of the [`corpus`] and makes the checks of
    /// [`check_output`], with the counts `counts(m, (V, E, F))` from the
    /// input's `V`, `E`, `F` (point-spheres left out), then the scheme's own
    /// checks `more(name, m, r)`.
    pub fn check_on_corpus(
        scheme: impl Fn(&Mesh) -> crate::error::Result<Mesh>,
        counts: impl Fn(&Mesh, (usize, usize, usize)) -> (usize, usize, usize),
        more: impl Fn(&str, &Mesh, &Mesh),
    ) {
        for (name, m) in corpus() {
            let ps = n_point_spheres(&m);
            let want = counts(&m, (m.n_vertices() - ps, m.n_edges(), m.n_faces() - ps));
            let r = scheme(&m).unwrap_or_else(|err| panic!("{name}: {err}"));
            check_output(name, &m, &r, want);
            more(name, &m, &r);
        }
    }

    /// A cube without its first face, closed by a hole face.
    pub fn cube_with_hole() -> Mesh {
        let c = primitives::cube().to_polygons();
        let sizes: Vec<i64> = c.sizes[1..].iter().map(|&s| s as i64).collect();
        let idx: Vec<i64> = c.indices[4..].iter().map(|&s| s as i64).collect();
        let opts = BuildOptions { close_boundaries: true, ..Default::default() };
        Mesh::from_polygons(primitives::cube().positions().to_vec(), &sizes, &idx, opts).unwrap()
    }

    /// A cube whose faces 0 and 1 are merged by InsertEdge (genus 1): the
    /// merged face runs along both sides of the new edge.
    pub fn handle_cube() -> Mesh {
        let mut m = crate::primitives::cube();
        let a = m.face_halfedge(FaceId(0)).unwrap();
        let b = m.face_halfedge(FaceId(1)).unwrap();
        m.insert_edge(Corner::Halfedge(a), Corner::Halfedge(b)).unwrap();
        assert_eq!(m.genus(), 1);
        m
    }

    /// A prism over a counter-clockwise simple polygon (may be non-convex):
    /// planar faces, every vertex 3-valent.
    pub fn prism(profile: &[[f64; 2]], height: f64) -> Mesh {
        let n = profile.len() as i64;
        let mut pos: Vec<DVec3> = profile.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect();
        pos.extend(profile.iter().map(|p| DVec3::new(p[0], p[1], height)));
        let mut sizes = vec![n, n];
        let mut idx: Vec<i64> = (0..n).rev().collect();
        idx.extend(n..2 * n);
        for i in 0..n {
            let j = (i + 1) % n;
            sizes.push(4);
            idx.extend([i, j, n + j, n + i]);
        }
        Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap()
    }

    /// A five-pointed star prism (non-convex planar faces).
    pub fn star_prism() -> Mesh {
        let pts: Vec<[f64; 2]> = (0..10)
            .map(|k| {
                let r = if k % 2 == 0 { 1.0 } else { 0.4 };
                let a = std::f64::consts::PI * k as f64 / 5.0;
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        prism(&pts, 0.5)
    }

    pub fn counts(m: &Mesh) -> (usize, usize, usize) {
        (m.n_vertices(), m.n_edges(), m.n_faces())
    }

    /// A cube with a self-loop (a one-gon inside a quad, made by InsertEdge
    /// on one corner twice) and a two-gon (an edge doubling a cube edge).
    pub fn one_gon_two_gon_cube() -> Mesh {
        let mut m = crate::primitives::cube();
        let h = m.face_halfedge(FaceId(0)).unwrap();
        m.insert_edge(Corner::Halfedge(h), Corner::Halfedge(h)).unwrap();
        let g = m.face_halfedge(FaceId(3)).unwrap();
        let g2 = m.next(g);
        m.insert_edge(Corner::Halfedge(g), Corner::Halfedge(g2)).unwrap();
        m.validate().unwrap();
        assert_eq!(m.n_self_loops(), 1);
        let hist = m.face_size_histogram();
        assert_eq!(hist.get(&1), Some(&1));
        assert_eq!(hist.get(&2), Some(&1));
        m
    }
}



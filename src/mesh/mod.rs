//! The topological mesh: a closed, orientable 2-manifold polygon mesh stored as
//! half-edges in struct-of-arrays columns.
//!
//! This is the DLFL of the high-genus dissertation (ch. II.5) in half-edge form:
//! a *corner* `{v, f}` is the half-edge leaving `v` inside face `f` (the corner
//! at its tail), so the corners of a face are its half-edges in cycle order and
//! an edge joins the two corners where its half-edges start.
//!
//! Legal here, unlike most half-edge libraries: self-loops, several edges
//! between the same two vertices, two-gons, one-gons (a face bounded by one
//! self-loop), a vertex repeated in one face, and point-spheres (one vertex,
//! one face, no edge). See `docs/internals.md` for the encoding and every
//! invariant that [`Mesh::validate`] checks.
//!
//! The structure knows nothing about any scheme; schemes live in
//! `crate::schemes` and build new meshes with [`Mesh::from_corner_twins`], or
//! fill the columns themselves and hand them to [`Mesh::from_columns`].

pub mod build;
mod boundary;
mod direct;
mod populate;
mod euler;
mod batch;
mod export;
mod twins;
mod query;
mod validate;

pub use build::{BuildOptions, PolygonFaces};
pub use direct::{unfilled_points, written, zeroed_points, Columns};
pub use populate::{populate, populate_on, set_populate};
pub use euler::Corner;
pub use query::Histogram;

pub(crate) use glam::DVec3;

macro_rules! id_type {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        #[repr(transparent)]
        pub struct $name(pub u32);
        impl $name {
            #[inline]
            pub fn idx(self) -> usize {
                self.0 as usize
            }
            #[inline]
            pub fn new(i: usize) -> Self {
                debug_assert!(i < NONE as usize);
                Self(i as u32)
            }
        }
    };
}

id_type!(
    /// A vertex: a point and the corners that refer to it.
    VertexId
);
id_type!(
    /// A half-edge, equivalently the corner at its tail. `twin(h) = h ^ 1`.
    HalfedgeId
);
id_type!(
    /// An edge: half-edges `2e` and `2e + 1`.
    EdgeId
);
id_type!(
    /// A face: a cyclic sequence of corners.
    FaceId
);

impl HalfedgeId {
    #[inline]
    pub fn twin(self) -> HalfedgeId {
        HalfedgeId(self.0 ^ 1)
    }
    #[inline]
    pub fn edge(self) -> EdgeId {
        EdgeId(self.0 >> 1)
    }
}

impl EdgeId {
    /// The half-edge `2e`; its twin is `2e + 1`.
    #[inline]
    pub fn halfedge(self) -> HalfedgeId {
        HalfedgeId(self.0 << 1)
    }
}

/// Internal "no element" sentinel; never returned through the public API.
pub(crate) const NONE: u32 = u32::MAX;
/// Flag in `v_out` / `f_start` marking a point-sphere: the low bits then hold
/// the face (in `v_out`) or the vertex (in `f_start`) of the point-sphere.
pub(crate) const POINT: u32 = 1 << 31;
/// Largest number of elements of one kind (ids use 31 bits, see [`POINT`]).
pub const MAX_ELEMENTS: usize = (POINT - 1) as usize;

/// A closed, orientable 2-manifold polygon mesh. See the module docs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    // --- vertices
    pub(crate) pos: Vec<DVec3>,
    /// An outgoing half-edge, or `POINT | face` for a point-sphere vertex.
    pub(crate) v_out: Vec<u32>,
    // --- half-edges (corners); twin(h) = h ^ 1
    pub(crate) he_next: Vec<u32>,
    pub(crate) he_prev: Vec<u32>,
    /// Tail vertex: the vertex of the corner.
    pub(crate) he_vert: Vec<u32>,
    pub(crate) he_face: Vec<u32>,
    // --- faces
    /// A half-edge of the face, or `POINT | vertex` for a point-sphere face.
    pub(crate) f_start: Vec<u32>,
    /// Faces added by `close_boundaries` to cap a hole: part of the topology,
    /// left out of every export.
    pub(crate) f_hole: Vec<bool>,
}

/// A face's boundary as seen from outside the encoding.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum FaceStart {
    /// An ordinary face: one of its half-edges (the first corner).
    Halfedge(HalfedgeId),
    /// A point-sphere face: its single vertex, no edge.
    Point(VertexId),
}

impl Mesh {
    /// An empty mesh (no components).
    pub fn new() -> Self {
        Self::default()
    }

    // ------------------------------------------------------------------ counts

    #[inline]
    pub fn n_vertices(&self) -> usize {
        self.pos.len()
    }
    #[inline]
    pub fn n_halfedges(&self) -> usize {
        self.he_next.len()
    }
    #[inline]
    pub fn n_edges(&self) -> usize {
        self.he_next.len() / 2
    }
    /// All faces, holes included.
    #[inline]
    pub fn n_faces(&self) -> usize {
        self.f_start.len()
    }
    /// Faces marked as holes by `close_boundaries`.
    pub fn n_holes(&self) -> usize {
        self.f_hole.iter().filter(|&&h| h).count()
    }

    // ------------------------------------------------------------ navigation

    #[inline]
    pub fn next(&self, h: HalfedgeId) -> HalfedgeId {
        HalfedgeId(self.he_next[h.idx()])
    }
    #[inline]
    pub fn prev(&self, h: HalfedgeId) -> HalfedgeId {
        HalfedgeId(self.he_prev[h.idx()])
    }
    /// Tail of `h`: the vertex of the corner `h`.
    #[inline]
    pub fn vertex(&self, h: HalfedgeId) -> VertexId {
        VertexId(self.he_vert[h.idx()])
    }
    /// Head of `h` (tail of its twin and of `next(h)`).
    #[inline]
    pub fn head(&self, h: HalfedgeId) -> VertexId {
        VertexId(self.he_vert[h.twin().idx()])
    }
    #[inline]
    pub fn face(&self, h: HalfedgeId) -> FaceId {
        FaceId(self.he_face[h.idx()])
    }
    /// The next outgoing half-edge around the tail of `h`, rotating so that
    /// the corner between `h` and the result is `twin(prev(h))`'s face side.
    #[inline]
    pub fn rotate(&self, h: HalfedgeId) -> HalfedgeId {
        self.prev(h).twin()
    }
    /// True when both ends of the edge are one vertex.
    #[inline]
    pub fn is_self_loop(&self, e: EdgeId) -> bool {
        let h = e.halfedge();
        self.he_vert[h.idx()] == self.he_vert[h.twin().idx()]
    }

    #[inline]
    pub fn position(&self, v: VertexId) -> DVec3 {
        self.pos[v.idx()]
    }
    #[inline]
    pub fn set_position(&mut self, v: VertexId, p: DVec3) {
        self.pos[v.idx()] = p;
    }
    #[inline]
    pub fn positions(&self) -> &[DVec3] {
        &self.pos
    }
    /// Moving vertices never changes topology, so this is always safe.
    #[inline]
    pub fn positions_mut(&mut self) -> &mut [DVec3] {
        &mut self.pos
    }

    /// An outgoing half-edge of `v`, or `None` for a point-sphere vertex.
    #[inline]
    pub fn vertex_halfedge(&self, v: VertexId) -> Option<HalfedgeId> {
        let o = self.v_out[v.idx()];
        (o & POINT == 0).then_some(HalfedgeId(o))
    }
    /// Whether any vertex is a point-sphere (the schemes' one-pass and
    /// in-place paths leave those meshes to their general path).
    pub(crate) fn has_point_spheres(&self) -> bool {
        self.v_out.iter().any(|&o| o & POINT != 0)
    }
    /// The face of the point-sphere `v` belongs to, if it is one.
    #[inline]
    pub fn point_sphere_face(&self, v: VertexId) -> Option<FaceId> {
        let o = self.v_out[v.idx()];
        (o & POINT != 0).then_some(FaceId(o & !POINT))
    }
    #[inline]
    pub fn face_start(&self, f: FaceId) -> FaceStart {
        let s = self.f_start[f.idx()];
        if s & POINT != 0 {
            FaceStart::Point(VertexId(s & !POINT))
        } else {
            FaceStart::Halfedge(HalfedgeId(s))
        }
    }
    /// The first corner of `f`, `None` for a point-sphere face.
    #[inline]
    pub fn face_halfedge(&self, f: FaceId) -> Option<HalfedgeId> {
        match self.face_start(f) {
            FaceStart::Halfedge(h) => Some(h),
            FaceStart::Point(_) => None,
        }
    }
    #[inline]
    pub fn is_hole(&self, f: FaceId) -> bool {
        self.f_hole[f.idx()]
    }

    /// The corners (half-edges) of `f` in cycle order from its first corner;
    /// empty for a point-sphere face.
    pub fn face_halfedges(&self, f: FaceId) -> FaceHalfedges<'_> {
        let start = self.face_halfedge(f);
        FaceHalfedges { mesh: self, start, cur: start }
    }
    /// The vertices of `f` in cycle order, repeats kept (a point-sphere face
    /// yields its one vertex).
    pub fn face_vertices(&self, f: FaceId) -> impl Iterator<Item = VertexId> + '_ {
        let point = match self.face_start(f) {
            FaceStart::Point(v) => Some(v),
            FaceStart::Halfedge(_) => None,
        };
        point.into_iter().chain(self.face_halfedges(f).map(|h| self.vertex(h)))
    }
    /// Number of corners of `f` (1 for a point-sphere face). A plain walk
    /// of `next`: the open levels' rows call it once per term group.
    #[inline]
    pub fn face_degree(&self, f: FaceId) -> usize {
        let s = self.f_start[f.idx()];
        if s & POINT != 0 {
            return 1;
        }
        let (mut h, mut n) = (self.he_next[s as usize], 1usize);
        while h != s {
            n += 1;
            h = self.he_next[h as usize];
        }
        n
    }
    /// Outgoing half-edges of `v` in rotation order; empty for a point-sphere.
    pub fn vertex_halfedges(&self, v: VertexId) -> VertexHalfedges<'_> {
        let start = self.vertex_halfedge(v);
        VertexHalfedges { mesh: self, start, cur: start }
    }
    /// Number of edge ends at `v` (a self-loop counts twice); 0 for a point-sphere.
    pub fn valence(&self, v: VertexId) -> usize {
        self.vertex_halfedges(v).count()
    }
    pub fn vertices(&self) -> impl ExactSizeIterator<Item = VertexId> {
        (0..self.n_vertices() as u32).map(VertexId)
    }
    pub fn faces(&self) -> impl ExactSizeIterator<Item = FaceId> {
        (0..self.n_faces() as u32).map(FaceId)
    }
    pub fn edges(&self) -> impl ExactSizeIterator<Item = EdgeId> {
        (0..self.n_edges() as u32).map(EdgeId)
    }
    pub fn halfedges(&self) -> impl ExactSizeIterator<Item = HalfedgeId> {
        (0..self.n_halfedges() as u32).map(HalfedgeId)
    }

    /// Raw columns for fast bulk algorithms (read-only): `next`, `vertex`
    /// (tail) and `face` per half-edge.
    pub fn halfedge_columns(&self) -> (&[u32], &[u32], &[u32]) {
        (&self.he_next, &self.he_vert, &self.he_face)
    }
}

/// Iterator over the corners of a face. See [`Mesh::face_halfedges`].
pub struct FaceHalfedges<'a> {
    mesh: &'a Mesh,
    start: Option<HalfedgeId>,
    cur: Option<HalfedgeId>,
}

impl Iterator for FaceHalfedges<'_> {
    type Item = HalfedgeId;
    #[inline]
    fn next(&mut self) -> Option<HalfedgeId> {
        let h = self.cur?;
        let n = self.mesh.next(h);
        self.cur = if Some(n) == self.start { None } else { Some(n) };
        Some(h)
    }
}

/// Iterator over the outgoing half-edges of a vertex. See [`Mesh::vertex_halfedges`].
pub struct VertexHalfedges<'a> {
    mesh: &'a Mesh,
    start: Option<HalfedgeId>,
    cur: Option<HalfedgeId>,
}

impl Iterator for VertexHalfedges<'_> {
    type Item = HalfedgeId;
    #[inline]
    fn next(&mut self) -> Option<HalfedgeId> {
        let h = self.cur?;
        let n = self.mesh.rotate(h);
        self.cur = if Some(n) == self.start { None } else { Some(n) };
        Some(h)
    }
}

#[cfg(test)]
mod tests;

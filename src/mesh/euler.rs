//! The four fundamental operators of the high-genus dissertation, ch. II.5
//! (after Akleman & Chen's minimal operator set): CreateVertex, DeleteVertex,
//! InsertEdge, DeleteEdge. Each keeps the mesh a valid orientable 2-manifold.
//!
//! Deletions compact at once by swap-remove: the last element of the kind
//! takes the removed element's id, so columns stay dense. Ids of the moved
//! element change; every other id is kept.

use super::{EdgeId, FaceId, FaceStart, HalfedgeId, Mesh, VertexId, NONE, POINT, MAX_ELEMENTS};
use crate::error::{MeshError, Result};
use glam::DVec3;

/// An operand of the operators: a vertex-face pair `{v, f}` (ch. II.5).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Corner {
    /// The corner at the tail of this half-edge, inside its face.
    Halfedge(HalfedgeId),
    /// The lone corner of a point-sphere.
    Point(VertexId),
}

impl Mesh {
    /// The corner at `position` of face `f`, counting from its first corner
    /// (the order of `face_indices`).
    pub fn corner(&self, f: FaceId, position: usize) -> Result<Corner> {
        if f.idx() >= self.n_faces() {
            return Err(MeshError::InvalidArgument(format!(
                "face {} out of range (mesh has {} faces)",
                f.0,
                self.n_faces()
            )));
        }
        match self.face_start(f) {
            FaceStart::Point(v) if position == 0 => Ok(Corner::Point(v)),
            FaceStart::Halfedge(h0) => {
                let mut h = h0;
                for _ in 0..position {
                    h = self.next(h);
                    if h == h0 {
                        break;
                    }
                }
                if position > 0 && h == h0 {
                    return Err(MeshError::InvalidArgument(format!(
                        "face {} has {} corners; position {position} is out of range",
                        f.0,
                        self.face_degree(f)
                    )));
                }
                Ok(Corner::Halfedge(h))
            }
            FaceStart::Point(_) => Err(MeshError::InvalidArgument(format!(
                "face {} is a point-sphere with one corner; position {position} is out of range",
                f.0
            ))),
        }
    }

    /// The face a corner lies in.
    pub fn corner_face(&self, c: Corner) -> FaceId {
        match c {
            Corner::Halfedge(h) => self.face(h),
            Corner::Point(v) => self.point_sphere_face(v).expect("Corner::Point on a vertex with edges"),
        }
    }

    /// The vertex of a corner.
    pub fn corner_vertex(&self, c: Corner) -> VertexId {
        match c {
            Corner::Halfedge(h) => self.vertex(h),
            Corner::Point(v) => v,
        }
    }

    fn check_corner(&self, c: Corner) -> Result<()> {
        match c {
            Corner::Halfedge(h) if h.idx() < self.n_halfedges() => Ok(()),
            Corner::Halfedge(h) => Err(MeshError::InvalidArgument(format!(
                "half-edge {} out of range (mesh has {})",
                h.0,
                self.n_halfedges()
            ))),
            Corner::Point(v) if v.idx() < self.n_vertices() && self.point_sphere_face(v).is_some() => Ok(()),
            Corner::Point(v) => Err(MeshError::InvalidArgument(format!("vertex {} is not a point-sphere", v.0))),
        }
    }

    /// **CreateVertex(p)**: adds a point-sphere (one vertex, one face, no
    /// edge) at `p`. Returns `(v, f)`.
    ///
    /// Contract: V+1, F+1, E unchanged; χ += 2; components += 1; genus unchanged.
    pub fn create_vertex(&mut self, p: DVec3) -> Result<(VertexId, FaceId)> {
        if !p.is_finite() {
            return Err(MeshError::NonFinite { vertex: self.n_vertices() });
        }
        if self.n_vertices() >= MAX_ELEMENTS || self.n_faces() >= MAX_ELEMENTS {
            return Err(MeshError::InvalidArgument("mesh too large for 31-bit ids".into()));
        }
        let v = self.pos.len() as u32;
        let f = self.f_start.len() as u32;
        self.pos.push(p);
        self.v_out.push(POINT | f);
        self.f_start.push(POINT | v);
        self.f_hole.push(false);
        Ok((VertexId(v), FaceId(f)))
    }

    /// **DeleteVertex(v)**: removes a point-sphere. Any other vertex is a
    /// precondition error and the mesh is left unchanged (the dissertation's
    /// version returns silently; here the caller learns why).
    ///
    /// Contract: V−1, F−1; χ −= 2; components −= 1. The last vertex takes id
    /// `v` and the last face takes the point-sphere's face id.
    pub fn delete_vertex(&mut self, v: VertexId) -> Result<()> {
        if v.idx() >= self.n_vertices() {
            return Err(MeshError::InvalidArgument(format!(
                "vertex {} out of range (mesh has {} vertices)",
                v.0,
                self.n_vertices()
            )));
        }
        let Some(f) = self.point_sphere_face(v) else {
            return Err(MeshError::Precondition(format!(
                "DeleteVertex: vertex {} is not a point-sphere (it has {} edge ends); delete its edges first",
                v.0,
                self.valence(v)
            )));
        };
        self.swap_remove_face(f);
        self.swap_remove_vertex(v);
        Ok(())
    }

    /// **InsertEdge(c1, c2)**: a new edge from corner `c1` to corner `c2`.
    /// Returns it; its half-edge `2e` runs from `c1`'s vertex to `c2`'s.
    ///
    /// Contract (E+1 always):
    /// * corners of one face (including `c1 == c2`, which adds a self-loop
    ///   bounding a new one-gon): the face splits in two; F+1, χ, components
    ///   and genus unchanged. The new face is the one on the `2e` side.
    /// * corners of two faces of one component: the faces merge; F−1,
    ///   χ −= 2, genus += 1 (a handle).
    /// * corners of two components (point-spheres included): the faces merge;
    ///   F−1, χ −= 2, components −= 1, total genus unchanged.
    ///
    /// When faces merge, the last face takes the id of `c2`'s face.
    pub fn insert_edge(&mut self, c1: Corner, c2: Corner) -> Result<EdgeId> {
        self.check_corner(c1)?;
        self.check_corner(c2)?;
        if self.n_halfedges() + 2 > MAX_ELEMENTS || self.n_faces() >= MAX_ELEMENTS {
            return Err(MeshError::InvalidArgument("mesh too large for 31-bit ids".into()));
        }
        let (v1, v2) = (self.corner_vertex(c1), self.corner_vertex(c2));
        let (f1, f2) = (self.corner_face(c1), self.corner_face(c2));
        let e = self.n_edges() as u32;
        let (a, b) = (2 * e, 2 * e + 1);
        self.he_next.extend([NONE, NONE]);
        self.he_prev.extend([NONE, NONE]);
        self.he_vert.extend([v1.0, v2.0]);
        self.he_face.extend([f1.0, f1.0]);
        let (a_, b_) = (HalfedgeId(a), HalfedgeId(b));
        match (c1, c2) {
            (Corner::Halfedge(h1), Corner::Halfedge(h2)) => {
                let (p1, p2) = (self.prev(h1), self.prev(h2));
                if h1 == h2 {
                    self.link(p1, b_);
                    self.link(b_, h1);
                    self.link(a_, a_);
                } else {
                    self.link(p1, a_);
                    self.link(a_, h2);
                    self.link(p2, b_);
                    self.link(b_, h1);
                }
                if f1 == f2 {
                    // split: b stays in f1, a's cycle becomes a new face
                    self.f_start[f1.idx()] = b;
                    let nf = self.push_face(a);
                    self.set_cycle_face(a_, nf);
                } else {
                    self.f_start[f1.idx()] = a;
                    self.set_cycle_face(a_, f1);
                    self.swap_remove_face(f2);
                }
            }
            (Corner::Point(_), Corner::Halfedge(h2)) => {
                let p2 = self.prev(h2);
                self.link(p2, b_);
                self.link(b_, a_);
                self.link(a_, h2);
                self.v_out[v1.idx()] = a;
                // f1 is the point-sphere's face: it goes, f2 absorbs the edge
                self.f_start[f2.idx()] = a;
                self.he_face[a as usize] = f2.0;
                self.he_face[b as usize] = f2.0;
                self.swap_remove_face(f1);
            }
            (Corner::Halfedge(h1), Corner::Point(_)) => {
                let p1 = self.prev(h1);
                self.link(p1, a_);
                self.link(a_, b_);
                self.link(b_, h1);
                self.v_out[v2.idx()] = b;
                self.f_start[f1.idx()] = a;
                self.swap_remove_face(f2);
            }
            (Corner::Point(_), Corner::Point(_)) => {
                if v1 == v2 {
                    // a self-loop on a point-sphere: two one-gons
                    self.link(a_, a_);
                    self.link(b_, b_);
                    self.v_out[v1.idx()] = a;
                    self.f_start[f1.idx()] = a;
                    let nf = self.push_face(b);
                    self.he_face[b as usize] = nf.0;
                } else {
                    self.link(a_, b_);
                    self.link(b_, a_);
                    self.v_out[v1.idx()] = a;
                    self.v_out[v2.idx()] = b;
                    self.f_start[f1.idx()] = a;
                    self.swap_remove_face(f2);
                }
            }
        }
        Ok(EdgeId(e))
    }

    /// **DeleteEdge(e)**: the inverse of InsertEdge.
    ///
    /// Contract (E−1 always):
    /// * different faces on the two sides: they merge; F−1; χ, components,
    ///   genus unchanged.
    /// * the same face on both sides: it separates in two; F+1; χ += 2 and
    ///   either genus −1 (a handle is cut) or components +1 (the face was a
    ///   bridge between two parts). An end vertex left with no edge becomes a
    ///   point-sphere with its own face.
    ///
    /// The last edge takes id `e`; a face that disappears is replaced by the
    /// last face.
    pub fn delete_edge(&mut self, e: EdgeId) -> Result<()> {
        if e.idx() >= self.n_edges() {
            return Err(MeshError::InvalidArgument(format!(
                "edge {} out of range (mesh has {} edges)",
                e.0,
                self.n_edges()
            )));
        }
        let a = e.halfedge();
        let b = a.twin();
        let gone = |h: HalfedgeId| h == a || h == b;
        let (fa, fb) = (self.face(a), self.face(b));
        let (va, vb) = (self.vertex(a), self.vertex(b));

        // replacement outgoing half-edges for the end vertices
        let other_out = |m: &Mesh, v: VertexId| -> Option<HalfedgeId> {
            m.vertex_halfedges(v).find(|&h| !gone(h))
        };
        let new_out_a = other_out(self, va);
        let new_out_b = if vb == va { new_out_a } else { other_out(self, vb) };

        // splice a and b out of their cycles
        let (pa, pb) = (self.prev(a), self.prev(b));
        // a walk that reaches a removed side continues after its twin
        let skip = |m: &Mesh, x: HalfedgeId| -> HalfedgeId {
            let mut y = m.next(x);
            while gone(y) {
                y = m.next(y.twin());
            }
            y
        };
        // two faces merge into one cycle, which keeps fa's id: only fb's
        // sides change face (relabelling the whole cycle made merging a
        // quad into a growing face cost the face's size each time)
        let from_b: Vec<HalfedgeId> = if fa != fb { self.face_halfedges_from(b).skip(1).collect() } else { Vec::new() };
        let seeds: Vec<HalfedgeId> = [pa, pb].into_iter().filter(|&x| !gone(x)).collect();
        let targets: Vec<HalfedgeId> = seeds.iter().map(|&x| skip(self, x)).collect();
        for (&x, &y) in seeds.iter().zip(&targets) {
            self.link(x, y);
        }

        // faces of the remaining cycles
        let mut free_faces: Vec<FaceId> = if fa == fb { vec![fa] } else { vec![fa, fb] };
        // a merged face is a hole only if both sides were
        let hole = self.f_hole[fa.idx()] && self.f_hole[fb.idx()];
        if fa != fb {
            if let Some(&c) = seeds.first() {
                free_faces.remove(0);
                self.f_start[fa.idx()] = c.0;
                self.f_hole[fa.idx()] = hole;
                for h in from_b {
                    self.he_face[h.idx()] = fa.0;
                }
            }
        }
        let mut cycles: Vec<HalfedgeId> = Vec::new();
        for &s in seeds.iter().filter(|_| fa == fb) {
            if cycles.iter().any(|&c| self.face_halfedges_from(c).any(|h| h == s)) {
                continue;
            }
            cycles.push(s);
        }
        for &c in &cycles {
            let f = if !free_faces.is_empty() { free_faces.remove(0) } else { self.push_face(c.0) };
            self.f_start[f.idx()] = c.0;
            self.f_hole[f.idx()] = hole;
            self.set_cycle_face(c, f);
        }
        // isolated end vertices become point-spheres
        let mut ends = vec![(va, new_out_a)];
        if vb != va {
            ends.push((vb, new_out_b));
        }
        for (v, out) in ends {
            match out {
                Some(h) => self.v_out[v.idx()] = h.0,
                None => {
                    let f = if !free_faces.is_empty() { free_faces.remove(0) } else { self.push_face(POINT | v.0) };
                    self.f_start[f.idx()] = POINT | v.0;
                    self.f_hole[f.idx()] = false;
                    self.v_out[v.idx()] = POINT | f.0;
                }
            }
        }
        self.swap_remove_edge(e);
        // remove freed faces, highest id first so the other stays valid
        free_faces.sort_unstable_by(|x, y| y.cmp(x));
        for f in free_faces {
            self.swap_remove_face(f);
        }
        Ok(())
    }

    // ---------------------------------------------------------------- helpers

    /// The cycle of half-edges starting at `h` (need not be the face's first corner).
    pub(crate) fn face_halfedges_from(&self, h: HalfedgeId) -> impl Iterator<Item = HalfedgeId> + '_ {
        let mut cur = Some(h);
        std::iter::from_fn(move || {
            let x = cur?;
            let n = self.next(x);
            cur = if n == h { None } else { Some(n) };
            Some(x)
        })
    }

    #[inline]
    pub(crate) fn link(&mut self, x: HalfedgeId, y: HalfedgeId) {
        self.he_next[x.idx()] = y.0;
        self.he_prev[y.idx()] = x.0;
    }

    fn push_face(&mut self, start: u32) -> FaceId {
        self.f_start.push(start);
        self.f_hole.push(false);
        FaceId(self.f_start.len() as u32 - 1)
    }

    fn set_cycle_face(&mut self, start: HalfedgeId, f: FaceId) {
        let mut h = start;
        loop {
            self.he_face[h.idx()] = f.0;
            h = self.next(h);
            if h == start {
                break;
            }
        }
    }

    /// Removes face `f` (already detached from every half-edge and vertex);
    /// the last face takes its id.
    fn swap_remove_face(&mut self, f: FaceId) {
        let last = self.f_start.len() - 1;
        if f.idx() != last {
            let s = self.f_start[last];
            self.f_start[f.idx()] = s;
            self.f_hole[f.idx()] = self.f_hole[last];
            if s & POINT != 0 {
                self.v_out[(s & !POINT) as usize] = POINT | f.0;
            } else {
                self.set_cycle_face(HalfedgeId(s), f);
            }
        }
        self.f_start.pop();
        self.f_hole.pop();
    }

    /// Removes vertex `v` (referenced by nothing but its own point-sphere
    /// face, already removed); the last vertex takes its id.
    fn swap_remove_vertex(&mut self, v: VertexId) {
        let last = self.pos.len() - 1;
        if v.idx() != last {
            self.pos[v.idx()] = self.pos[last];
            let o = self.v_out[last];
            self.v_out[v.idx()] = o;
            if o & POINT != 0 {
                self.f_start[(o & !POINT) as usize] = POINT | v.0;
            } else {
                let outs: Vec<HalfedgeId> = self.vertex_halfedges(VertexId(last as u32)).collect();
                for h in outs {
                    self.he_vert[h.idx()] = v.0;
                }
            }
        }
        self.pos.pop();
        self.v_out.pop();
    }

    /// Removes edge `e` (already unlinked: nothing points at its half-edges);
    /// the last edge takes its id.
    fn swap_remove_edge(&mut self, e: EdgeId) {
        let last = self.n_edges() - 1;
        if e.idx() != last {
            let (old0, new0) = (2 * last as u32, 2 * e.0);
            let remap = |x: u32| if x == old0 || x == old0 + 1 { x - old0 + new0 } else { x };
            for k in 0..2 {
                let (o, n) = ((old0 + k) as usize, (new0 + k) as usize);
                self.he_next[n] = remap(self.he_next[o]);
                self.he_prev[n] = remap(self.he_prev[o]);
                self.he_vert[n] = self.he_vert[o];
                self.he_face[n] = self.he_face[o];
            }
            for k in 0..2 {
                let n = new0 + k;
                let (p, nx) = (self.he_prev[n as usize], self.he_next[n as usize]);
                self.he_next[p as usize] = n;
                self.he_prev[nx as usize] = n;
                let v = self.he_vert[n as usize] as usize;
                if self.v_out[v] == old0 + k {
                    self.v_out[v] = n;
                }
                let f = self.he_face[n as usize] as usize;
                if self.f_start[f] == old0 + k {
                    self.f_start[f] = n;
                }
            }
        }
        let nh = self.he_next.len() - 2;
        self.he_next.truncate(nh);
        self.he_prev.truncate(nh);
        self.he_vert.truncate(nh);
        self.he_face.truncate(nh);
    }
}

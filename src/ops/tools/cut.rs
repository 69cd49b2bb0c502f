//! Conical cuts (TopMod's sculpting tools `cutSelectedVertices`,
//! `cutSelectedEdges`, `cutSelectedFaces` → `performCutting` → `localCut`,
//! `include/dlflaux/DLFLSculpting.cc`, the only description): each
//! selected element defines a plane, and the part of the surface around
//! it on the plane's positive side — the vertices reachable from a seed
//! vertex through vertices on that side — is cut off and capped by a new
//! face through the points where its edges cross the plane.
//!
//! Planes, as TopMod: for a vertex, through the mean of the points at
//! `offset` (a fraction of each edge) along its edges, normal to its
//! averaged normal, seed the vertex; for an edge, through the mean of the
//! points at `offset` along the other edges of both ends, normal to the sum
//! of its two faces' normals, seed its first end; for a face, through the
//! mean of the points at `offset` along the edges leaving its corners off
//! the face, normal to the face, seed its highest corner. All planes are
//! taken from the input. Cuts whose regions share a vertex or an edge are
//! made one after the other (later ones on the cut mesh), the others
//! together in one pass; a cut whose seed an earlier one removed is skipped.
//!
//! Counts per cut of a region of r vertices and e_r edges inside, crossed
//! by c edges, in a region that is a disk: V − r + c, E − e_r + c,
//! F − (faces entirely inside) + 1; genus unchanged.

use super::builder::{tag, Builder};
use crate::error::{MeshError, Result};
use crate::mesh::{EdgeId, FaceId, HalfedgeId, Mesh, VertexId};
use glam::DVec3;

/// One cut: its plane and seed vertex, and the element it came from (for errors).
#[derive(Clone, Debug)]
struct Cut {
    seed: VertexId,
    normal: DVec3,
    point: DVec3,
    what: String,
}

fn check_offset(call: &str, offset: f64) -> Result<()> {
    if !(offset.is_finite() && offset > 0.0 && offset <= 2.0) {
        return Err(MeshError::InvalidArgument(format!("{call}: offset = {} must be in (0, 2] (a fraction of the edge lengths)", crate::error::num(offset))));
    }
    Ok(())
}

impl Mesh {
    fn refuse_for_cut(&self, call: &str) -> Result<()> {
        self.refuse_open(call, "cuts need a closed surface")?;
        if let Some(f) = self.faces().find(|&f| self.face_halfedge(f).is_none()) {
            return Err(MeshError::Precondition(format!("{call}: face {} is a point-sphere", f.0)));
        }
        Ok(())
    }

    /// **Cut by vertex** (module docs): each vertex of `vertices` cut off by
    /// a plane at `offset` (in (0, 2], a fraction of its edges; TopMod's
    /// default 0.25). Returns the mesh and the number of cuts made.
    pub fn cut_vertices(&self, vertices: &[usize], offset: f64) -> Result<(Mesh, usize)> {
        check_offset("cut_vertices", offset)?;
        // meshes near f64's ends are cut at unit size (offset is relative)
        crate::geometry::scale_free_with(self, |m, _| m.cut_vertices_unscaled(vertices, offset))
    }

    fn cut_vertices_unscaled(&self, vertices: &[usize], offset: f64) -> Result<(Mesh, usize)> {
        self.refuse_for_cut("cut_vertices")?;
        let normals = self.vertex_normals();
        let mut cuts = Vec::new();
        for (i, &v) in vertices.iter().enumerate() {
            if v >= self.n_vertices() {
                return Err(MeshError::InvalidArgument(format!("cut_vertices: vertex {v} out of range (mesh has {} vertices)", self.n_vertices())));
            }
            if vertices[..i].contains(&v) {
                return Err(MeshError::InvalidArgument(format!("cut_vertices: vertex {v} is selected twice")));
            }
            let vid = VertexId::new(v);
            let p = self.position(vid);
            let pts: Vec<DVec3> = self.vertex_halfedges(vid).map(|h| p + offset * (self.position(self.head(h)) - p)).collect();
            let point = pts.iter().sum::<DVec3>() / pts.len() as f64;
            cuts.push(Cut { seed: vid, normal: normals[v], point, what: format!("vertex {v}") });
        }
        self.apply_cuts("cut_vertices", cuts, offset)
    }

    /// **Cut by edge** (module docs): each edge of `edges` cut off by a
    /// plane at `offset` along the neighbouring edges. Returns the mesh and
    /// the number of cuts made.
    pub fn cut_edges(&self, edges: &[usize], offset: f64) -> Result<(Mesh, usize)> {
        check_offset("cut_edges", offset)?;
        // meshes near f64's ends are cut at unit size (offset is relative)
        crate::geometry::scale_free_with(self, |m, _| m.cut_edges_unscaled(edges, offset))
    }

    fn cut_edges_unscaled(&self, edges: &[usize], offset: f64) -> Result<(Mesh, usize)> {
        self.refuse_for_cut("cut_edges")?;
        let fnorm = self.face_normals();
        let mut cuts = Vec::new();
        for (i, &e) in edges.iter().enumerate() {
            if e >= self.n_edges() {
                return Err(MeshError::InvalidArgument(format!("cut_edges: edge {e} out of range (mesh has {} edges)", self.n_edges())));
            }
            if edges[..i].contains(&e) {
                return Err(MeshError::InvalidArgument(format!("cut_edges: edge {e} is selected twice")));
            }
            let h = EdgeId::new(e).halfedge();
            let mut pts = Vec::new();
            for end in [h, h.twin()] {
                let v = self.vertex(end);
                let p = self.position(v);
                for g in self.vertex_halfedges(v) {
                    if g.edge() != h.edge() {
                        pts.push(p + offset * (self.position(self.head(g)) - p));
                    }
                }
            }
            if pts.is_empty() {
                return Err(MeshError::Precondition(format!("cut_edges: edge {e} has no neighbouring edges to place its plane")));
            }
            let point = pts.iter().sum::<DVec3>() / pts.len() as f64;
            let normal = (fnorm[self.face(h).idx()] + fnorm[self.face(h.twin()).idx()]).normalize_or_zero();
            cuts.push(Cut { seed: self.vertex(h), normal, point, what: format!("edge {e}") });
        }
        self.apply_cuts("cut_edges", cuts, offset)
    }

    /// **Cut by face** (module docs): each face of `faces` sliced off by a
    /// plane parallel to it at `offset` along the edges leaving it. Returns
    /// the mesh and the number of cuts made.
    pub fn cut_faces(&self, faces: &[usize], offset: f64) -> Result<(Mesh, usize)> {
        check_offset("cut_faces", offset)?;
        // meshes near f64's ends are cut at unit size (offset is relative)
        crate::geometry::scale_free_with(self, |m, _| m.cut_faces_unscaled(faces, offset))
    }

    fn cut_faces_unscaled(&self, faces: &[usize], offset: f64) -> Result<(Mesh, usize)> {
        self.refuse_for_cut("cut_faces")?;
        let fnorm = self.face_normals();
        let mut cuts = Vec::new();
        for (i, &f) in faces.iter().enumerate() {
            if f >= self.n_faces() {
                return Err(MeshError::InvalidArgument(format!("cut_faces: face {f} out of range (mesh has {} faces)", self.n_faces())));
            }
            if faces[..i].contains(&f) {
                return Err(MeshError::InvalidArgument(format!("cut_faces: face {f} is selected twice")));
            }
            let fid = FaceId::new(f);
            let mut pts = Vec::new();
            for v in self.face_vertices(fid) {
                let p = self.position(v);
                for g in self.vertex_halfedges(v) {
                    if self.face(g) != fid && self.face(g.twin()) != fid {
                        pts.push(p + offset * (self.position(self.head(g)) - p));
                    }
                }
            }
            if pts.is_empty() {
                return Err(MeshError::Precondition(format!("cut_faces: face {f} has no edges leaving it to place its plane")));
            }
            let point = pts.iter().sum::<DVec3>() / pts.len() as f64;
            let normal = fnorm[f];
            let seed = self.face_vertices(fid).max_by(|&a, &b| normal.dot(self.position(a)).total_cmp(&normal.dot(self.position(b)))).unwrap();
            cuts.push(Cut { seed, normal, point, what: format!("face {f}") });
        }
        self.apply_cuts("cut_faces", cuts, offset)
    }

    /// Applies cuts in batches of non-touching regions (`offset` only names
    /// itself in the error of a cut that removes nothing).
    fn apply_cuts(&self, call: &str, cuts: Vec<Cut>, offset: f64) -> Result<(Mesh, usize)> {
        for c in &cuts {
            if c.normal == DVec3::ZERO {
                return Err(MeshError::Precondition(format!("{call}: {} has no normal to cut along", c.what)));
            }
            if c.normal.dot(self.position(c.seed) - c.point) <= 0.0 {
                return Err(MeshError::Precondition(format!(
                    "{call}: {} lies on or below its cutting plane (a saddle or a flat spot, or offset = {} too small to move \
                     the plane off it); nothing to cut off",
                    c.what,
                    crate::error::num(offset)
                )));
            }
        }
        let mut m = self.clone();
        // current id of every input vertex (None once cut away)
        let mut now: Vec<Option<u32>> = (0..self.n_vertices() as u32).map(Some).collect();
        let mut pending: Vec<Cut> = cuts;
        let mut made = 0;
        while !pending.is_empty() {
            crate::cancel::check()?;
            let nv = m.n_vertices();
            let mut owner = vec![u32::MAX; nv];
            let mut batch: Vec<(Cut, Vec<u32>)> = Vec::new();
            let mut later = Vec::new();
            for c in pending {
                let Some(seed) = now[c.seed.idx()] else { continue };
                let d = |v: u32| c.normal.dot(m.pos[v as usize] - c.point);
                if d(seed) <= 0.0 {
                    continue; // an earlier cut moved the surface below this plane
                }
                // region: BFS through vertices above the plane
                let mut region = vec![seed];
                let mut mark = std::collections::HashSet::new();
                mark.insert(seed);
                let mut k = 0;
                let mut clash = false;
                while k < region.len() {
                    let v = region[k];
                    k += 1;
                    if owner[v as usize] != u32::MAX {
                        clash = true;
                    }
                    for h in m.vertex_halfedges(VertexId(v)) {
                        let w = m.head(h).0;
                        if owner[w as usize] != u32::MAX {
                            clash = true; // touches another region of this batch
                        }
                        if d(w) > 0.0 && mark.insert(w) {
                            region.push(w);
                        }
                    }
                }
                if clash {
                    later.push(c);
                    continue;
                }
                for &v in &region {
                    owner[v as usize] = batch.len() as u32;
                }
                batch.push((c, region));
            }
            pending = later;
            if batch.is_empty() {
                break;
            }
            made += batch.len();
            let (next, map) = m.cut_regions(call, &batch, &owner)?;
            for slot in now.iter_mut() {
                *slot = slot.and_then(|v| map[v as usize]);
            }
            m = next;
        }
        Ok((m, made))
    }

    /// One pass: every region removed, its crossing edges cut at the plane
    /// and the crossings of each loop joined by a cap face. Returns the mesh
    /// and the new id of every old vertex.
    fn cut_regions(&self, call: &str, batch: &[(Cut, Vec<u32>)], owner: &[u32]) -> Result<(Mesh, Vec<Option<u32>>)> {
        let nv = self.n_vertices();
        let inside = |v: VertexId| owner[v.idx()] != u32::MAX;
        // every component keeps something
        let (label, nc) = self.vertex_components();
        let mut kept = vec![false; nc];
        for v in self.vertices() {
            if !inside(v) {
                kept[label[v.idx()] as usize] = true;
            }
        }
        if let Some(v) = self.vertices().find(|&v| !kept[label[v.idx()] as usize]) {
            let (c, _) = &batch[owner[v.idx()] as usize];
            return Err(MeshError::Precondition(format!("{call}: the plane of {} cuts away its whole component; use a smaller offset", c.what)));
        }
        let mut map = vec![None; nv];
        let mut pos = Vec::new();
        for v in self.vertices() {
            if !inside(v) {
                map[v.idx()] = Some(pos.len() as u32);
                pos.push(self.position(v));
            }
        }
        // one crossing point per edge with one end inside
        let mut cross = vec![u32::MAX; self.n_edges()];
        for e in self.edges() {
            let h = e.halfedge();
            let (a, b) = (self.vertex(h), self.head(h));
            if inside(a) == inside(b) {
                continue;
            }
            let (u, w) = if inside(a) { (a, b) } else { (b, a) };
            let (c, _) = &batch[owner[u.idx()] as usize];
            let (du, dw) = (c.normal.dot(self.position(u) - c.point), c.normal.dot(self.position(w) - c.point));
            let t = (du / (du - dw)).clamp(0.0, 1.0);
            cross[e.idx()] = pos.len() as u32;
            pos.push(self.position(u).lerp(self.position(w), t));
        }
        let mut b = Builder::with_positions(pos);
        let mut cap_next: rustc_hash::FxHashMap<u32, (u32, u64)> = Default::default();
        for f in self.faces() {
            let hs: Vec<HalfedgeId> = self.face_halfedges(f).collect();
            let Some(s) = hs.iter().position(|&h| !inside(self.vertex(h))) else { continue };
            let n = hs.len();
            let (mut vs, mut ts) = (Vec::new(), Vec::new());
            let mut k = 0;
            while k < n {
                let c = hs[(s + k) % n];
                // c is outside here
                vs.push(map[self.vertex(c).idx()].unwrap());
                ts.push(tag(0, c.edge().idx()));
                k += 1;
                if k < n + 1 && inside(self.vertex(hs[(s + k) % n])) {
                    let xin = cross[c.edge().idx()];
                    let mut last = hs[(s + k) % n];
                    while inside(self.vertex(hs[(s + k) % n])) {
                        last = hs[(s + k) % n];
                        k += 1;
                    }
                    let xout = cross[last.edge().idx()];
                    vs.push(xin);
                    ts.push(tag(1, c.idx()));
                    vs.push(xout);
                    ts.push(tag(0, last.edge().idx()));
                    cap_next.insert(xout, (xin, tag(1, c.idx())));
                }
            }
            b.face(&vs, &ts);
        }
        // caps: chain the crossings
        let mut starts: Vec<u32> = cap_next.keys().copied().collect();
        starts.sort_unstable();
        let mut done = std::collections::HashSet::new();
        for s in starts {
            if done.contains(&s) {
                continue;
            }
            let (mut vs, mut ts) = (Vec::new(), Vec::new());
            let mut x = s;
            loop {
                done.insert(x);
                let Some(&(y, t)) = cap_next.get(&x) else {
                    return Err(MeshError::Invariant("cut: a cap boundary does not close".into()));
                };
                vs.push(x);
                ts.push(t);
                x = y;
                if x == s {
                    break;
                }
                if vs.len() > cap_next.len() {
                    return Err(MeshError::Invariant(format!("{call}: a cap loop does not close")));
                }
            }
            b.face(&vs, &ts);
        }
        let m = b.build(call)?;
        Ok((m, map))
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::testing::*;
    use crate::primitives;

    #[test]
    fn truncate_cube_corners() {
        let m = primitives::cube();
        let (r, k) = m.cut_vertices(&(0..8).collect::<Vec<_>>(), 0.25).unwrap();
        assert_eq!(k, 8);
        assert_eq!(counts(&r), (24, 36, 14, 1, 0));
        let (r, _) = m.cut_vertices(&[0], 0.25).unwrap();
        assert_eq!(counts(&r), (10, 15, 7, 1, 0));
        assert!(m.cut_vertices(&[8], 0.25).is_err());
        assert!(m.cut_vertices(&[0, 0], 0.25).is_err());
        assert!(m.cut_vertices(&[0], 0.0).is_err());
    }

    #[test]
    fn cut_edges_and_faces() {
        let m = primitives::cube();
        let (r, _) = m.cut_edges(&[0], 0.25).unwrap();
        // both ends and the edge go, 4 crossings, one cap
        assert_eq!(counts(&r), (8 - 2 + 4, 12 - 1 + 4, 7, 1, 0));
        let (r, k) = m.cut_edges(&(0..12).collect::<Vec<_>>(), 0.25).unwrap();
        assert_eq!(counts(&r).3, 1);
        assert_eq!(counts(&r).4, 0);
        assert!(k >= 1);
        let (r, _) = m.cut_faces(&[0], 0.25).unwrap();
        // the face's 4 corners go, 4 crossings, the cap replaces it
        assert_eq!(counts(&r), (8, 12, 6, 1, 0));
        let t = primitives::torus(8, 6, 1.0, 0.4).unwrap();
        let (r, _) = t.cut_vertices(&[0], 0.3).unwrap();
        assert_eq!(counts(&r).4, 1);
    }
}

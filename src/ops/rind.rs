//! Rind modeling, the improved algorithm of the dissertation's ch. V.3.
//!
//! [`Rind::new`] builds the offset shell automatically (V.3.1): the mesh is
//! duplicated, the copy's orientation reversed and each copied vertex moved
//! by the thickness along the inward averaged vertex normal; a table maps
//! each outer face to its inner twin and their matching corners.
//! [`Rind::punch`] connects an outer face to its twin with CreatePipe;
//! [`Rind::peel`] also removes the infinitely thin walls left between
//! neighbouring holes and the two-gons they leave (V.3.2).
//!
//! **Open meshes.** The rind of an open surface M is its solid shell: the
//! rind of the capped surface with every hole face peeled at once, so each
//! boundary loop becomes a strip of quads joining the outer and inner copies
//! of its rim. The result is the double of M, closed: χ = 2χ(M), one
//! component per component of M, genus 2g + b − 1 for a connected M of genus
//! g with b ≥ 1 boundary loops (a disk gives a sphere, an annulus or an open
//! tube a torus). The hole faces count among the outer faces `0..F` and are
//! listed as peeled; vertex normals at the rim average the real faces only.
//!
//! Topology: the fresh rind of a genus-g connected mesh has two components
//! of genus g. The first punch joins them (components −1, genus unchanged);
//! every further punch adds a handle (genus +1). Peeling a face removes, per
//! wall shared with an earlier hole, one handle (genus −1), or separates a
//! piece when that wall closes a ring of holes. Peeling a strip of n faces
//! in a row thus gives genus 2g + 0 (one hole), whereas punching them gives
//! 2g + n − 1.

use super::remap_deleted_edge;
use crate::error::{MeshError, Result};
use crate::mesh::{Corner, FaceId, HalfedgeId, Mesh, VertexId};
use glam::DVec3;

/// A rind: a mesh with the face correspondence of its offset shell.
///
/// Faces are named by their index in the rind's initial mesh
/// ([`Rind::initial_face_count`] faces): `0..F` are the outer shell (the
/// source mesh's faces, same indices), `F..2F` their inner twins.
#[derive(Clone, Debug)]
pub struct Rind {
    mesh: Mesh,
    /// Corner 0 of each outer face (valid while the face is not punched).
    outer: Vec<HalfedgeId>,
    /// The matching corner of its inner twin.
    inner: Vec<HalfedgeId>,
    punched: Vec<bool>,
}

impl Rind {
    /// The offset shell of `source` at `thickness` (V.3.1).
    ///
    /// An open source (with hole faces) gives its closed solid shell, the
    /// hole faces peeled (module docs).
    ///
    /// Errors: a thickness that is not finite and positive; a source with
    /// point-spheres or a vertex whose averaged normal vanishes;
    /// a thickness that flips an inner face against its outer twin (named).
    pub fn new(source: &Mesh, thickness: f64) -> Result<Rind> {
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(MeshError::InvalidArgument(format!("rind: thickness {} must be finite and positive", crate::error::num(thickness))));
        }
        if let Some(f) = source.faces().find(|&f| source.face_halfedge(f).is_none()) {
            return Err(MeshError::Precondition(format!("rind: face {} is a point-sphere; it has no rind", f.0)));
        }
        let normals = source.vertex_normals();
        if let Some(v) = normals.iter().position(|n| *n == DVec3::ZERO) {
            return Err(MeshError::Precondition(format!("rind: vertex {v} has no averaged normal (its faces cancel)")));
        }
        // positions: outer copy, then inner copy moved inward
        let mut pos = source.positions().to_vec();
        pos.extend(source.positions().iter().zip(&normals).map(|(&p, &n)| p - thickness * n));
        Rind::from_shell(source, pos, &format!("thickness {}", crate::error::num(thickness)))
    }

    /// The rind of `source` with the given positions: `pos` holds the outer
    /// copy's vertices, then the inner copy's (2V entries). `how` names the
    /// offset in the flip error. Used by [`Rind::new`] and rind by scaling.
    pub(crate) fn from_shell(source: &Mesh, pos: Vec<DVec3>, how: &str) -> Result<Rind> {
        let nv = source.n_vertices();
        let nf = source.n_faces();
        debug_assert_eq!(pos.len(), 2 * nv);
        // corners: outer faces as they are, then each inner face reversed
        // (v0, vN−1, …, v1); the inner corner at vi is the reversed side of
        // prev(hi). Corner ids: outer corner of h, inner corner of the
        // reversed side g.
        let nh = source.n_halfedges();
        let mut outer_id = vec![0u32; nh];
        let mut inner_id = vec![0u32; nh];
        let mut sizes = Vec::with_capacity(2 * nf);
        let mut verts = Vec::with_capacity(2 * nh);
        for f in source.faces() {
            let hs: Vec<HalfedgeId> = source.face_halfedges(f).collect();
            sizes.push(hs.len() as u32);
            for &h in &hs {
                outer_id[h.idx()] = verts.len() as u32;
                verts.push(source.vertex(h).0);
            }
        }
        for f in source.faces() {
            let hs: Vec<HalfedgeId> = source.face_halfedges(f).collect();
            let n = hs.len();
            sizes.push(n as u32);
            for k in 0..n {
                let hi = hs[(n - k) % n];
                let g = source.prev(hi);
                inner_id[g.idx()] = verts.len() as u32;
                verts.push(source.vertex(hi).0 + nv as u32);
            }
        }
        let mut twin = vec![0u32; verts.len()];
        for h in source.halfedges() {
            twin[outer_id[h.idx()] as usize] = outer_id[h.twin().idx()];
            twin[inner_id[h.idx()] as usize] = inner_id[h.twin().idx()];
        }
        let mesh = Mesh::from_corner_twins(pos, &sizes, &verts, &twin)?;
        // no inner face may turn over, nor any of its sides reverse
        let inner_pos = |v: VertexId| mesh.position(VertexId(v.0 + nv as u32));
        for f in source.faces().filter(|&f| !source.is_hole(f)) {
            let n_out = source.face_newell(f);
            let mut n_in = DVec3::ZERO;
            let mut reversed = false;
            for h in source.face_halfedges(f) {
                let (a, b) = (inner_pos(source.vertex(h)), inner_pos(source.head(h)));
                n_in += a.cross(b);
                let d_out = source.position(source.head(h)) - source.position(source.vertex(h));
                reversed |= (b - a).dot(d_out) <= 0.0 && d_out != DVec3::ZERO;
            }
            if n_in.dot(n_out) <= 0.0 || reversed {
                return Err(MeshError::Precondition(format!(
                    "rind: {how} flips the inner twin of face {} (the offset passes through it); use a smaller offset",
                    f.0
                )));
            }
        }
        let mut outer = Vec::with_capacity(nf);
        let mut inner = Vec::with_capacity(nf);
        for f in 0..nf {
            let Corner::Halfedge(a) = mesh.corner(FaceId::new(f), 0)? else { unreachable!() };
            let Corner::Halfedge(b) = mesh.corner(FaceId::new(nf + f), 0)? else { unreachable!() };
            outer.push(a);
            inner.push(b);
        }
        let mut rind = Rind { mesh, outer, inner, punched: vec![false; nf] };
        // an open surface: its shell is closed along each boundary loop by
        // peeling the hole faces (module docs)
        let holes: Vec<usize> = source.faces().filter(|&f| source.is_hole(f)).map(|f| f.idx()).collect();
        if !holes.is_empty() {
            rind.peel(&holes)?;
        }
        Ok(rind)
    }

    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }
    pub fn into_mesh(self) -> Mesh {
        self.mesh
    }
    /// Faces of the initial rind mesh: 2F for a source of F faces.
    pub fn initial_face_count(&self) -> usize {
        2 * self.outer.len()
    }
    /// Whether outer face `f` has been punched or peeled.
    pub fn is_punched(&self, f: usize) -> bool {
        self.punched.get(f).copied().unwrap_or(false)
    }
    /// The outer faces punched or peeled so far, increasing.
    pub fn punched_faces(&self) -> Vec<usize> {
        (0..self.punched.len()).filter(|&f| self.punched[f]).collect()
    }
    /// The current face id of outer face `f` and of its inner twin, while unpunched.
    pub fn face_pair(&self, f: usize) -> Option<(FaceId, FaceId)> {
        (f < self.outer.len() && !self.punched[f]).then(|| (self.mesh.face(self.outer[f]), self.mesh.face(self.inner[f])))
    }

    /// Refuses peeling every remaining outer face: every wall goes and nothing
    /// is left (peeling all six faces of a cube rind gave an empty mesh).
    /// Punching them all is fine: the walls stay, a frame of genus F − 1.
    fn check_leaves_something(&self, faces: &[usize], what: &str) -> Result<()> {
        let left = self.punched.iter().filter(|&&p| !p).count();
        if !faces.is_empty() && faces.len() >= left {
            return Err(MeshError::InvalidArgument(format!(
                "{what}: selecting all {left} remaining outer faces would leave nothing of the rind; keep at least one face"
            )));
        }
        Ok(())
    }

    fn check(&self, faces: &[usize], what: &str) -> Result<()> {
        let nf = self.outer.len();
        for (i, &f) in faces.iter().enumerate() {
            if f >= 2 * nf {
                return Err(MeshError::InvalidArgument(format!("{what}: face {f} out of range (the rind has {} faces)", 2 * nf)));
            }
            if f >= nf {
                return Err(MeshError::InvalidArgument(format!(
                    "{what}: face {f} is on the inner shell (the inner twin of face {}); select outer faces 0..{nf}",
                    f - nf
                )));
            }
            if self.punched[f] {
                return Err(MeshError::Precondition(format!("{what}: face {f} is already punched")));
            }
            if faces[..i].contains(&f) {
                return Err(MeshError::InvalidArgument(format!("{what}: face {f} is selected twice")));
            }
        }
        Ok(())
    }

    /// Punches a hole through each outer face of `faces` (V.3.2, hole
    /// punching): CreatePipe(c1, c2) between the face and its inner twin at
    /// matching corners. Contract per face: E+N, F+N−2, and components −1
    /// (first punch of a fresh rind) or genus +1. On error nothing changes.
    pub fn punch(&mut self, faces: &[usize]) -> Result<()> {
        self.check(faces, "punch")?;
        for &f in faces {
            self.pipe(f)?;
        }
        Ok(())
    }

    fn pipe(&mut self, f: usize) -> Result<Vec<HalfedgeId>> {
        let p = self.mesh.create_pipe(Corner::Halfedge(self.outer[f]), Corner::Halfedge(self.inner[f]))?;
        debug_assert_eq!(p.subdivisions, 0);
        self.punched[f] = true;
        Ok(p.sides)
    }

    /// Peels each outer face of `faces` (V.3.2, peeling): punches it, then
    /// for each side whose outer and inner edges both separate the same two
    /// faces — an infinitely thin wall against an earlier hole — deletes the
    /// wall's outer and inner edges (a handle is cut) and one edge of each
    /// two-gon that leaves at the wall's ends, with DeleteEdgeWithCleanup (an
    /// end vertex that loses every face goes with its inner twin).
    /// On error nothing changes.
    pub fn peel(&mut self, faces: &[usize]) -> Result<()> {
        self.check(faces, "peel")?;
        self.check_leaves_something(faces, "peel")?;
        for &f in faces {
            let sides = self.pipe(f)?;
            // tracked half-edges: the table's corners, then this pipe's sides
            let nt = self.outer.len();
            let mut tracked: Vec<Option<HalfedgeId>> =
                self.outer.iter().chain(&self.inner).map(|&h| Some(h)).chain(sides.iter().map(|&h| Some(h))).collect();
            for i in 0..sides.len() {
                let Some(a) = tracked[2 * nt + i] else { continue };
                let m = &self.mesh;
                let q = m.face(a);
                let inner_side = m.next(m.next(a));
                let (x, y) = (m.face(a.twin()), m.face(inner_side.twin()));
                if m.face_degree(q) != 4 || x != y || x == q {
                    continue;
                }
                // the wall: delete its outer edge (the quads merge into a
                // hexagon), then its inner edge (two two-gons remain)
                let ends = [m.prev(a), m.next(a)];
                let base = tracked.len();
                tracked.push(Some(inner_side));
                tracked.extend(ends.iter().map(|&h| Some(h)));
                self.delete_tracked(a, &mut tracked)?;
                if let Some(h) = tracked[base] {
                    self.delete_tracked(h, &mut tracked)?;
                }
                for k in 1..3 {
                    let Some(h) = tracked[base + k] else { continue };
                    if self.mesh.face_degree(self.mesh.face(h)) == 2 {
                        self.delete_tracked(h, &mut tracked)?;
                    }
                }
                tracked.truncate(base);
            }
            for (k, t) in tracked[..2 * nt].iter().enumerate() {
                // corners of punched faces may go; those of the others never do
                let Some(h) = *t else { continue };
                if k < nt {
                    self.outer[k] = h;
                } else {
                    self.inner[k - nt] = h;
                }
            }
        }
        Ok(())
    }

    /// DeleteEdgeWithCleanup on the edge of `h`, keeping `tracked` current.
    fn delete_tracked(&mut self, h: HalfedgeId, tracked: &mut [Option<HalfedgeId>]) -> Result<()> {
        let e = h.edge();
        let last = crate::mesh::EdgeId::new(self.mesh.n_edges() - 1);
        self.mesh.delete_edge_with_cleanup(e)?;
        remap_deleted_edge(e, last, tracked);
        Ok(())
    }
}

impl Mesh {
    /// The offset shell of this mesh at `thickness`: see [`Rind::new`].
    pub fn rind(&self, thickness: f64) -> Result<Rind> {
        Rind::new(self, thickness)
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use super::*;
    use crate::primitives;

    fn centre_faces(m: &Mesh, n: usize) -> Vec<usize> {
        // faces of a grid cube whose centroid is a face centre of the cube
        let c = m.face_centroids();
        (0..m.n_faces()).filter(|&f| (c[f].length() - 1.0).abs() < 1e-9 && n % 2 == 1).collect()
    }

    #[test]
    fn fresh_rind_is_two_nested_shells() {
        let m = grid_cube(3);
        let r = m.rind(0.2).unwrap();
        let (v, e, f, c, g) = counts(r.mesh());
        assert_eq!((v, e, f, c, g), (2 * 56, 2 * 108, 2 * 54, 2, 0));
        assert!(r.mesh().signed_volume() > 0.0);
        assert!(r.mesh().signed_volume() < m.signed_volume());
        assert_eq!(r.face_pair(0), Some((FaceId(0), FaceId(54))));
    }

    #[test]
    fn open_surfaces_give_closed_shells() {
        use crate::mesh::BuildOptions;
        // an open box (a cube without its top), a flat 3 x 3 grid and an open tube
        let c = primitives::cube();
        let mut idx = Vec::new();
        for f in c.faces().skip(1) {
            idx.extend(c.face_vertices(f).map(|v| v.0 as i64));
        }
        let opts = BuildOptions { close_boundaries: true, ..Default::default() };
        let open_box = Mesh::from_polygons(c.positions().to_vec(), &[4; 5], &idx, opts).unwrap();
        let n = 6;
        let tube_pos: Vec<DVec3> = (0..2)
            .flat_map(|z| (0..n).map(move |i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                DVec3::new(t.cos(), t.sin(), z as f64)
            }))
            .collect();
        let tube_idx: Vec<i64> = (0..n as i64).flat_map(|i| [i, (i + 1) % 6, 6 + (i + 1) % 6, 6 + i]).collect();
        let tube = Mesh::from_polygons(tube_pos, &[4; 6], &tube_idx, opts).unwrap();
        for (m, genus) in [(open_box, 0), (tube, 1)] {
            let r = m.rind(0.1).unwrap();
            let s = r.mesh();
            s.validate().unwrap();
            assert!(s.is_closed());
            assert_eq!((s.euler_characteristic(), s.n_components(), s.genus()), (2 * m.euler_characteristic(), 1, genus));
            assert_eq!(r.punched_faces().len(), m.n_boundary_loops());
            assert!(s.signed_volume() > 0.0);
        }
    }

    #[test]
    fn punching_counts() {
        let m = grid_cube(3);
        let centres = centre_faces(&m, 3);
        assert_eq!(centres.len(), 6);
        let mut r = m.rind(0.2).unwrap();
        for (k, &f) in centres.iter().enumerate() {
            let (v, e, ff, c, g) = counts(r.mesh());
            r.punch(&[f]).unwrap();
            let (c2, g2) = if k == 0 { (c - 1, g) } else { (c, g + 1) };
            assert_eq!(counts(r.mesh()), (v, e + 4, ff + 2, c2, g2));
        }
        assert_eq!(r.mesh().genus(), 5);
        assert_eq!(r.punched_faces(), {
            let mut s = centres.clone();
            s.sort();
            s
        });
    }

    #[test]
    fn peeling_a_strip_leaves_one_hole() {
        let m = grid_cube(3);
        // the three faces of the middle row on the top side (z = 1)
        let c = m.face_centroids();
        let mut strip: Vec<usize> = (0..m.n_faces()).filter(|&f| (c[f].z - 1.0).abs() < 1e-9 && c[f].y.abs() < 1e-9).collect();
        strip.sort_by(|&a, &b| c[a].x.partial_cmp(&c[b].x).unwrap());
        assert_eq!(strip.len(), 3);
        let mut r = m.rind(0.2).unwrap();
        r.peel(&strip).unwrap();
        let (v, _, _, comps, g) = counts(r.mesh());
        assert_eq!((comps, g), (1, 0));
        // the two walls' end vertices merged their pipe edges: no vertex lost
        assert_eq!(v, 2 * 56);
        // punching instead leaves two handles (walls)
        let mut p = m.rind(0.2).unwrap();
        p.punch(&strip).unwrap();
        assert_eq!(p.mesh().genus(), 2);
        // each wall: 2 quads, 4 edges (outer, inner, two pipe edges) fewer
        assert_eq!(p.mesh().n_faces() - r.mesh().n_faces(), 2 * 2);
        assert_eq!(p.mesh().n_edges() - r.mesh().n_edges(), 2 * 4);
    }

    #[test]
    fn peeling_a_block_removes_its_inner_vertex() {
        // 2 × 2 block around a vertex of a 4 × 4 grid face: one hole, the
        // centre vertex and its inner twin vanish
        let m = grid_cube(4);
        let c = m.face_centroids();
        let block: Vec<usize> = (0..m.n_faces())
            .filter(|&f| (c[f].z - 1.0).abs() < 1e-9 && c[f].x.abs() < 0.5 && c[f].y.abs() < 0.5)
            .collect();
        assert_eq!(block.len(), 4);
        let mut r = m.rind(0.1).unwrap();
        let v0 = r.mesh().n_vertices() as i64;
        r.peel(&block).unwrap();
        let (v, _, _, comps, g) = counts(r.mesh());
        assert_eq!((comps, g), (1, 0));
        assert_eq!(v, v0 - 2);
    }

    /// χ of the part M of `m` left after removing the faces in `gone`
    /// (faces, edges and vertices touching a kept face).
    fn chi_of_rest(m: &Mesh, gone: &[bool]) -> i64 {
        let keep = |h: HalfedgeId| !gone[m.face(h).idx()];
        let f = gone.iter().filter(|&&g| !g).count() as i64;
        let e = m.edges().filter(|e| keep(e.halfedge()) || keep(e.halfedge().twin())).count() as i64;
        // the corners at v are its outgoing half-edges
        let v = m.vertices().filter(|&v| m.vertex_halfedges(v).any(keep)).count() as i64;
        v - e + f
    }

    #[test]
    fn random_peels_double_the_rest() {
        // peeling any set S of faces gives the double of M = mesh − S: χ = 2χ(M)
        let mut rng = crate::test_rng::Xorshift::new(0x9e3779b97f4a7c15);
        let mut rnd = move |n: usize| (rng.next_u64() % n as u64) as usize;
        for src in [grid_cube(3), primitives::torus(6, 4, 1.0, 0.4).unwrap(), primitives::cube()] {
            let nf = src.n_faces();
            for _ in 0..40 {
                let mut r = src.rind(0.1).unwrap();
                let mut gone = vec![false; nf];
                let k = 1 + rnd(nf - 1); // peeling all is refused (below)
                let mut order: Vec<usize> = (0..nf).collect();
                for i in 0..nf {
                    order.swap(i, i + rnd(nf - i));
                }
                // peel in a few batches
                let chosen = &order[..k];
                for batch in chosen.chunks(1 + rnd(4)) {
                    r.peel(batch).unwrap();
                    for &f in batch {
                        gone[f] = true;
                    }
                    r.mesh().validate().unwrap();
                    assert_eq!(r.mesh().euler_characteristic(), 2 * chi_of_rest(&src, &gone));
                }
                // the unpeeled faces still have their twins, and can be punched
                if let Some(f) = (0..nf).find(|&f| !gone[f]) {
                    let chi = r.mesh().euler_characteristic();
                    r.punch(&[f]).unwrap();
                    assert_eq!(r.mesh().euler_characteristic(), chi - 2);
                }
            }
            // peeling everything would leave nothing: refused, the rind unchanged
            let mut r = src.rind(0.1).unwrap();
            let before = counts(r.mesh());
            let e = r.peel(&(0..nf).collect::<Vec<_>>()).unwrap_err();
            assert!(e.to_string().contains("would leave nothing"), "{e}");
            assert_eq!(counts(r.mesh()), before);
        }
    }

    #[test]
    fn errors_name_the_face() {
        let m = primitives::cube();
        let msg = |e: MeshError| e.to_string();
        assert!(msg(m.rind(0.0).unwrap_err()).contains("thickness"));
        assert!(msg(m.rind(f64::NAN).unwrap_err()).contains("thickness"));
        // the cube's vertex normals are diagonal: a thickness past √3 turns faces over
        assert!(msg(m.rind(2.0).unwrap_err()).contains("flips the inner twin of face"));
        let mut r = m.rind(0.3).unwrap();
        assert!(msg(r.punch(&[7]).unwrap_err()).contains("face 7 is on the inner shell"));
        assert!(msg(r.punch(&[12]).unwrap_err()).contains("out of range"));
        r.punch(&[2]).unwrap();
        let before = r.mesh().clone();
        assert!(msg(r.punch(&[0, 2]).unwrap_err()).contains("face 2 is already punched"));
        assert!(msg(r.peel(&[1, 1]).unwrap_err()).contains("twice"));
        assert_eq!(r.mesh(), &before);
    }
}

//! Multi-face handle (TopMod's `multiConnectFaces`, both algorithms of its
//! UI, `include/dlflaux/DLFLMultiConnect.cc`, the only description) and
//! rind by scaling (`createCrustWithScaling`, `include/dlflaux/DLFLCrust.cc`).
//!
//! Multi-face handle: the vertices of the k selected faces, each moved
//! `extrude` along its face's unit normal and scaled by `scale` about their
//! centroid, span a convex hull, the hub; every selected face whose moved
//! copy is a face of the hub is joined to it by CreatePipe. On one
//! component: V + Σnᵢ, the hub's E and F added, then each pipe E + nᵢ,
//! F − 2; the first pipe joins the hub (components −1), each further one
//! adds a handle: genus + k − 1.
//!
//! Closest-edge algorithm (`multiConnectFaces(obj, faces)`, TopMod's
//! *closest edge* choice): every pair of sides of two different selected
//! faces is a candidate bridge, the quad `[a, b, c, d]` of side a→b of one
//! face and side c→d of the other. A candidate is kept when that quad is
//! planar within 5° (the dot product of its normals at two opposite
//! corners, taken at points a quarter along the sides, above cos 5°) and
//! its normal is not within 5° of the normal of the plane through the two
//! faces' centroids and the selection's centroid (TopMod; where that plane
//! is undefined, always with two faces and with centroids in line to a
//! relative 1e-10, the test is left out, where TopMod refuses every pair).
//! Candidates are taken by increasing distance of the sides'
//! midpoints, each side used once; each bridge is two InsertEdges, a–d and
//! b–c, either left out when those corners are already neighbours (a bridge
//! beside an earlier one shares its edge). Last, TopMod's `edgeCleanup` of
//! the new edges: one with the same face on both sides, or between faces
//! whose unit normals agree within 1e-5, is deleted. TopMod sorts every
//! pair of selected sides (quadratic in their number); `closest_sides` finds
//! the same bridges in the same order with a k-d tree (n log n when most
//! sides have a valid partner nearby, quadratic only when few have); the
//! counts follow the operators: per InsertEdge E + 1 and F + 1 (a face split)
//! or genus + 1 / components − 1 (two faces joined), per deletion their
//! inverse.

use super::hull::convex_hull;
use crate::error::{MeshError, Result};
use crate::mesh::{Corner, FaceId, HalfedgeId, Mesh};
use crate::ops::Rind;
use glam::DVec3;

/// How `bridge_pairs` finds the closest-edge bridges.
enum Search {
    Tree,
    #[cfg(test)]
    Brute,
}

impl Mesh {
    /// The disjoint union of this mesh and `other` (other's vertices, faces
    /// and half-edges numbered after this one's; this mesh's ids unchanged,
    /// which the local crossing check relies on). The columns are
    /// concatenated with offsets: twins stay `h ^ 1` because every mesh has
    /// an even number of half-edges. (It was a rebuild through
    /// `from_corner_twins`: 5 of the 5.6 ms a convex-hull handle took on a
    /// 100k-face mesh.)
    pub(crate) fn disjoint_union(&self, other: &Mesh) -> Result<Mesh> {
        use crate::mesh::{MAX_ELEMENTS, POINT};
        let (nv, nh, nf) = (self.n_vertices(), self.n_halfedges(), self.n_faces());
        if nv + other.n_vertices() > MAX_ELEMENTS || nh + other.n_halfedges() > MAX_ELEMENTS || nf + other.n_faces() > MAX_ELEMENTS {
            return Err(MeshError::InvalidArgument(format!("disjoint union: more than {MAX_ELEMENTS} elements of one kind")));
        }
        let (nv, nh, nf) = (nv as u32, nh as u32, nf as u32);
        let cat = |a: &[u32], b: &[u32], shift: &dyn Fn(u32) -> u32| -> Vec<u32> {
            let mut v = Vec::with_capacity(a.len() + b.len());
            v.extend_from_slice(a);
            v.extend(b.iter().map(|&x| shift(x)));
            v
        };
        // point-sphere links carry a flag and the id of the other kind
        let v_out = cat(&self.v_out, &other.v_out, &|o| if o & POINT != 0 { POINT | ((o & !POINT) + nf) } else { o + nh });
        let f_start = cat(&self.f_start, &other.f_start, &|s| if s & POINT != 0 { POINT | ((s & !POINT) + nv) } else { s + nh });
        let mut pos = Vec::with_capacity(self.pos.len() + other.pos.len());
        pos.extend_from_slice(&self.pos);
        pos.extend_from_slice(&other.pos);
        let mut f_hole = self.f_hole.clone();
        f_hole.extend_from_slice(&other.f_hole);
        let u = Mesh {
            pos,
            v_out,
            he_next: cat(&self.he_next, &other.he_next, &|h| h + nh),
            he_prev: cat(&self.he_prev, &other.he_prev, &|h| h + nh),
            he_vert: cat(&self.he_vert, &other.he_vert, &|v| v + nv),
            he_face: cat(&self.he_face, &other.he_face, &|f| f + nf),
            f_start,
            f_hole,
        };
        debug_assert!(u.validate().is_ok());
        Ok(u)
    }

    /// The selection of both multi-face handles: at least two distinct faces
    /// in range, none a hole or a point-sphere.
    fn check_handle_faces(&self, name: &str, faces: &[usize]) -> Result<()> {
        if faces.len() < 2 {
            return Err(MeshError::InvalidArgument(format!("{name}: {} faces given; at least 2 are needed", faces.len())));
        }
        let nf = self.n_faces();
        for (i, &f) in faces.iter().enumerate() {
            if f >= nf {
                return Err(MeshError::InvalidArgument(format!("{name}: face {f} out of range (mesh has {nf} faces)")));
            }
            if faces[..i].contains(&f) {
                return Err(MeshError::InvalidArgument(format!("{name}: face {f} is selected twice")));
            }
            let fid = FaceId::new(f);
            if self.is_hole(fid) || self.face_halfedge(fid).is_none() {
                return Err(MeshError::Precondition(format!("{name}: face {f} is a hole or a point-sphere")));
            }
        }
        Ok(())
    }

    /// **Multi-face handle** through a convex hub (module docs): `faces`
    /// (at least two, distinct, not holes) are each joined to the hull of
    /// their vertices moved `extrude` along their normals and scaled by
    /// `scale` about the centroid. A hub outside the solid (the faces look
    /// at it) is a solid blob; a hub behind the first face (negative
    /// `extrude`, inside the solid) is turned inside out into a cavity, as
    /// TopMod does.
    ///
    /// Errors: fewer than two faces, repeats, out of range, point-spheres;
    /// a non-positive or non-finite `scale`; a moved face that is not a
    /// face of the hub (its vertices hidden inside, or merged with
    /// another's: choose a larger `extrude` or fewer faces); a hull without
    /// volume.
    pub fn multi_face_handle(&self, faces: &[usize], scale: f64, extrude: f64) -> Result<Mesh> {
        self.check_handle_faces("multi_face_handle", faces)?;
        if !(scale.is_finite() && scale > 0.0) || !extrude.is_finite() {
            return Err(MeshError::InvalidArgument(format!(
                "multi_face_handle: scale = {scale} must be finite and positive, extrude = {extrude} finite"
            )));
        }
        // meshes at 1e±300 are joined at unit size, the extrusion with them
        crate::geometry::scale_free(self, |m, s| m.multi_face_handle_unscaled(faces, scale, extrude / s))
    }

    fn multi_face_handle_unscaled(&self, faces: &[usize], scale: f64, extrude: f64) -> Result<Mesh> {
        // moved copies: point k of face i is its k-th corner from the first
        let mut pts = Vec::new();
        let mut owner = Vec::new();
        let mut corners: Vec<Vec<HalfedgeId>> = Vec::new();
        for (i, &f) in faces.iter().enumerate() {
            let fid = FaceId::new(f);
            let n = self.face_unit_normal(fid);
            if n == DVec3::ZERO {
                return Err(MeshError::Precondition(format!("multi_face_handle: face {f} has no normal (zero area)")));
            }
            let hs: Vec<HalfedgeId> = self.face_halfedges(fid).collect();
            for &h in &hs {
                pts.push(self.position(self.vertex(h)) + extrude * n);
                owner.push(i);
            }
            corners.push(hs);
        }
        let c = pts.iter().sum::<DVec3>() / pts.len() as f64;
        for p in pts.iter_mut() {
            *p = c + (*p - c) * scale;
        }
        let (hub, src) = convex_hull(&pts)?;
        // the hub face of each selected face: all of its moved corners, nothing else
        let mut hub_corner = vec![None; faces.len()];
        for hf in hub.faces() {
            let vs: Vec<usize> = hub.face_vertices(hf).map(|v| src[v.idx()]).collect();
            let i = owner[vs[0]];
            if vs.len() == corners[i].len() && vs.iter().all(|&s| owner[s] == i) {
                // the hub corner at the copy of the face's first corner
                let first = (0..owner.len()).find(|&s| owner[s] == i).unwrap();
                let h = hub.face_halfedges(hf).find(|&h| src[hub.vertex(h).idx()] == first).unwrap();
                hub_corner[i] = Some(h);
            }
        }
        if let Some(i) = hub_corner.iter().position(|c| c.is_none()) {
            return Err(MeshError::Precondition(format!(
                "multi_face_handle: the moved copy of face {} is not a face of the hub (its corners are hidden inside the hull or share a plane with another face's); use a larger extrude or other faces",
                faces[i]
            )));
        }
        // a hub behind the faces is a cavity (TopMod looks at the first face
        // only; faces on both sides of the hub would pipe through it)
        let hub_c = hub.positions().iter().sum::<DVec3>() / hub.n_vertices() as f64;
        let behind = |i: usize| {
            let n = self.face_newell(FaceId::new(faces[i]));
            let fc = corners[i].iter().map(|&h| self.position(self.vertex(h))).sum::<DVec3>() / corners[i].len() as f64;
            n.dot(fc - hub_c) > 0.0
        };
        let cavity = behind(0);
        if let Some(i) = (1..faces.len()).find(|&i| behind(i) != cavity) {
            return Err(MeshError::Precondition(format!(
                "multi_face_handle: faces {} and {} face the hub from opposite sides (one looks at it, the other away)",
                faces[0], faces[i]
            )));
        }
        let hub = if cavity { hub.reversed()? } else { hub };
        let mut m = self.disjoint_union(&hub)?;
        let voff = self.n_vertices() as u32;
        // hub vertex of each moved point
        let mut hub_vertex = vec![u32::MAX; pts.len()];
        for (hv, &s) in src.iter().enumerate() {
            hub_vertex[s] = voff + hv as u32;
        }
        // sides are found by their end vertices, whose ids pipes never change
        let side = |m: &Mesh, a: u32, b: u32| -> Option<HalfedgeId> {
            m.vertex_halfedges(crate::mesh::VertexId(a)).find(|&h| m.head(h).0 == b)
        };
        let mut first = 0usize;
        for hs in corners.iter() {
            let n = hs.len();
            let (v0, v1) = (self.vertex(hs[0]).0, self.vertex(hs[1 % n]).0);
            // the hub's copy runs the other way round (the faces look at each other)
            let (w0, wl) = (hub_vertex[first], hub_vertex[first + n - 1]);
            first += n;
            let c1 = side(&m, v0, v1).expect("selected face side");
            let c2 = side(&m, w0, wl)
                .filter(|&h| m.face_degree(m.face(h)) == n)
                .ok_or_else(|| MeshError::Invariant("multi_face_handle: the hub face of a selected face is not where expected".into()))?;
            m.create_pipe(Corner::Halfedge(c1), Corner::Halfedge(c2))?;
        }
        Ok(m)
    }

    /// **Multi-face handle, closest-edge algorithm** (module docs): bridges
    /// between the nearest sides of the `faces` (at least two, distinct, not
    /// holes or point-spheres). Returns the mesh and the number of bridges.
    ///
    /// Errors: fewer than two faces, repeats, out of range, point-spheres,
    /// holes; no candidate bridge (no pair of sides spans a planar quad).
    pub fn multi_face_handle_edges(&self, faces: &[usize]) -> Result<(Mesh, usize)> {
        let name = "multi_face_handle(algorithm='closest_edge')";
        self.check_handle_faces(name, faces)?;
        let (sides, pairs) = self.bridge_pairs(faces, Search::Tree)?;
        if pairs.is_empty() {
            return Err(MeshError::Precondition(format!("{name}: no two sides of different faces span a planar quad (within 5°); nothing to bridge")));
        }
        let mut m = self.clone();
        let first_new = m.n_edges();
        let mut bridges = 0;
        for &(x, y) in &pairs {
            let (h1, h2) = (sides[x].1, sides[y].1);
            let (n1, n2) = (m.next(h1), m.next(h2));
            let neighbours = |m: &Mesh, u: HalfedgeId, w: HalfedgeId| m.next(u) == w || m.prev(u) == w;
            for (u, w) in [(h1, n2), (n1, h2)] {
                if !neighbours(&m, u, w) {
                    m.insert_edge(Corner::Halfedge(u), Corner::Halfedge(w))?;
                }
            }
            bridges += 1;
        }
        // TopMod's edgeCleanup of the new edges, all at once (one DeleteEdge
        // at a time relabels the growing merged face each time: a second for
        // two 16,000-gon caps)
        let normal = |m: &Mesh, f: FaceId| m.face_unit_normal(f);
        let doomed: Vec<usize> = (first_new..m.n_edges())
            .filter(|&e| {
                let h = HalfedgeId::new(2 * e);
                let (f, g) = (m.face(h), m.face(h.twin()));
                f == g || (normal(&m, f).dot(normal(&m, g)) - 1.0).abs() < 1e-5
            })
            .collect();
        m.delete_edges(&doomed.iter().map(|&e| crate::mesh::EdgeId(e as u32)).collect::<Vec<_>>())?;
        Ok((m, bridges))
    }

    /// The closest-edge handle's bridges (module docs): the selected faces'
    /// sides (face's index in `faces`, half-edge) and pairs of indices into
    /// them (lower first), in the order TopMod's sorted candidate list
    /// takes them; `Search::Brute` builds that list (quadratic), the tree
    /// finds the same pairs without it (`closest_sides`).
    fn bridge_pairs(&self, faces: &[usize], search: Search) -> Result<(Vec<(usize, HalfedgeId)>, Vec<(usize, usize)>)> {
        let p = |h: HalfedgeId| self.position(self.vertex(h));
        let q = |h: HalfedgeId| self.position(self.head(h));
        let cen: Vec<DVec3> = faces
            .iter()
            .map(|&f| {
                let hs: Vec<HalfedgeId> = self.face_halfedges(FaceId::new(f)).collect();
                hs.iter().map(|&h| p(h)).sum::<DVec3>() / hs.len() as f64
            })
            .collect();
        let cc = cen.iter().sum::<DVec3>() / cen.len() as f64;
        let sides: Vec<(usize, HalfedgeId)> = faces.iter().enumerate().flat_map(|(i, &f)| self.face_halfedges(FaceId::new(f)).map(move |h| (i, h))).collect();
        let cos5 = 5f64.to_radians().cos();
        // side x (a → b) and side y (c → d), x < y, as TopMod computes them
        let dist = |x: usize, y: usize| {
            let ((_, h1), (_, h2)) = (sides[x], sides[y]);
            ((p(h1) + q(h1)) - (p(h2) + q(h2))).length() * 0.5
        };
        let valid = |x: usize, y: usize| {
            let ((i, h1), (j, h2)) = (sides[x], sides[y]);
            let (a, b, c, d) = (p(h1), q(h1), p(h2), q(h2));
            let (a1, b1) = (0.75 * a + 0.25 * b, 0.25 * a + 0.75 * b);
            let (c1, d1) = (0.75 * c + 0.25 * d, 0.25 * c + 0.75 * d);
            let n11 = (d1 - a1).cross(b1 - a1).normalize_or_zero();
            let n21 = (b1 - c1).cross(d1 - c1).normalize_or_zero();
            let normal = (n11 + n21).normalize_or_zero();
            // undefined (the test left out) when the centroids are collinear
            // with cc up to rounding: normalizing that rounding noise gave an
            // arbitrary direction, which refused the bridges of two facing
            // caps near one arbitrary plane (TopMod normalizes above 1e-10,
            // an absolute size, and refuses every pair with two faces)
            let (u, v) = (cen[i] - cc, cen[j] - cc);
            let c = u.cross(v);
            let plane = if c.length() <= 1e-10 * u.length() * v.length() { DVec3::ZERO } else { c.normalize_or_zero() };
            let faces_ok = plane == DVec3::ZERO || plane.dot(normal).abs() < cos5;
            n11.dot(n21) > cos5 && faces_ok
        };
        let group: Vec<u32> = sides.iter().map(|&(i, _)| i as u32).collect();
        let pairs = match search {
            Search::Tree => {
                let mid: Vec<DVec3> = sides.iter().map(|&(_, h)| (p(h) + q(h)) * 0.5).collect();
                super::closest_sides::greedy_pairs(&mid, &group, dist, valid)?
            }
            #[cfg(test)]
            Search::Brute => super::closest_sides::brute_pairs_for_tests(sides.len(), &group, dist, valid),
        };
        Ok((sides, pairs))
    }

    /// The mesh with every face's orientation reversed: half-edge h keeps
    /// its id and edge but runs the other way.
    pub(crate) fn reversed(&self) -> Result<Mesh> {
        let mut m = self.clone();
        for h in 0..m.n_halfedges() {
            let hh = HalfedgeId::new(h);
            m.he_vert[h] = self.head(hh).0;
        }
        std::mem::swap(&mut m.he_next, &mut m.he_prev);
        for v in self.vertices() {
            if let Some(h) = self.vertex_halfedge(v) {
                m.v_out[v.idx()] = h.twin().0;
            }
        }
        m.validate()?;
        Ok(m)
    }

    /// **Rind by scaling** (TopMod's `createCrustWithScaling`): the offset
    /// shell is a copy scaled by `scale` about the vertex centroid — inside
    /// for 0 < scale < 1 (the copy is the inner shell); for scale > 1 the
    /// scaled copy is the outer shell and the mesh itself the inner one
    /// (TopMod's negative factor s ∈ [−1, 0) is scale = −1/s here). Faces
    /// and punching as [`Mesh::rind`].
    pub fn rind_by_scaling(&self, scale: f64) -> Result<Rind> {
        if !(scale.is_finite() && scale > 0.0) || scale == 1.0 {
            return Err(MeshError::InvalidArgument(format!(
                "rind_by_scaling: scale = {scale} must be finite, positive and not 1 (below 1 the copy is inside, above 1 outside)"
            )));
        }
        if let Some(f) = self.faces().find(|&f| self.face_halfedge(f).is_none()) {
            return Err(MeshError::Precondition(format!("rind_by_scaling: face {} is a point-sphere; it has no rind", f.0)));
        }
        let nv = self.n_vertices();
        let c = self.positions().iter().sum::<DVec3>() / nv.max(1) as f64;
        let scaled = |p: DVec3, s: f64| c + (p - c) * s;
        let mut pos = Vec::with_capacity(2 * nv);
        if scale < 1.0 {
            pos.extend_from_slice(self.positions());
            pos.extend(self.positions().iter().map(|&p| scaled(p, scale)));
        } else {
            pos.extend(self.positions().iter().map(|&p| scaled(p, scale)));
            pos.extend_from_slice(self.positions());
        }
        let src = if scale < 1.0 { self.clone() } else { let mut s = self.clone(); for p in s.positions_mut() { *p = scaled(*p, scale); } s };
        Rind::from_shell(&src, pos, &format!("scale {}", crate::error::num(scale)))
    }
}


#[cfg(test)]
mod tests {
    use super::super::super::testing::*;
    use super::Search;
    use crate::primitives;

    fn face_at(m: &crate::Mesh, p: [f64; 3]) -> usize {
        let cs = m.face_centroids();
        (0..m.n_faces()).find(|&i| (cs[i] - glam::DVec3::from_array(p)).length() < 1e-9).unwrap()
    }

    #[test]
    fn disjoint_union_keeps_both_meshes_ids() {
        // the columns concatenated: this mesh's ids unchanged, the other's
        // shifted; both meshes' polygons and twins come back as given, for
        // self-loops, two-gons, point-spheres and boundaries too
        use crate::schemes::hosts::test_meshes::{corpus, open_meshes};
        let all: Vec<_> = corpus().into_iter().chain(open_meshes()).collect();
        for (an, a) in &all {
            for (bn, b) in all.iter().step_by(3) {
                let u = a.disjoint_union(b).unwrap();
                u.validate().unwrap_or_else(|e| panic!("{an} + {bn}: {e}"));
                let ((sa, ia), (sb, ib), (su, iu)) = (a.polygons_i64(), b.polygons_i64(), u.polygons_i64());
                let nv = a.n_vertices() as i64;
                assert_eq!(su, [sa, sb].concat(), "{an} + {bn}");
                assert_eq!(iu, ia.iter().copied().chain(ib.iter().map(|&i| i + nv)).collect::<Vec<_>>(), "{an} + {bn}");
                let (ta, tb) = (a.corner_twins(), b.corner_twins());
                let off = ta.len() as i64;
                let want: Vec<i64> = ta.iter().copied().chain(tb.iter().map(|&t| if t >= 0 { t + off } else { t })).collect();
                assert_eq!(u.corner_twins(), want, "{an} + {bn}");
                assert_eq!(&u.positions()[..a.n_vertices()], a.positions());
                assert_eq!(u.n_holes(), a.n_holes() + b.n_holes());
                for f in 0..a.n_faces() {
                    let f = crate::FaceId::new(f);
                    assert_eq!(u.face_halfedges(f).collect::<Vec<_>>(), a.face_halfedges(f).collect::<Vec<_>>(), "{an}: face ids and corners kept");
                }
            }
        }
    }

    #[test]
    fn three_cubes_join_at_a_hub() {
        // faces looking at a common point: the hub is a solid blob
        let mut m = primitives::cube();
        for t in [[-3., 0., 0.], [3., 0., 0.], [0., 4., 0.]] {
            let mut c = primitives::cube();
            for p in c.positions_mut() {
                *p += glam::DVec3::from_array(t);
            }
            m = m.disjoint_union(&c).unwrap();
        }
        let sel = [face_at(&m, [-2., 0., 0.]), face_at(&m, [2., 0., 0.]), face_at(&m, [0., 3., 0.])];
        let (v, _, _, c, g) = counts(&m);
        assert_eq!(c, 4);
        let r = m.multi_face_handle(&sel, 1.0, 0.5).unwrap();
        assert_eq!(counts(&r).0, v + 12);
        assert_eq!((counts(&r).3, counts(&r).4), (c - 2, g));
        assert!(m.multi_face_handle(&sel[..1], 1.0, 0.5).is_err());
        assert!(m.multi_face_handle(&[sel[0], sel[0]], 1.0, 0.5).is_err());
        // the faces themselves (no extrusion) span the hub too
        assert!(m.multi_face_handle(&sel, 1.0, 0.0).is_ok());
    }

    #[test]
    fn closest_edges_make_a_tube() {
        // two cubes with facing faces: four bridges, the tube of a CreatePipe
        let mut m = primitives::cube();
        let mut c = primitives::cube();
        for p in c.positions_mut() {
            p.x += 3.0;
        }
        m = m.disjoint_union(&c).unwrap();
        let sel = [face_at(&m, [1., 0., 0.]), face_at(&m, [2., 0., 0.])];
        let (r, k) = m.multi_face_handle_edges(&sel).unwrap();
        assert_eq!(k, 4);
        assert_eq!(counts(&r), (16, 28, 14, 1, 0));
        // three faces of one grid cube: bridges between the nearest sides, a valid mesh
        let g = grid_cube(3);
        let sel = [face_at(&g, [1., 0., 0.]), face_at(&g, [0., 1., 0.]), face_at(&g, [0., 0., 1.])];
        let (r, k) = g.multi_face_handle_edges(&sel).unwrap();
        assert!(k >= 1);
        let (v, e, _, _, _) = counts(&r);
        let (v0, e0, _, _, _) = counts(&g);
        assert_eq!(v, v0);
        assert!(e > e0);
        assert!(g.multi_face_handle_edges(&sel[..1]).is_err());
        assert!(g.multi_face_handle_edges(&[sel[0], sel[0]]).unwrap_err().to_string().contains("twice"));
    }


    #[test]
    fn bridges_are_topmods_sorted_pairs() {
        // the tree search against TopMod's sorted list of every pair: prism
        // and antiprism caps (all bridges at one distance: ties), faces of a
        // grid cube and of a jittered torus, two to five faces
        use crate::schemes::conway::seeds;
        let mut meshes: Vec<(String, crate::Mesh, Vec<usize>)> = Vec::new();
        for n in [3, 4, 5, 17, 64, 301] {
            let m = seeds::prism(n).unwrap();
            let caps: Vec<usize> = (0..m.n_faces()).filter(|&f| m.face_degree(crate::FaceId::new(f)) == n).collect();
            meshes.push((format!("prism {n}"), m, caps));
            let m = seeds::antiprism(n).unwrap();
            let caps: Vec<usize> = (0..m.n_faces()).filter(|&f| m.face_degree(crate::FaceId::new(f)) == n).collect();
            meshes.push((format!("antiprism {n}"), m, caps));
        }
        let g = grid_cube(4);
        for sel in [vec![0, 20], vec![3, 40, 77], vec![1, 2, 3, 4, 5], vec![10, 11]] {
            meshes.push((format!("grid cube {sel:?}"), g.clone(), sel));
        }
        let mut t = primitives::torus(24, 12, 3.0, 1.0).unwrap();
        for (i, p) in t.positions_mut().iter_mut().enumerate() {
            p.z += ((i * 37 % 11) as f64 - 5.0) * 0.01;
        }
        for sel in [vec![0, 1], vec![0, 144], vec![5, 50, 150, 250], vec![7, 8, 31, 32]] {
            meshes.push((format!("torus {sel:?}"), t.clone(), sel));
        }
        let mut pairs = 0;
        for (name, m, sel) in &meshes {
            let (_, tree) = m.bridge_pairs(sel, Search::Tree).unwrap();
            let (_, brute) = m.bridge_pairs(sel, Search::Brute).unwrap();
            assert_eq!(tree, brute, "{name}");
            pairs += tree.len();
        }
        assert!(pairs > 400, "too few bridges to compare ({pairs})");
    }

    #[test]
    fn cavity_through_a_cube() {
        let m = grid_cube(3);
        let (_, _, _, c, g) = counts(&m);
        let sel = [face_at(&m, [0., 0., 1.]), face_at(&m, [0., 0., -1.]), face_at(&m, [1., 0., 0.])];
        let r = m.multi_face_handle(&sel, 0.5, -0.5).unwrap();
        assert_eq!((counts(&r).3, counts(&r).4), (c, g + 2));
        // the hub lies inside the cube
        assert!(r.positions()[m.n_vertices()..].iter().all(|p| p.abs().max_element() < 1.0));
    }

    #[test]
    fn rind_by_scaling_shells() {
        let m = primitives::dodecahedron();
        for s in [0.8, 1.25] {
            let r = m.rind_by_scaling(s).unwrap();
            let (v, e, f, c, g) = counts(r.mesh());
            assert_eq!((v, e, f, c, g), (40, 60, 24, 2, 0));
            let mut p = r.clone();
            p.punch(&[0, 3]).unwrap();
            assert_eq!(counts(p.mesh()).4, 1);
        }
        assert!(m.rind_by_scaling(1.0).is_err());
        assert!(m.rind_by_scaling(-0.5).is_err());
    }
}

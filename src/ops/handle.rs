//! Multi-segment curved handles (dissertation ch. IV).
//!
//! A handle between faces f1 and f2 is k − 1 intermediate cross-sections,
//! each made by CreateFaceManifold, joined by k CreatePipe operations
//! (IV.1). The sections follow the Hermite curve (eq. 4.1)
//!
//! H(t) = p1·h1(t) + p2·h2(t) + w1·n1·h3(t) − w2·n2·h4(t)
//!
//! from the centroid p1 of f1 along its unit normal n1 to the centroid p2 of
//! f2 against its normal n2 (IV.2); the weights are the tangent lengths, in
//! model units, and negative weights send the curve into the solid, making a
//! hole (tunnel) instead of a handle. Section shapes morph from f1 to f2 in
//! polar coordinates about their centroids (IV.3): both faces are rotated
//! onto the reference plane R normal to p2 − p1, resolved into (r, θ) with
//! θ increasing monotonically along each face and the first corners less
//! than 180° apart, interpolated linearly in t, then turned to face along
//! H'(t) and centred on H(t). The corners c1, c2 are matched with each other
//! (then around both faces), so choosing them sets the handle's twist. Faces
//! of different sizes are equalized first by SubdivideEdge, as for
//! CreatePipe.
//!
//! The rotation onto R is undefined when a face's travel direction is
//! exactly opposite to the chord (the dissertation ignores this case); a
//! half-turn about an arbitrary perpendicular axis is used then.

use crate::error::{MeshError, Result};
use crate::mesh::{Corner, HalfedgeId, Mesh};
use glam::{DQuat, DVec3};

/// What [`Mesh::add_handle`] made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Handle {
    /// Edges added to the smaller end face by SubdivideEdge first.
    pub subdivisions: usize,
    /// Corners per cross-section (N).
    pub corners: usize,
    /// The quads' first-face sides of each pipe segment, from f1 to f2.
    pub segments: Vec<Vec<HalfedgeId>>,
}

/// TopMod's pinch and twist of a handle (`hermiteConnectFaces`,
/// `include/dlflaux/DLFLConnect.cc`, the only description; TopMod's UI
/// shows these but its default handle tool passes none of them): each
/// section is scaled by a quadratic Bézier in t₂ from 1 at the ends to
/// `pinch` at `center` (t₂ = (t / center)^(1/width) before it,
/// (1 − (t − center)/(1 − center))^(1/width) after), and the second face's
/// angles gain `extra_twists` full turns.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct HandleShape {
    /// Section scale at the centre (1: no pinch; TopMod's range −10..10,
    /// here (0, 10]: zero or negative would collapse or flip sections).
    pub pinch: f64,
    /// Where along the handle (0, 1) the pinch is strongest.
    pub center: f64,
    /// TopMod's "pinch width" (bubble), in [0.001, 10]: above 1 the pinch
    /// spreads along the handle, below 1 it narrows.
    pub width: f64,
    /// Extra full turns of the sections from the first face to the second.
    pub extra_twists: u32,
}

impl Default for HandleShape {
    fn default() -> Self {
        HandleShape { pinch: 1.0, center: 0.5, width: 1.0, extra_twists: 0 }
    }
}

impl HandleShape {
    fn check(&self) -> Result<()> {
        let bad = |name: &str, x: f64, range: &str| {
            Err(MeshError::InvalidArgument(format!("add_handle: {name} = {} must be in {range}", crate::error::num(x))))
        };
        if !(self.pinch.is_finite() && self.pinch > 0.0 && self.pinch <= 10.0) {
            return bad("pinch", self.pinch, "(0, 10]");
        }
        if !(self.center > 0.0 && self.center < 1.0) {
            return bad("pinch_center", self.center, "(0, 1)");
        }
        if !(self.width >= 0.001 && self.width <= 10.0) {
            return bad("pinch_width", self.width, "[0.001, 10]");
        }
        if self.extra_twists > 100 {
            return bad("extra_twists", self.extra_twists as f64, "0..=100");
        }
        Ok(())
    }

    /// The section scale at t (TopMod's `pinch_scaling`).
    pub fn scaling(&self, t: f64) -> f64 {
        let c = self.center;
        let u = if t <= c { t / c } else { 1.0 - (t - c) / (1.0 - c) };
        let u = u.clamp(0.0, 1.0).powf(1.0 / self.width);
        (1.0 - u) * (1.0 - u) + 2.0 * (1.0 - u) * u * self.pinch + u * u * self.pinch
    }
}

fn hermite(t: f64) -> ([f64; 4], [f64; 4]) {
    let (t2, t3) = (t * t, t * t * t);
    (
        [2. * t3 - 3. * t2 + 1., -2. * t3 + 3. * t2, t3 - 2. * t2 + t, t3 - t2],
        [6. * t2 - 6. * t, -6. * t2 + 6. * t, 3. * t2 - 4. * t + 1., 3. * t2 - 2. * t],
    )
}

/// Unwraps angles so they increase along the sequence.
fn monotone(theta: &mut [f64]) {
    use std::f64::consts::TAU;
    for j in 1..theta.len() {
        while theta[j] < theta[j - 1] {
            theta[j] += TAU;
        }
    }
}

/// s = +1: a handle leaving f1 along its normal; s = −1: a tunnel leaving against it.
fn travel_sign(w1: f64, w2: f64, n1: DVec3, chord: DVec3) -> f64 {
    if w1 + w2 != 0.0 {
        (w1 + w2).signum()
    } else if n1.dot(chord) >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The two end faces resolved in polar coordinates on the reference plane R
/// (IV.3): entry j of each end sequence runs counter-clockwise about the
/// travel direction, the first entries of both being the chosen corners.
struct EndFrames {
    nr: DVec3,
    x_axis: DVec3,
    y_axis: DVec3,
    rad1: Vec<f64>,
    th1: Vec<f64>,
    rad2: Vec<f64>,
    th2: Vec<f64>,
}

impl EndFrames {
    /// `pa`, `pb`: corner positions of f1 from c1 and of f2 from c2, each in
    /// its face's order.
    fn new(pa: &[DVec3], pb: &[DVec3], p1: DVec3, p2: DVec3, n1: DVec3, n2: DVec3, s: f64) -> EndFrames {
        use std::f64::consts::{PI, TAU};
        let (d1, d2) = (s * n1, -s * n2); // travel directions at both ends
        let nr = (p2 - p1).normalize();
        let at = |v: &[DVec3], j: isize| v[j.rem_euclid(v.len() as isize) as usize];
        // f1 runs counter-clockwise about n1, f2 about n2: reverse as needed
        let q1: Vec<DVec3> = (0..pa.len() as isize).map(|j| at(pa, if s > 0.0 { j } else { -j })).collect();
        let q2: Vec<DVec3> = (0..pb.len() as isize).map(|j| at(pb, if s > 0.0 { -j } else { j })).collect();
        // rotate each end onto R about its centroid, and flatten into R
        let onto_r = |q: &[DVec3], c: DVec3, d: DVec3| -> Vec<DVec3> {
            let rot = DQuat::from_rotation_arc(d, nr);
            q.iter()
                .map(|&p| {
                    let x = rot * (p - c);
                    x - x.dot(nr) * nr
                })
                .collect()
        };
        let (r1, r2) = (onto_r(&q1, p1, d1), onto_r(&q2, p2, d2));
        // reference axes: X towards the midpoint of f1's last side
        let n = r1.len();
        let mut x_axis = (r1[n - 1] + r1[0]) * 0.5;
        if x_axis.length() < 1e-12 {
            x_axis = r1[0];
        }
        if x_axis.length() < 1e-12 {
            x_axis = nr.any_orthonormal_vector();
        }
        let x_axis = x_axis.normalize();
        let y_axis = nr.cross(x_axis);
        let polar = |r: &[DVec3]| -> (Vec<f64>, Vec<f64>) {
            let rad = r.iter().map(|p| p.length()).collect();
            let mut th: Vec<f64> = r.iter().map(|p| p.dot(y_axis).atan2(p.dot(x_axis))).collect();
            monotone(&mut th);
            (rad, th)
        };
        let (rad1, th1) = polar(&r1);
        let (rad2, mut th2) = polar(&r2);
        // first corners less than half a turn apart
        let shift = ((th1[0] - th2[0] + PI) / TAU).floor() * TAU;
        for t in th2.iter_mut() {
            *t += shift;
        }
        EndFrames { nr, x_axis, y_axis, rad1, th1, rad2, th2 }
    }
}

impl Mesh {
    /// A multi-segment curved handle (ch. IV.4) of `segments` segments from
    /// the face of corner `c1` to the face of corner `c2`, with Hermite
    /// tangent lengths `w1`, `w2` (negative: a tunnel through the solid).
    ///
    /// Contract, with d the splits that equalize the faces (as CreatePipe)
    /// and N the common size: V + d + N(k−1), E + d + N(2k−1),
    /// F + Nk − 2; one component: genus +1; two: components −1.
    ///
    /// Errors: the same face twice, faces sharing an edge, a point-sphere
    /// face, `segments` = 0, non-finite weights or weights of opposite signs,
    /// coincident face centroids, a degenerate (zero-area) face.
    pub fn add_handle(&mut self, c1: HalfedgeId, c2: HalfedgeId, segments: usize, w1: f64, w2: f64) -> Result<Handle> {
        self.add_handle_shaped(c1, c2, segments, w1, w2, HandleShape::default())
    }

    /// [`Mesh::add_handle`] with TopMod's pinch and twist parameters
    /// ([`HandleShape`]); the default shape is `add_handle` itself.
    pub fn add_handle_shaped(&mut self, c1: HalfedgeId, c2: HalfedgeId, segments: usize, w1: f64, w2: f64, shape: HandleShape) -> Result<Handle> {
        shape.check()?;
        super::check_halfedge(self, c1)?;
        super::check_halfedge(self, c2)?;
        let (f1, f2) = (self.face(c1), self.face(c2));
        if f1 == f2 {
            return Err(MeshError::Precondition(format!("add_handle: both corners are in face {}", f1.0)));
        }
        if self.face_halfedges(f1).any(|h| self.face(h.twin()) == f2) {
            return Err(MeshError::Precondition(format!(
                "add_handle: faces {} and {} share an edge; a handle needs faces apart",
                f1.0, f2.0
            )));
        }
        if segments == 0 || segments > 100_000 {
            return Err(MeshError::InvalidArgument(format!("add_handle: segments = {segments} must be in 1..=100000")));
        }
        if !(w1.is_finite() && w2.is_finite()) || w1 * w2 < 0.0 {
            return Err(MeshError::InvalidArgument(format!(
                "add_handle: weights ({w1}, {w2}) must be finite and of one sign (both negative make a hole)"
            )));
        }
        let (p1, p2) = (self.face_centroids_of(f1), self.face_centroids_of(f2));
        let (n1, n2) = (self.face_unit_normal(f1), self.face_unit_normal(f2));
        for (f, n) in [(f1, n1), (f2, n2)] {
            if n == DVec3::ZERO {
                return Err(MeshError::Precondition(format!("add_handle: face {} has no normal (zero area)", f.0)));
            }
        }
        let chord = p2 - p1;
        if chord.length() <= 1e-12 * (1.0 + p1.length()) {
            return Err(MeshError::Precondition(format!(
                "add_handle: faces {} and {} have the same centroid",
                f1.0, f2.0
            )));
        }
        // equal sizes first; centroids are then taken over the new corners
        let (mut a, mut b) = (Corner::Halfedge(c1), Corner::Halfedge(c2));
        let subdivisions = self.equalize_faces(&mut a, &mut b, "add_handle")?;
        let (Corner::Halfedge(c1), Corner::Halfedge(c2)) = (a, b) else { unreachable!() };
        let ca: Vec<HalfedgeId> = self.face_halfedges_from(c1).collect();
        let cb: Vec<HalfedgeId> = self.face_halfedges_from(c2).collect();
        let n = ca.len();
        let pa: Vec<DVec3> = ca.iter().map(|&h| self.position(self.vertex(h))).collect();
        let pb: Vec<DVec3> = cb.iter().map(|&h| self.position(self.vertex(h))).collect();
        let (p1, p2) = (pa.iter().sum::<DVec3>() / n as f64, pb.iter().sum::<DVec3>() / n as f64);

        let s = travel_sign(w1, w2, n1, p2 - p1);
        let fr = EndFrames::new(&pa, &pb, p1, p2, n1, n2, s);
        let (nr, x_axis, y_axis) = (fr.nr, fr.x_axis, fr.y_axis);
        let (rad1, th1, rad2, th2) = (&fr.rad1, &fr.th1, &fr.rad2, &fr.th2);

        // sections at t = i/k (IV.4 step 4)
        let curve = |t: f64| -> (DVec3, DVec3) {
            let (h, dh) = hermite(t);
            let p = p1 * h[0] + p2 * h[1] + w1 * n1 * h[2] - w2 * n2 * h[3];
            let d = p1 * dh[0] + p2 * dh[1] + w1 * n1 * dh[2] - w2 * n2 * dh[3];
            (p, d)
        };
        let mut sections = Vec::with_capacity(segments - 1);
        for i in 1..segments {
            let t = i as f64 / segments as f64;
            let (p, d) = curve(t);
            let dir = if d.length() > 1e-12 { d.normalize() } else { nr };
            let rot = DQuat::from_rotation_arc(nr, dir);
            let pinch = shape.scaling(t);
            let turns = std::f64::consts::TAU * shape.extra_twists as f64;
            let pts: Vec<DVec3> = (0..n)
                .map(|j| {
                    let r = pinch * ((1. - t) * rad1[j] + t * rad2[j]);
                    let th = (1. - t) * th1[j] + t * (th2[j] + turns);
                    p + rot * (r * (th.cos() * x_axis + th.sin() * y_axis))
                })
                .collect();
            sections.push(self.create_face_manifold(&pts)?);
        }
        // pipes between facing faces (IV.1 step 2): a handle pairs each
        // section's back face with what precedes it, a tunnel its front face
        let mut prev = Corner::Halfedge(c1);
        let mut segs = Vec::with_capacity(segments);
        for sec in &sections {
            let (towards, away) = if s > 0.0 { (sec.back_corner, sec.front_corner) } else { (sec.front_corner, sec.back_corner) };
            segs.push(self.create_pipe(prev, towards)?.sides);
            prev = away;
        }
        segs.push(self.create_pipe(prev, Corner::Halfedge(c2))?.sides);
        Ok(Handle { subdivisions, corners: n, segments: segs })
    }

    /// The corner of the face of `c2` that [`Mesh::add_handle`] should
    /// match with `c1` for the least twist: the one whose polar angle on the
    /// reference plane is closest to that of `c1`.
    pub fn aligned_handle_corner(&self, c1: HalfedgeId, c2: HalfedgeId, w1: f64, w2: f64) -> Result<HalfedgeId> {
        super::check_halfedge(self, c1)?;
        super::check_halfedge(self, c2)?;
        let (f1, f2) = (self.face(c1), self.face(c2));
        let (p1, p2) = (self.face_centroids_of(f1), self.face_centroids_of(f2));
        let (n1, n2) = (self.face_unit_normal(f1), self.face_unit_normal(f2));
        if n1 == DVec3::ZERO || n2 == DVec3::ZERO || (p2 - p1).length() <= 1e-12 * (1.0 + p1.length()) {
            return Ok(c2);
        }
        let s = travel_sign(w1, w2, n1, p2 - p1);
        let pa: Vec<DVec3> = self.face_halfedges_from(c1).map(|h| self.position(self.vertex(h))).collect();
        let mut best = (f64::INFINITY, c2);
        for c in self.face_halfedges_from(c2) {
            let pb: Vec<DVec3> = self.face_halfedges_from(c).map(|h| self.position(self.vertex(h))).collect();
            let fr = EndFrames::new(&pa, &pb, p1, p2, n1, n2, s);
            let d = (fr.th2[0] - fr.th1[0]).abs();
            if d < best.0 - 1e-9 {
                best = (d, c);
            }
        }
        Ok(best.1)
    }

    fn face_centroids_of(&self, f: crate::mesh::FaceId) -> DVec3 {
        let (s, k) = self.face_vertices(f).fold((DVec3::ZERO, 0usize), |(s, k), v| (s + self.position(v), k + 1));
        s / k as f64
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use crate::mesh::{FaceId, HalfedgeId, Mesh};

    fn face_at(m: &Mesh, c: [f64; 3]) -> HalfedgeId {
        let cs = m.face_centroids();
        let f = (0..m.n_faces()).find(|&f| (cs[f] - glam::DVec3::from_array(c)).length() < 1e-9).expect("face");
        m.face_halfedge(FaceId::new(f)).unwrap()
    }

    #[test]
    fn tunnel_through_a_grid_cube() {
        let mut m = grid_cube(3);
        let (v, e, f, c, g) = counts(&m);
        let a = face_at(&m, [0., 0., 1.]);
        let b = face_at(&m, [0., 0., -1.]);
        let b = m.aligned_handle_corner(a, b, -1.0, -1.0).unwrap();
        let h = m.add_handle(a, b, 3, -1.0, -1.0).unwrap();
        let (n, k) = (4, 3);
        assert_eq!(h.corners, n as usize);
        assert_eq!(counts(&m), (v + n * (k - 1), e + n * (2 * k - 1), f + n * k - 2, c, g + 1));
        // the straight tunnel: every new vertex has |x|, |y| = 1/3 and z inside
        for p in &m.positions()[v as usize..] {
            assert!((p.x.abs() - 1. / 3.).abs() < 1e-9 && (p.y.abs() - 1. / 3.).abs() < 1e-9, "{p}");
            assert!(p.z.abs() < 1.0);
        }
    }

    #[test]
    fn arch_and_errors() {
        let mut m = grid_cube(5);
        let (v, e, f, c, g) = counts(&m);
        let a = face_at(&m, [-0.8, 0., 1.]);
        let b = face_at(&m, [0.8, 0., 1.]);
        m.add_handle(a, b, 6, 2.0, 2.0).unwrap();
        let (n, k) = (4, 6);
        assert_eq!(counts(&m), (v + n * (k - 1), e + n * (2 * k - 1), f + n * k - 2, c, g + 1));
        // the arch rises above the top face
        assert!(m.positions()[v as usize..].iter().all(|p| p.z > 1.0));
        let mut m = grid_cube(3);
        let a = face_at(&m, [0., 0., 1.]);
        let b = face_at(&m, [2. / 3., 0., 1.]);
        assert!(m.add_handle(a, b, 3, 1., 1.).unwrap_err().to_string().contains("share an edge"));
        let b = face_at(&m, [0., 0., -1.]);
        assert!(m.add_handle(a, a, 3, 1., 1.).is_err());
        assert!(m.add_handle(a, b, 0, 1., 1.).is_err());
        assert!(m.add_handle(a, b, 3, 1., -1.).is_err());
        assert_eq!(counts(&m), counts(&grid_cube(3)));
    }

    /// Winding number of a closed polygon about its centroid, seen along its
    /// Newell normal, and whether every turn is positive (a star about it).
    fn star_winding(pts: &[glam::DVec3]) -> (f64, bool) {
        let c = pts.iter().sum::<glam::DVec3>() / pts.len() as f64;
        let mut n = glam::DVec3::ZERO;
        for i in 0..pts.len() {
            n += pts[i].cross(pts[(i + 1) % pts.len()]);
        }
        let n = n.normalize();
        let mut total = 0.0;
        let mut all_positive = true;
        for i in 0..pts.len() {
            let (a, b) = (pts[i] - c, pts[(i + 1) % pts.len()] - c);
            let turn = n.dot(a.cross(b)).atan2(a.dot(b));
            all_positive &= turn > 0.0;
            total += turn;
        }
        (total / std::f64::consts::TAU, all_positive)
    }

    #[test]
    fn sections_are_star_shaped_between_unlike_faces() {
        // a quad (cube top) to a long, thin, rotated hexagon far away: every
        // intermediate section winds once around its centre with positive turns
        for twist in 0..6 {
            let mut m = grid_cube(1);
            let hex: Vec<glam::DVec3> = (0..6)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::TAU / 6.0 + 0.4;
                    glam::DVec3::new(3.0 + 0.2 * a.sin(), 2.0 * a.cos(), 5.0 + 0.3 * a.cos())
                })
                .collect();
            let fm = m.create_face_manifold(&hex).unwrap();
            let top = face_at(&m, [0., 0., 1.]);
            let crate::Corner::Halfedge(back) = fm.back_corner else { panic!() };
            let mut c2 = back;
            for _ in 0..twist {
                c2 = m.next(c2);
            }
            let nv = m.n_vertices();
            let h = m.add_handle(top, c2, 7, 4.0, 4.0).unwrap();
            assert_eq!((h.corners, h.subdivisions), (6, 2));
            m.validate().unwrap();
            let new = &m.positions()[nv + h.subdivisions..];
            assert_eq!(new.len(), 6 * 6);
            for section in new.chunks(6) {
                let (w, positive) = star_winding(section);
                assert!((w - 1.0).abs() < 1e-9 && positive, "twist {twist}: winding {w}");
            }
        }
    }

    #[test]
    fn pinch_and_twists() {
        let base = grid_cube(3);
        let a = face_at(&base, [0., 0., 1.]);
        let b = face_at(&base, [0., 0., -1.]);
        let b = base.aligned_handle_corner(a, b, -1.0, -1.0).unwrap();
        let mut plain = base.clone();
        plain.add_handle(a, b, 4, -1.0, -1.0).unwrap();
        let mut same = base.clone();
        same.add_handle_shaped(a, b, 4, -1.0, -1.0, super::HandleShape::default()).unwrap();
        assert_eq!(plain, same);
        let mut m = base.clone();
        let shape = super::HandleShape { pinch: 0.5, center: 0.5, width: 1.0, extra_twists: 1 };
        m.add_handle_shaped(a, b, 4, -1.0, -1.0, shape).unwrap();
        assert_eq!(counts(&m), counts(&plain));
        // the middle section (t = 1/2) is half as wide as the plain one
        let nv = base.n_vertices();
        let mid = |m: &Mesh| m.positions()[nv + 4..nv + 8].iter().map(|p| (p.x * p.x + p.y * p.y).sqrt()).sum::<f64>();
        assert!((mid(&m) / mid(&plain) - 0.5).abs() < 1e-9);
        for bad in [super::HandleShape { pinch: 0.0, ..shape }, super::HandleShape { center: 1.0, ..shape }, super::HandleShape { width: 0.0, ..shape }] {
            let mut c = base.clone();
            assert!(c.add_handle_shaped(a, b, 4, -1.0, -1.0, bad).is_err());
            assert_eq!(c, base);
        }
    }

    #[test]
    fn two_components_join() {
        let mut m = grid_cube(1);
        let fm = m.create_face_manifold(&[glam::DVec3::new(0., 0., 4.), glam::DVec3::new(0., 1., 4.), glam::DVec3::new(1., 0., 4.)]).unwrap();
        let (v, e, f, c, g) = counts(&m);
        let top = face_at(&m, [0., 0., 1.]);
        let crate::Corner::Halfedge(tri) = fm.back_corner else { panic!() };
        let h = m.add_handle(top, tri, 2, 1., 1.).unwrap();
        assert_eq!(h.subdivisions, 1);
        let (n, k) = (4, 2);
        assert_eq!(counts(&m), (v + 1 + n * (k - 1), e + 1 + n * (2 * k - 1), f + n * k - 2, c - 1, g));
    }
}

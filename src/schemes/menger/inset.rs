//! Step 1 (VII.3 step 1): every face's normal and thickness `D`, and its
//! inset corners, the remeshing face's corners at distance `D` from both
//! side lines (module docs of [`super`], "Thickness, welding, planarity").

use super::{MengerOptions, Reduction};
use crate::error::{MeshError, Result};
use crate::mesh::{HalfedgeId, Mesh};
use glam::DVec3;

/// The corner at the tail of `h` in its face (unit normal `n`): the unit
/// in-plane inward normals of its outgoing and incoming sides, and whether
/// the corner is convex.
pub(super) fn corner_sides(m: &Mesh, n: DVec3, h: HalfedgeId) -> (DVec3, DVec3, bool) {
    let pos = m.positions();
    let pv = pos[m.vertex(h).idx()];
    let t1 = (pos[m.head(h).idx()] - pv).normalize_or_zero();
    let t0 = (pv - pos[m.vertex(m.prev(h)).idx()]).normalize_or_zero();
    (n.cross(t1).normalize_or_zero(), n.cross(t0).normalize_or_zero(), t0.cross(t1).dot(n) > 0.0)
}

/// Whether `x` lies at least `dist` inside both sides of the corner at `pv`
/// with inward side normals `w1, w2` ([`corner_sides`]).
pub(super) fn inside_corner(x: DVec3, pv: DVec3, (w1, w2): (DVec3, DVec3), dist: f64) -> bool {
    (x - pv).dot(w1) >= dist && (x - pv).dot(w2) >= dist
}

/// Unit face normals, thickness `D` per face, the offset depth per face
/// (`D` unless `red` reduces it, module docs "Thickness reduction") and the
/// inset corner per half-edge (the corner at its tail in its face), after
/// checking the options and the input's faces.
pub(super) fn faces_and_insets(m: &Mesh, o: &MengerOptions, red: Option<&Reduction>) -> Result<Faces> {
    if !(o.thickness > 0.0 && o.thickness.is_finite()) || (o.relative && o.thickness >= 0.5) {
        return Err(MeshError::InvalidArgument(format!(
            "menger: thickness must be positive{} (got {})",
            if o.relative { " and below 1/2 of the face width" } else { "" },
            crate::error::num(o.thickness)
        )));
    }
    if !(o.collapse_angle.is_finite() && (0.0..=180.0).contains(&o.collapse_angle)) {
        return Err(MeshError::InvalidArgument(format!(
            "menger: collapse_angle = {} is out of range; it must be a finite angle in [0, 180] degrees",
            crate::error::num(o.collapse_angle)
        )));
    }
    let nh = m.n_halfedges();
    let nf = m.n_faces();
    for f in m.faces() {
        crate::cancel::poll(f.0 as usize)?;
        if m.face_halfedge(f).is_none() || m.face_degree(f) < 3 {
            return Err(MeshError::InvalidArgument(format!(
                "menger: face {} has {} corner(s); every face needs at least three",
                f.0,
                m.face_degree(f)
            )));
        }
    }
    if m.n_self_loops() > 0 {
        return Err(MeshError::InvalidArgument("menger: self-loops have no length to thicken; smooth the mesh first".into()));
    }
    let pos = m.positions();
    let p = |h: HalfedgeId| pos[m.vertex(h).idx()];
    // --- faces: normal, width, thickness
    let mut face_n = crate::mesh::zeroed_points(nf);
    let mut face_d = vec![0.0; nf];
    for f in m.faces() {
        crate::cancel::poll(f.0 as usize)?;
        let nw = m.face_newell(f);
        let n = nw.normalize_or_zero();
        if n == DVec3::ZERO {
            return Err(MeshError::InvalidArgument(format!("menger: face {} has zero area", f.0)));
        }
        let hs: Vec<HalfedgeId> = m.face_halfedges(f).collect();
        let c = hs.iter().map(|&h| p(h)).sum::<DVec3>() / hs.len() as f64;
        let mut width = f64::INFINITY;
        for &h in &hs {
            let (a, b) = (p(h), p(m.next(h)));
            let t = (b - a).normalize_or_zero();
            let d = ((c - a) - t * (c - a).dot(t)).length();
            width = width.min(2.0 * d);
        }
        face_n[f.idx()] = n;
        face_d[f.idx()] = width;
    }
    if o.relative {
        // D = t · the smallest width among the faces around the face's
        // vertices, so a wide face next to a thin wall does not reach through it
        let width = face_d.clone();
        let mut vmin = vec![f64::INFINITY; m.n_vertices()];
        for h in m.halfedges() {
            let v = m.vertex(h).idx();
            vmin[v] = vmin[v].min(width[m.face(h).idx()]);
        }
        for f in m.faces() {
            let w = m.face_halfedges(f).map(|h| vmin[m.vertex(h).idx()]).fold(f64::INFINITY, f64::min);
            face_d[f.idx()] = o.thickness * w;
        }
    } else {
        // the relative rule's bound (t < 1/2 of the smallest width around a
        // face) in absolute terms: beyond it inset corners cross and the
        // offset surface turns inside out (cube of side 2 at D = 10: volume −13600)
        let limit = 0.5 * face_d.iter().copied().fold(f64::INFINITY, f64::min);
        if o.thickness >= limit {
            return Err(MeshError::InvalidArgument(format!(
                "menger: thickness = {} (absolute) is out of range; on this mesh it must be in (0, {limit}) (half the smallest face width)",
                o.thickness
            )));
        }
        face_d.iter_mut().for_each(|d| *d = o.thickness);
    }
    // a reduced face's depth (factors of exactly 1 elsewhere, so
    // unreduced faces are bit for bit what they were)
    let mut face_depth = face_d.clone();
    if let Some(r) = red {
        for f in 0..nf {
            face_depth[f] = face_d[f] * r.depth[f];
        }
    }
    // --- inset corners
    let mut q = crate::mesh::zeroed_points(nh);
    for h in m.halfedges() {
        crate::cancel::poll(h.0 as usize)?;
        let f = m.face(h).idx();
        let n = face_n[f];
        let pv = p(h);
        let (w1, w2, _) = corner_sides(m, n, h);
        let den = 1.0 + w1.dot(w2);
        if den < 1e-9 || w1 == DVec3::ZERO || w2 == DVec3::ZERO {
            return Err(MeshError::InvalidArgument(format!(
                "menger: corner at vertex {} of face {} is a zero-angle spike",
                m.vertex(h).0,
                f
            )));
        }
        q[h.idx()] = pv + face_d[f] * (w1 + w2) / den;
    }
    Ok(Faces { face_n, face_d, face_depth, q })
}

/// What [`faces_and_insets`] derives per face and per corner.
pub(super) struct Faces {
    pub(super) face_n: Vec<DVec3>,
    pub(super) face_d: Vec<f64>,
    pub(super) face_depth: Vec<f64>,
    pub(super) q: Vec<DVec3>,
}

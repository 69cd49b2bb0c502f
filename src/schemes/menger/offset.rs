//! Steps 2–3 (VII.3 steps 2–3, VII.4): the offset corners `q − D n_f`, the
//! edge classes by dihedral angle (collapse, strip, miter) and the merged
//! offset corner of every group of faces joined by collapsed edges, with
//! the meeting point of a fully collapsed vertex (module docs of
//! [`super`], step 3 and "Crossing check").

use super::inset::{corner_sides, faces_and_insets, Faces};
use super::{EdgeKind, MengerOptions, Offset, Reduction, ANGLE_TOL};
use crate::error::Result;
use crate::mesh::{HalfedgeId, Mesh};
use glam::{DMat3, DVec3};

/// Everything one iteration derives from the input's geometry.
pub(super) struct Plan {
    pub(super) face_n: Vec<DVec3>,
    /// The inset `D` per face (step 1) and its offset depth (step 2; `D`
    /// unless reduced, module docs "Thickness reduction").
    pub(super) face_d: Vec<f64>,
    pub(super) face_depth: Vec<f64>,
    /// Inset corner per half-edge (the corner at its tail in its face).
    pub(super) q: Vec<DVec3>,
    pub(super) kind: Vec<EdgeKind>,
    /// Merged offset-corner group per half-edge, and the group positions.
    pub(super) group: Vec<u32>,
    pub(super) group_pos: Vec<DVec3>,
    /// [`Offset::PerFace`]: every group is one corner, the depth is bounded
    /// at sharp edges and collapsed edges get strips (module docs,
    /// "Per-face corners").
    pub(super) per_face: bool,
}

/// The least-squares solution of `a x = b` (`a` a sum of `n nᵀ` over plane
/// normals) nearest to `x0` along directions `a` barely constrains. Iterative
/// refinement of a slightly regularized solve: exact (to rounding) when the
/// planes are consistent, so faces built on them stay planar, where a plain
/// regularized solve leaves them off by the regularization (about 1e-11 of
/// the thickness, enough to fail the planarity test and fan the face).
fn least_squares_from(a: DMat3, b: DVec3, x0: DVec3) -> DVec3 {
    let lam = 1e-6 * (a.x_axis.x + a.y_axis.y + a.z_axis.z);
    let inv = (a + DMat3::from_diagonal(DVec3::splat(lam))).inverse();
    let mut x = x0;
    for _ in 0..6 {
        x += inv * (b - a * x);
    }
    x
}

pub(super) fn plan(m: &Mesh, o: &MengerOptions, full: &[bool], red: Option<&Reduction>) -> Result<Plan> {
    let Faces { face_n, face_d, mut face_depth, q } = faces_and_insets(m, o, red)?;
    let per_face = o.offset == Offset::PerFace;
    if per_face {
        sharp_edge_depth(m, &face_n, &face_d, &mut face_depth);
    }
    let pos = m.positions();
    let p = |h: HalfedgeId| pos[m.vertex(h).idx()];
    let nh = m.n_halfedges();
    // --- edge classes by the interior dihedral angle
    let collapse = o.collapse_angle.to_radians() + ANGLE_TOL;
    let kind: Vec<EdgeKind> = m
        .edges()
        .map(|e| {
            let phi = interior_angle(m, &face_n, e.halfedge());
            if phi <= collapse {
                EdgeKind::Collapse
            } else if phi <= std::f64::consts::PI + ANGLE_TOL {
                EdgeKind::Strip
            } else {
                EdgeKind::Miter
            }
        })
        .collect();
    // --- merge offset corners across collapsed edges, per vertex
    let mut parent: Vec<u32> = (0..nh as u32).collect();
    for h in m.halfedges() {
        crate::cancel::poll(h.0 as usize)?;
        if !per_face && kind[h.edge().idx()] == EdgeKind::Collapse {
            // corners h and next(twin(h)) lie on either side of edge(h) at its tail
            crate::union_find::union(&mut parent, h.0, m.next(h.twin()).0);
        }
    }
    for v in m.vertices() {
        crate::cancel::poll(v.0 as usize)?;
        if per_face || !full[v.idx()] {
            continue;
        }
        let hs: Vec<HalfedgeId> = m.vertex_halfedges(v).collect();
        for w in hs.windows(2) {
            crate::union_find::union(&mut parent, w[0].0, w[1].0);
        }
    }
    let mut group = vec![u32::MAX; nh];
    let mut members: Vec<Vec<u32>> = Vec::new();
    for h in 0..nh as u32 {
        crate::cancel::poll(h as usize)?;
        let r = crate::union_find::root(&mut parent, h);
        if group[r as usize] == u32::MAX {
            group[r as usize] = members.len() as u32;
            members.push(Vec::new());
        }
        let g = group[r as usize];
        group[h as usize] = g;
        members[g as usize].push(h);
    }
    let group_pos: Vec<DVec3> = members
        .iter()
        .map(|hs| {
            let raw = |h: u32| {
                let f = m.face(HalfedgeId(h)).idx();
                q[h as usize] - face_depth[f] * face_n[f]
            };
            if hs.len() == 1 {
                return raw(hs[0]);
            }
            let pv = p(HalfedgeId(hs[0]));
            let dmin = hs.iter().map(|&h| face_depth[m.face(HalfedgeId(h)).idx()]).fold(f64::INFINITY, f64::min);
            if full[m.vertex(HalfedgeId(hs[0])).idx()] {
                if let Some(y) = pipe_meeting_point(m, &face_n, (&face_d, &face_depth), hs, pv, dmin) {
                    return y;
                }
                let normals: Vec<DVec3> = hs.iter().map(|&h| face_n[m.face(HalfedgeId(h)).idx()]).collect();
                if let Some(y) = below_every_face_projected(pv, &normals, dmin) {
                    return y;
                }
            }
            // least squares on the offset planes; the mean of the raw offset
            // corners along any direction the planes leave free
            let avg = hs.iter().map(|&h| raw(h)).sum::<DVec3>() / hs.len() as f64;
            let (mut a, mut b) = (DMat3::ZERO, DVec3::ZERO);
            for &h in hs {
                let f = m.face(HalfedgeId(h)).idx();
                let n = face_n[f];
                a += DMat3::from_cols(n * n.x, n * n.y, n * n.z);
                b += n * (n.dot(pv) - face_depth[f]);
            }
            let x = least_squares_from(a, b, avg);
            // a sharp vertex amplifies the offset (D / sin of its half
            // angle); keep the merged corner within √3·D of the vertex, the
            // cube corner's offset, so it stays inside thin corners
            let dmax = 3f64.sqrt() * dmin;
            let off = x - pv;
            if off.length() > dmax * (1.0 + 1e-9) { pv + off * (dmax / off.length()) } else { x }
        })
        .collect();
    Ok(Plan { face_n, face_d, face_depth, q, kind, group, group_pos, per_face })
}

/// Sharp edges bound the offset depth of their faces ([`Offset::PerFace`],
/// module docs "Per-face corners"). In the cross-section of a convex edge
/// of interior angle `φ` between faces with insets `D₁, D₂` and depths
/// `d₁, d₂`, face 1's offset corner is `D₁ w₁ − d₁ n₁` from the edge (`w₁`
/// its in-plane inward normal, `n₁` its outward normal), and
/// `n₂·(D₁ w₁ − d₁ n₁) = −D₁ sin φ + d₁ cos φ`: it lies at least `d₂`
/// below face 2 when `d₁ cos φ + d₂ ≤ D₁ sin φ`, which both depths at most
/// `min(D₁, D₂) tan(φ/2)` satisfy, both ways. For `φ ≥ 90°` that bound is at
/// least `min(D₁, D₂)` and is not applied (two faces of unequal `D` there
/// keep their depth `D`, off the condition by at most their difference);
/// below, the depths of both faces are bounded by [`SHARP_MARGIN`] times
/// it. Then the strip between the two offset edges
/// cuts the corner of the mitred offset (a bevel inside it), and each pipe,
/// a right prism of depth `d` over its window `D` from the edge, stays in
/// the wedge (whose thickness there is `D tan φ`).
fn sharp_edge_depth(m: &Mesh, face_n: &[DVec3], face_d: &[f64], face_depth: &mut [f64]) {
    for e in m.edges() {
        let h = e.halfedge();
        let (f1, f2) = (m.face(h).idx(), m.face(h.twin()).idx());
        let phi = interior_angle(m, face_n, h);
        if phi > 0.0 && phi < std::f64::consts::FRAC_PI_2 - ANGLE_TOL {
            let bound = SHARP_MARGIN * face_d[f1].min(face_d[f2]) * (0.5 * phi).tan();
            face_depth[f1] = face_depth[f1].min(bound);
            face_depth[f2] = face_depth[f2].min(bound);
        }
    }
}

/// Whether every edge meets at 90°, 180° or 270° (within [`ANGLE_TOL`]),
/// for unit face normals `face_n`: the cube's family, whose per-face
/// vertex faces stay as built (module docs, "Per-face corners", invariant 5).
pub(super) fn right_angled(m: &Mesh, face_n: &[DVec3]) -> bool {
    m.edges().all(|e| {
        let phi = interior_angle(m, face_n, e.halfedge());
        [1.0, 2.0, 3.0].iter().any(|k| (phi - k * std::f64::consts::FRAC_PI_2).abs() <= ANGLE_TOL)
    })
}

/// The interior (material) dihedral angle of the edge of `h`, in radians
/// (0 to 2π; π for a flat edge), from the unit normals of its two faces.
pub(super) fn interior_angle(m: &Mesh, face_n: &[DVec3], h: HalfedgeId) -> f64 {
    let pos = m.positions();
    let (n1, n2) = (face_n[m.face(h).idx()], face_n[m.face(h.twin()).idx()]);
    let t = (pos[m.head(h).idx()] - pos[m.vertex(h).idx()]).normalize_or_zero();
    std::f64::consts::PI - n1.cross(n2).dot(t).atan2(n1.dot(n2))
}

/// The share of the largest depth [`sharp_edge_depth`] allows, below 1 so
/// that the strip across a sharp edge keeps a width.
pub(super) const SHARP_MARGIN: f64 = 0.8;

/// The meeting point of all pipes at a fully collapsed vertex (module docs,
/// "Crossing check"): the point nearest the vertex that lies at least `D`
/// below every face around it and projects onto every convex corner at
/// least `D/2` inside both its sides, so each pipe wall there is a planar
/// quad perpendicular to its face (as at the cube's corners). `None` when
/// no point does (a saddle whose corners' projections cannot all hold it).
/// `pv` is the vertex, `dmin` the smallest `D` of its faces.
fn pipe_meeting_point(m: &Mesh, face_n: &[DVec3], (face_d, face_depth): (&[f64], &[f64]), hs: &[u32], pv: DVec3, dmin: f64) -> Option<DVec3> {
    let mut planes: Vec<(DVec3, f64)> = Vec::with_capacity(3 * hs.len());
    for &h in hs {
        let f = m.face(HalfedgeId(h)).idx();
        let (n, d) = (face_n[f], face_d[f]);
        planes.push((n, n.dot(pv) - face_depth[f]));
        let (w1, w2, convex) = corner_sides(m, n, HalfedgeId(h));
        if convex {
            planes.push((-w1, -w1.dot(pv) - 0.5 * d));
            planes.push((-w2, -w2.dot(pv) - 0.5 * d));
        }
    }
    nearest_in_halfspaces(&planes, pv, dmin)
}

/// The fallback point of a fully collapsed vertex at `pv` with no
/// [`pipe_meeting_point`] (module docs, "Crossing check"): `dmin` below
/// every face around it (outward unit `normals`) along the direction `u`
/// farthest below all their planes (the largest `min u·nᵢ`, the centre of
/// the normals' spherical cap), kept within `√3·dmin` of the vertex like
/// every merged corner; at a cube corner it is the corner's exact offset.
/// `None` when the normals do not lie in an open hemisphere (no direction
/// points below every face).
pub(super) fn below_every_face(pv: DVec3, normals: &[DVec3], dmin: f64) -> Option<DVec3> {
    // the point nearest the origin with n·x ≥ 1 for every normal: x / |x|
    // is the direction, 1 / |x| its margin
    below_along(pv, min_norm_above(normals)?, dmin)
}

/// [`below_every_face`] with the point found by Dykstra's projections
/// ([`nearest_in_halfspaces`]), which stop short of it where normals are
/// nearly parallel (up to 1e-4 of its length) and may miss it near the
/// edge of a hemisphere: the merged construction keeps it so that its
/// outputs and the figures measured on them stay as they were.
pub(super) fn below_every_face_projected(pv: DVec3, normals: &[DVec3], dmin: f64) -> Option<DVec3> {
    let planes: Vec<(DVec3, f64)> = normals.iter().map(|&n| (-n, -1.0)).collect();
    below_along(pv, nearest_in_halfspaces(&planes, DVec3::ZERO, 1.0)?, dmin)
}

/// `dmin` below `pv` along `-x`, at most `√3·dmin` (`x` the point nearest
/// the origin with every `n·x ≥ 1`).
fn below_along(pv: DVec3, x: DVec3, dmin: f64) -> Option<DVec3> {
    let len = x.length();
    (len.is_finite() && len > 0.0).then(|| pv - x * (dmin * len.min(3f64.sqrt()) / len))
}

/// The point nearest the origin with `a·x ≥ 1` for every `a` in `normals`,
/// exactly: the optimum of this small convex problem is the unique point
/// meeting its KKT conditions, `x = Σ λᵢ aᵢ` over an active set of at
/// most three (independent, in 3D) normals with `aᵢ·x = 1`, `λᵢ ≥ 0`, and
/// every other `a·x ≥ 1`; active sets are tried by size, one to three.
/// `None` when no point qualifies (the normals fit in no open hemisphere).
/// Replaces Dykstra's projections ([`nearest_in_halfspaces`]), which took
/// up to 500 sweeps where normals are nearly parallel (a fifth of a
/// per-face iteration of the 400×250 torus).
pub(super) fn min_norm_above(normals: &[DVec3]) -> Option<DVec3> {
    const TOL: f64 = 1e-12;
    let feasible = |x: DVec3| normals.iter().all(|a| a.dot(x) >= 1.0 - TOL);
    let k = normals.len();
    for a in normals {
        let x = *a / a.length_squared();
        if x.is_finite() && feasible(x) {
            return Some(x);
        }
    }
    for i in 0..k {
        for j in i + 1..k {
            let (a, b) = (normals[i], normals[j]);
            let (g11, g12, g22) = (a.length_squared(), a.dot(b), b.length_squared());
            let det = g11 * g22 - g12 * g12;
            if !(det > 1e-14 * g11 * g22) {
                continue; // parallel: the single normals above cover it
            }
            let (l1, l2) = ((g22 - g12) / det, (g11 - g12) / det);
            if l1 < -TOL || l2 < -TOL {
                continue;
            }
            let x = l1 * a + l2 * b;
            if feasible(x) {
                return Some(x);
            }
        }
    }
    for i in 0..k {
        for j in i + 1..k {
            for l in j + 1..k {
                let (a, b, c) = (normals[i], normals[j], normals[l]);
                let det = a.dot(b.cross(c));
                if !(det.abs() > 1e-14 * a.length() * b.length() * c.length()) {
                    continue;
                }
                // the dual basis gives x (aᵢ·x = 1) and its coefficients
                let (da, db, dc) = (b.cross(c) / det, c.cross(a) / det, a.cross(b) / det);
                let x = da + db + dc;
                if da.dot(x) < -TOL || db.dot(x) < -TOL || dc.dot(x) < -TOL {
                    continue;
                }
                if feasible(x) {
                    return Some(x);
                }
            }
        }
    }
    None
}

/// The point of the half-spaces `n·x ≤ c` nearest to `pv` (Dykstra's
/// alternating projections), or `None` when they leave no point (within
/// `1e-9·scale`).
pub(super) fn nearest_in_halfspaces(planes: &[(DVec3, f64)], pv: DVec3, scale: f64) -> Option<DVec3> {
    let mut y = pv;
    let mut inc = vec![DVec3::ZERO; planes.len()];
    for _ in 0..500 {
        let y0 = y;
        for (k, &(n, c)) in planes.iter().enumerate() {
            let z = y + inc[k];
            let viol = n.dot(z) - c;
            let pz = if viol > 0.0 { z - viol * n } else { z };
            inc[k] = z - pz;
            y = pz;
        }
        if y.distance(y0) <= 1e-13 * scale {
            break;
        }
    }
    planes.iter().all(|&(n, c)| n.dot(y) - c <= 1e-9 * scale).then_some(y)
}

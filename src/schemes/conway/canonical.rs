//! Hart's canonical form, iteratively: planar faces, every edge tangent to
//! the unit sphere, the tangent points centred on the origin (G. W. Hart,
//! "Calculating Canonical Polyhedra", Mathematica in Education and Research
//! 6(3), 1997; the iteration is polyhedronisme's `canonicalize`:
//! `tangentify`, `recenter`, `planarize` with its stability factor 0.1).
//!
//! Only positions move; connectivity is the input's. The canonical form
//! exists for convex genus-0 polyhedra (Koebe–Andreev–Thurston); on other
//! inputs the iteration still runs and its residual says how far it got.
//! Each step accumulates every edge's and face's correction from the same
//! positions (Jacobi), where polyhedronisme updates edge by edge, so the
//! result does not depend on the edge order.

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use glam::DVec3;

/// polyhedronisme's `STABILITY_FACTOR`.
const STEP: f64 = 0.1;

/// The point of the line through `a`, `b` nearest the origin (`a` for a
/// zero-length edge).
fn tangent_point(a: DVec3, b: DVec3) -> DVec3 {
    let d = b - a;
    let l2 = d.length_squared();
    if l2 == 0.0 {
        a
    } else {
        a - d * (d.dot(a) / l2)
    }
}

/// Unit normal of a face from its corner positions (polyhedronisme's
/// `normal`: the sum of the cross products of consecutive edges), pointing
/// away from the origin; zero for a degenerate face.
fn face_normal(ps: &[DVec3], c: DVec3) -> DVec3 {
    let k = ps.len();
    let mut n = DVec3::ZERO;
    for i in 0..k {
        let (a, b, d) = (ps[i], ps[(i + 1) % k], ps[(i + 2) % k]);
        n += (b - a).cross(d - b);
    }
    let n = n.normalize_or_zero();
    if n.dot(c) < 0.0 {
        -n
    } else {
        n
    }
}

struct Topology {
    edges: Vec<(u32, u32)>,
    faces: Vec<Vec<u32>>,
}

impl Topology {
    fn of(m: &Mesh) -> Topology {
        let edges = (0..m.n_edges()).map(|e| (m.he_vert[2 * e], m.he_vert[2 * e + 1])).collect();
        let faces = m.faces().map(|f| m.face_vertices(f).map(|v| v.0).collect()).collect();
        Topology { edges, faces }
    }

    /// Max of: |1 − distance of an edge line from the origin|, a corner's
    /// distance from its face's mean plane, and the norm of the mean edge
    /// tangent point.
    fn residual(&self, p: &[DVec3]) -> f64 {
        let mut r = 0f64;
        let mut sum = DVec3::ZERO;
        for &(a, b) in &self.edges {
            let t = tangent_point(p[a as usize], p[b as usize]);
            sum += t;
            r = r.max((1.0 - t.length()).abs());
        }
        if !self.edges.is_empty() {
            r = r.max((sum / self.edges.len() as f64).length());
        }
        for f in &self.faces {
            let ps: Vec<DVec3> = f.iter().map(|&v| p[v as usize]).collect();
            let c = ps.iter().sum::<DVec3>() / ps.len() as f64;
            let n = face_normal(&ps, c);
            for q in &ps {
                r = r.max(n.dot(*q - c).abs());
            }
        }
        r
    }

    /// One step: tangentify, recenter, planarize. Returns the largest move.
    fn step(&self, p: &mut [DVec3], acc: &mut [DVec3]) -> f64 {
        acc.iter_mut().for_each(|a| *a = DVec3::ZERO);
        for &(a, b) in &self.edges {
            let t = tangent_point(p[a as usize], p[b as usize]);
            let c = t * (STEP / 2.0 * (1.0 - t.length()));
            acc[a as usize] += c;
            acc[b as usize] += c;
        }
        let old: Vec<DVec3> = p.to_vec();
        for (q, a) in p.iter_mut().zip(acc.iter()) {
            *q += *a;
        }
        self.recenter(p);
        acc.iter_mut().for_each(|a| *a = DVec3::ZERO);
        for f in &self.faces {
            let ps: Vec<DVec3> = f.iter().map(|&v| p[v as usize]).collect();
            let c = ps.iter().sum::<DVec3>() / ps.len() as f64;
            let n = face_normal(&ps, c);
            for (&v, q) in f.iter().zip(&ps) {
                acc[v as usize] += n * (STEP * n.dot(c - *q));
            }
        }
        let mut moved = 0f64;
        for ((q, a), o) in p.iter_mut().zip(acc.iter()).zip(&old) {
            *q += *a;
            moved = moved.max(q.distance(*o));
        }
        moved
    }

    /// Moves the mean edge tangent point to the origin.
    fn recenter(&self, p: &mut [DVec3]) {
        if self.edges.is_empty() {
            return;
        }
        let s: DVec3 = self.edges.iter().map(|&(a, b)| tangent_point(p[a as usize], p[b as usize])).sum();
        let c = s / self.edges.len() as f64;
        for q in p.iter_mut() {
            *q -= c;
        }
    }
}

/// Hart's canonical form by at most `iterations` steps, stopping once no
/// vertex moves more than `tol` in a step. Returns the mesh and the
/// residual (see [`Topology::residual`]: 0 for an exactly canonical
/// polyhedron). The input is first centred and scaled so its edges' mean
/// distance from the origin is 1.
///
/// Errors: a mesh with boundary loops, `tol` outside [0, 1], or
/// positions that stop being finite (the iteration diverged: the message
/// names the step).
pub fn canonicalize(m: &Mesh, iterations: usize, tol: f64) -> Result<(Mesh, f64)> {
    // positions are scaled to unit size first, so a step above 1 is no convergence
    if !(0.0..=1.0).contains(&tol) {
        return Err(MeshError::InvalidArgument(format!("canonicalize: tol = {} is outside [0, 1] (positions are scaled to unit size)", crate::error::num(tol))));
    }
    crate::schemes::hosts::refuse_holes("canonicalize", m)?;
    let topo = Topology::of(m);
    let mut out = m.clone();
    let p = out.positions_mut();
    if let Some(s) = crate::geometry::extreme_scale(p) {
        // 1e±300: tangent points overflow or underflow; the scaling below
        // makes the result size-free anyway (exact powers of two)
        p.iter_mut().for_each(|q| *q /= s);
    }
    topo.recenter(p);
    if !topo.edges.is_empty() {
        let mean = topo.edges.iter().map(|&(a, b)| tangent_point(p[a as usize], p[b as usize]).length()).sum::<f64>() / topo.edges.len() as f64;
        if mean > 0.0 && mean.is_finite() {
            p.iter_mut().for_each(|q| *q /= mean);
        }
    }
    let mut acc = crate::mesh::zeroed_points(p.len());
    for k in 0..iterations {
        crate::cancel::check()?;
        let moved = topo.step(p, &mut acc);
        if !moved.is_finite() || p.iter().any(|q| !q.is_finite()) {
            return Err(MeshError::Precondition(format!(
                "canonicalize: positions stopped being finite at step {k}; the mesh has no canonical form this iteration reaches"
            )));
        }
        if moved <= tol {
            break;
        }
    }
    let r = topo.residual(out.positions());
    Ok((out, r))
}

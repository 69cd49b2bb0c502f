//! Corner cutting (TopMod's *Corner Cutting*, `cornerCuttingSubdivide(obj,
//! alpha)`) and modified corner cutting (`modifiedCornerCuttingSubdivide(obj,
//! thickness)`), read from TopMod's source (`include/dlflaux/DLFLSubdiv.cc`),
//! the only description of these two; both have Doo-Sabin's connectivity
//! (the dual host: Doo & Sabin 1978, as in `schemes::doo_sabin`).
//!
//! Connectivity: one new vertex per corner; each n-gon gives an n-gon of its
//! corner points, each edge a quad, each valence-k vertex a k-gon.
//! V' = 2E, E' = 4E, F' = F + E + V; histogram: the input's face sizes,
//! E quads, and one k-gon per valence-k vertex. Output vertex h is the
//! point of corner (half-edge) h.
//!
//! Masks:
//! * corner cutting: corner k of an n-gon `x₀ … x_{n−1}` goes to
//!   `α x_k + Σ_{j≠k} (1 − α)(3 + 2 cos(2π(k − j)/n))/(3n − 5) x_j`
//!   (TopMod's generalised Doo-Sabin weights, which sum to 1 for n ≥ 2;
//!   α = 1/4 + 5/(4n) gives Doo-Sabin), computed in O(n) per face with the
//!   cosine/sine sums; a one-gon's point is its vertex.
//! * modified corner cutting: corner `v₀` between neighbours `v₁` (previous)
//!   and `v₂` (next) goes to `v₀ + x (n₁ + n₂)`, `nᵢ` the unit vectors to
//!   the neighbours and `x = √(t² / (1 − (n₁·n₂)²))`, `t = thickness / 2`:
//!   the point at distance t from both edges (on their bisector). Where
//!   TopMod's formula breaks (straight or zero-length edges; TopMod also
//!   swaps `v₂` for the corner after it when `|v₁ − v₂| < 0.001`, done here)
//!   the point moves by t towards the face centroid.

use crate::schemes::keyed::{In, Out};
use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::hosts::with_point_spheres;
use glam::DVec3;

/// Doo-Sabin's connectivity over new points `pts` (one per half-edge).
pub(crate) fn dual_host(i: &In, pts: Vec<DVec3>, name: &str) -> Result<Mesh> {
    let h_n = i.nh as u32;
    // keys: [0, H) the side of corner h's face, [H, 2H) the side of the
    // vertex face from corner h to rotate(h)
    let mut o = Out::new(pts, 2 * i.nh, i.nf + i.ne + i.nv, 4 * i.nh).of(i);
    // the point of corner h lies in h's face
    o.vertex_origins(|| i.face.to_vec());
    for f in 0..i.nf {
        o.from_face(f);
        for &h in i.fl.corners(f) {
            o.c(h, h);
        }
        o.end();
    }
    for e in 0..i.ne {
        let (h, t) = (2 * e, 2 * e + 1);
        // the quad of edge e straddles both its faces: the first side's
        o.from_face(i.face[h] as usize);
        let (nh, nt) = (i.next[h], i.next[t]);
        o.c(nh, h as u32);
        o.c(h as u32, h_n + nt);
        o.c(nt, t as u32);
        o.c(t as u32, h_n + nh);
        o.end();
    }
    for v in 0..i.nv {
        o.from_vertex(v);
        let h0 = i.m.v_out[v] as usize;
        let mut k = h0;
        loop {
            o.c(k as u32, h_n + k as u32);
            k = i.rot(k);
            if k == h0 {
                break;
            }
        }
        o.end();
    }
    o.finish(name)
}

/// TopMod's generalised Doo-Sabin mask with weight `alpha` on the corner
/// itself, over the points `x` of one face, written to `out` (O(n)).
pub(crate) fn cut_face(x: &[DVec3], alpha: f64, out: &mut Vec<DVec3>) {
    let n = x.len();
    if n == 1 {
        out.push(x[0]);
        return;
    }
    let sum: DVec3 = x.iter().sum();
    let (mut c, mut s) = (DVec3::ZERO, DVec3::ZERO);
    for (j, p) in x.iter().enumerate() {
        let (sn, cs) = turn(j, n);
        c += cs * *p;
        s += sn * *p;
    }
    let w = (1.0 - alpha) / (3.0 * n as f64 - 5.0);
    for (k, p) in x.iter().enumerate() {
        let (sn, cs) = turn(k, n);
        // Σ_{j≠k} (3 + 2 cos θ_{k−j}) x_j = 3 (Σx − x_k) + 2 (cos θ_k C + sin θ_k S − x_k)
        let rest = 3.0 * (sum - *p) + 2.0 * (cs * c + sn * s - *p);
        out.push(alpha * *p + w * rest);
    }
}

/// Faces up to this size read their turns from a table.
const TABLED: usize = 16;

/// `(sin, cos)` of `2πk/n` computed as `(2π/n · k).sin_cos()`, from a
/// table for n ≤ 16 (the same bits: the table is filled by that
/// expression); the sine and cosine per corner were 15 % of root-4 and
/// Doo-Sabin BC new on a 100k-quad torus (issue 16).
#[inline]
fn turn(k: usize, n: usize) -> (f64, f64) {
    let of = |k: usize, n: usize| (2.0 * std::f64::consts::PI / n as f64 * k as f64).sin_cos();
    static TABLE: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    if n <= TABLED && k < n {
        let t = TABLE.get_or_init(|| (1..=TABLED).flat_map(|n| (0..n).map(move |k| of(k, n))).collect());
        return t[n * (n - 1) / 2 + k];
    }
    of(k, n)
}

#[cfg(test)]
#[test]
fn turns_from_the_table_are_exact() {
    for n in 1..=TABLED + 3 {
        let step = 2.0 * std::f64::consts::PI / n as f64;
        for k in 0..n {
            let (a, b) = (turn(k, n), (step * k as f64).sin_cos());
            assert_eq!((a.0.to_bits(), a.1.to_bits()), (b.0.to_bits(), b.1.to_bits()), "{k}/{n}");
        }
    }
}

/// TopMod's corner cutting with weight `alpha` in [1/3, 1) (TopMod's UI
/// range; default 9/16). See the module docs.
pub fn corner_cutting(m: &Mesh, alpha: f64) -> Result<Mesh> {
    if !(alpha.is_finite() && (1.0 / 3.0 - 1e-12..1.0).contains(&alpha)) {
        return Err(MeshError::InvalidArgument(format!("corner_cutting: alpha = {} must be in [1/3, 1)", crate::error::num(alpha))));
    }
    with_point_spheres("corner_cutting", m, |m| {
        let i = In::new(m)?;
        let mut pts = crate::mesh::zeroed_points(i.nh);
        let (mut x, mut y) = (Vec::new(), Vec::new());
        for f in 0..i.nf {
            let hs = i.fl.corners(f);
            x.clear();
            y.clear();
            x.extend(hs.iter().map(|&h| i.p(h as usize)));
            cut_face(&x, alpha, &mut y);
            for (&h, p) in hs.iter().zip(&y) {
                pts[h as usize] = *p;
            }
        }
        dual_host(&i, pts, "corner_cutting")
    })
}

/// TopMod's modified corner cutting with `thickness` in [0, 1] (TopMod's
/// UI range; default 0.25). See the module docs.
pub fn modified_corner_cutting(m: &Mesh, thickness: f64) -> Result<Mesh> {
    if !(thickness.is_finite() && (0.0..=1.0).contains(&thickness)) {
        return Err(MeshError::InvalidArgument(format!("modified_corner_cutting: thickness = {} must be in [0, 1]", crate::error::num(thickness))));
    }
    with_point_spheres("modified_corner_cutting", m, |m| {
        let i = In::new(m)?;
        let cent = i.centroids();
        let t = thickness / 2.0;
        let mut pts = crate::mesh::zeroed_points(i.nh);
        for f in 0..i.nf {
            let hs = i.fl.corners(f);
            let n = hs.len();
            for (k, &h) in hs.iter().enumerate() {
                let v0 = i.p(h as usize);
                let v1 = i.p(hs[(k + n - 1) % n] as usize);
                let mut v2 = i.p(hs[(k + 1) % n] as usize);
                if (v1 - v2).length() < 0.001 {
                    v2 = i.p(hs[(k + 2) % n] as usize);
                }
                let (n1, n2) = ((v1 - v0).normalize_or_zero(), (v2 - v0).normalize_or_zero());
                let d = n1.dot(n2);
                let ok = n1 != DVec3::ZERO && n2 != DVec3::ZERO && d.abs() < 1.0 - 1e-9;
                pts[h as usize] = if ok { v0 + (t * t / (1.0 - d * d)).sqrt() * (n1 + n2) } else { v0 + t * (cent[f] - v0).normalize_or_zero() };
            }
        }
        dual_host(&i, pts, "modified_corner_cutting")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::tests::{check, dual_host_hist};

    #[test]
    fn counts() {
        let want = |_: &Mesh, (v, e, f): (usize, usize, usize)| (2 * e, 4 * e, f + e + v);
        check("corner_cutting", |m| corner_cutting(m, 9.0 / 16.0), want, dual_host_hist);
        check("modified_corner_cutting", |m| modified_corner_cutting(m, 0.25), want, dual_host_hist);
    }

    #[test]
    fn doo_sabin_weight_is_doo_sabin() {
        // α = 1/4 + 5/(4n) on a quad mesh reproduces Doo-Sabin's points
        let c = crate::primitives::cube();
        let a = corner_cutting(&c, 0.25 + 5.0 / 16.0).unwrap();
        let b = crate::schemes::doo_sabin::doo_sabin(&c).unwrap();
        let mut pa: Vec<[i64; 3]> = a.positions().iter().map(|p| { let q = (*p * 1e9).round(); [q.x as i64, q.y as i64, q.z as i64] }).collect();
        let mut pb: Vec<[i64; 3]> = b.positions().iter().map(|p| { let q = (*p * 1e9).round(); [q.x as i64, q.y as i64, q.z as i64] }).collect();
        pa.sort();
        pb.sort();
        assert_eq!(pa, pb);
    }

    #[test]
    fn modified_points_lie_at_the_thickness() {
        // on the cube every corner point is t = thickness/2 from both edges of its corner
        let c = crate::primitives::cube();
        let r = modified_corner_cutting(&c, 0.4).unwrap();
        let i = In::new(&c).unwrap();
        for h in 0..i.nh {
            let (v0, v2) = (i.p(h), i.q(h));
            let p = r.positions()[h];
            let along = (v2 - v0).normalize();
            let off = (p - v0) - along * (p - v0).dot(along);
            assert!((off.length() - 0.2).abs() < 1e-9);
        }
        assert!(corner_cutting(&c, 1.0).is_err() && corner_cutting(&c, 0.2).is_err());
        assert!(modified_corner_cutting(&c, -0.1).is_err() && modified_corner_cutting(&c, f64::NAN).is_err());
    }
}

//! TopMod's dodecahedral and icosahedral extrusions
//! (`include/dlflaux/DLFLExtrude.cc`: `extrudeFaceDodeca(obj, f, angle,
//! num, l1, l2, l3, false)` and `extrudeFaceIcosa(obj, f, angle, num, l1,
//! l2, l3)`, run by `MainWindow.cc` for the extrusion modes of those names;
//! TopMod's source is the only description). Each step adds three rings of
//! n points above the top n-gon `p₀ … p_{n−1}` (unit normal N, mean side
//! length L, α = −`angle`°, and `f(i)` the unit vector
//! `cos α · (e_i × N)/|…| + sin α · N` for the side direction e_i):
//!
//! * **dodecahedral** — TopMod's sequence: a cubical extrusion (ring R1), an
//!   octahedral one of it whose R1 sides are deleted (ring R2 of side
//!   midpoints), a cubical one (ring R3) whose R2 sides are deleted. Faces
//!   per step: the 2n pentagons `[p_j, p_{j+1}, R1_{j+1}, R2_j, R1_j]` and
//!   `[R2_j, R1_{j+1}, R2_{j+1}, R3_{j+1}, R3_j]`, the n-gon R3 on top (on a
//!   pentagon: the dodecahedron's ring of ten faces). Positions (TopMod's
//!   repositioning): R1_i = p_i + L·l1 · dir(f_prev × f_next), R2_i the
//!   midpoint of R1_i R1_{i+1} + L·cos 54°·l2 · dir(f(i) × e_i), R3_i =
//!   R2_i + ½(|p_{i−1}p_i| + |p_i p_{i+1}|)·l3² · dir of the cross product of
//!   the normals of the triangles beside R2_i (TopMod squares l3 there).
//!   Per step V += 3n, E += 5n, F += 2n.
//! * **icosahedral** — TopMod's sequence: an octahedral extrusion (ring Q1
//!   of side midpoints), a cubical one (ring Q2) whose Q1 sides are deleted,
//!   and each resulting pentagon `[Q1_j, p_{j+1}, Q1_{j+1}, Q2_{j+1}, Q2_j]`
//!   stellated around a centre C_{j+1}. Faces per step: 6n triangles, the
//!   n-gon Q2 on top (on a triangle: the icosahedron's 18 side triangles).
//!   Positions: Q1_i = the midpoint of p_i p_{i+1} + L·l1·√3/2 · dir(f(i) ×
//!   e_i); C_i = p_i + L·l2 · dir (TopMod's two tilted face normals at p_i);
//!   Q2_i = Q1_i + L·l3 · dir (the same construction at Q1_i). Per step
//!   V += 3n, E += 9n, F += 6n.
//!
//! TopMod's defaults: angle 40°, lengths (0.5, 1, 1) for dodecahedral and
//! 50°, (0.5, 0.7, 0.8) for icosahedral; its UI ranges: angle in [0, 180],
//! lengths in [0, 100]. A degenerate direction (zero cross product) leaves
//! the point where the offset starts, never NaN. TopMod's dodecahedral
//! *hexagonalize* option (deleting the top ring between segments) is not
//! offered.

use crate::schemes::keyed::Out;
use glam::DVec3;

fn unit(v: DVec3) -> DVec3 {
    v.normalize_or_zero()
}

/// `cos α · dir(a) + sin α · b`, normalised: a direction tilted from `a`
/// towards `b` (TopMod's `facenext` / `faceprev`).
fn tilt(a: DVec3, b: DVec3, alpha: f64) -> DVec3 {
    unit(alpha.cos() * unit(a) + alpha.sin() * b)
}

fn frame(p: &[DVec3]) -> (DVec3, f64) {
    let n = p.len();
    let nrm = unit((0..n).map(|j| p[j].cross(p[(j + 1) % n])).sum::<DVec3>());
    let l = (0..n).map(|j| (p[(j + 1) % n] - p[j]).length()).sum::<f64>() / n as f64;
    (nrm, l)
}

/// What both steps start from: the mean side length, the tilt angle, and
/// TopMod's tilted normal of every side `p_i → p_i+1`
/// (`facenext` at `p_i`; its `faceprev` at `p_i` is the same vector of side
/// `i − 1`, bit for bit: `nrm × unit(p_i−1 − p_i)` = `unit(p_i − p_i−1) × nrm`).
struct Base {
    lb: f64,
    alpha: f64,
    side: Vec<DVec3>,
}

impl Base {
    fn new(p: &[DVec3], angle: f64) -> Base {
        let n = p.len();
        let (nrm, lb) = frame(p);
        let alpha = -angle.to_radians();
        let side = (0..n).map(|i| tilt(unit(p[(i + 1) % n] - p[i]).cross(nrm), nrm, alpha)).collect();
        Base { lb, alpha, side }
    }
}

/// The rings R1, R2, R3 of one dodecahedral step over `p`.
pub(super) fn dodeca_rings(p: &[DVec3], angle: f64, l: [f64; 3]) -> [Vec<DVec3>; 3] {
    let n = p.len();
    let Base { lb, side, .. } = Base::new(p, angle);
    let (pr, nx) = (|i: usize| (i + n - 1) % n, |i: usize| (i + 1) % n);
    let fnext = |i: usize| side[i];
    let r1: Vec<DVec3> = (0..n).map(|i| p[i] + lb * l[0] * unit(side[pr(i)].cross(fnext(i)))).collect();
    let c54 = 54f64.to_radians().cos();
    let r2: Vec<DVec3> = (0..n).map(|i| (r1[i] + r1[nx(i)]) * 0.5 + lb * c54 * l[1] * unit(fnext(i).cross(unit(p[nx(i)] - p[i])))).collect();
    // the normal of the triangle (a, b, c) seen from b, as TopMod computes it
    let tri = |a: DVec3, b: DVec3, c: DVec3| unit(unit(c - b).cross(unit(a - b)));
    let r3: Vec<DVec3> = (0..n)
        .map(|i| {
            let lo = ((p[pr(i)] - p[i]).length() + (p[nx(i)] - p[i]).length()) * 0.5 * l[2] * l[2];
            let fprev = tri(r2[pr(i)], r1[i], r2[i]);
            let fnext = tri(r2[i], r1[nx(i)], r2[nx(i)]);
            r2[i] + lo * unit(fprev.cross(fnext))
        })
        .collect();
    [r1, r2, r3]
}

/// The rings Q1, C, Q2 of one icosahedral step over `p` (C_i sits over p_i).
pub(super) fn icosa_rings(p: &[DVec3], angle: f64, l: [f64; 3]) -> [Vec<DVec3>; 3] {
    let n = p.len();
    let Base { lb, alpha, side, .. } = Base::new(p, angle);
    let (pr, nx) = (|i: usize| (i + n - 1) % n, |i: usize| (i + 1) % n);
    let fnext = |i: usize| side[i];
    let q1: Vec<DVec3> = (0..n)
        .map(|i| (p[i] + p[nx(i)]) * 0.5 + lb * l[0] * 3f64.sqrt() * 0.5 * unit(fnext(i).cross(unit(p[nx(i)] - p[i]))))
        .collect();
    // TopMod's direction from two face normals tilted about the sides to `vn` and `vp`
    let dir = |fprev: DVec3, fnext: DVec3, vp: DVec3, vn: DVec3| {
        let (fnx, fpx) = (-fnext, -fprev);
        let fn2 = tilt(vn.cross(fnx), fnx, alpha);
        let fp2 = tilt(fpx.cross(vp), fpx, alpha);
        unit(fp2.cross(fn2))
    };
    let c: Vec<DVec3> = (0..n).map(|i| p[i] + lb * l[1] * dir(side[pr(i)], fnext(i), q1[pr(i)] - p[i], q1[i] - p[i])).collect();
    let q2: Vec<DVec3> = (0..n)
        .map(|i| {
            let at = q1[i];
            let (vprev, vnext) = (unit(c[i] - at), unit(c[nx(i)] - at));
            let (vn2, vp2) = (unit(p[nx(i)] - at), unit(p[i] - at));
            let fprev = unit(vprev.cross(vp2));
            let fnext = unit(vn2.cross(vnext));
            at + lb * l[2] * dir(fprev, fnext, vp2, vn2)
        })
        .collect();
    [q1, c, q2]
}

/// Faces of one dodecahedral step from `ring` (sides keyed `rkey`) to the
/// rings at vertex bases `b`, with 5n keys from `k`; returns the top ring's
/// keys (R3_j → R3_{j+1}).
pub(super) fn dodeca_band(o: &mut Out, ring: &[u32], rkey: &[u32], b: [u32; 3], k: u32) -> Vec<u32> {
    let n = ring.len() as u32;
    // keys: R0_j–R1_j, R1_{j+1}–R2_j, R1_j–R2_j, R2_j–R3_j, R3_j–R3_{j+1}
    let (v1, x, y, v3, t) = (|j: u32| k + j, |j: u32| k + n + j, |j: u32| k + 2 * n + j, |j: u32| k + 3 * n + j, |j: u32| k + 4 * n + j);
    for j in 0..n {
        let q = (j + 1) % n;
        let (r1, r2, r3) = (|i: u32| b[0] + i, |i: u32| b[1] + i, |i: u32| b[2] + i);
        o.c(ring[j as usize], rkey[j as usize]);
        o.c(ring[q as usize], v1(q));
        o.c(r1(q), x(j));
        o.c(r2(j), y(j));
        o.c(r1(j), v1(j));
        o.end();
        o.c(r2(j), x(j));
        o.c(r1(q), y(q));
        o.c(r2(q), v3(q));
        o.c(r3(q), t(j));
        o.c(r3(j), v3(j));
        o.end();
    }
    (0..n).map(t).collect()
}

/// Faces of one icosahedral step (as [`dodeca_band`], 9n keys); returns the
/// top ring's keys (Q2_j → Q2_{j+1}).
pub(super) fn icosa_band(o: &mut Out, ring: &[u32], rkey: &[u32], b: [u32; 3], k: u32) -> Vec<u32> {
    let n = ring.len() as u32;
    // keys: p_j–Q1_j, p_{j+1}–Q1_j, Q1_j–Q2_j, Q2_j–Q2_{j+1}, then the five
    // spokes of the centre C_{j+1} (to Q1_j, p_{j+1}, Q1_{j+1}, Q2_{j+1}, Q2_j)
    let (pk, pn, u, t) = (|j: u32| k + j, |j: u32| k + n + j, |j: u32| k + 2 * n + j, |j: u32| k + 3 * n + j);
    let s = |j: u32, i: u32| k + 4 * n + 5 * j + i;
    let (q1, q2) = (|i: u32| b[0] + i, |i: u32| b[2] + i);
    for j in 0..n {
        let q = (j + 1) % n;
        let c = b[1] + q;
        let (pj, pq) = (ring[j as usize], ring[q as usize]);
        for [(v0, k0), (v1, k1), (v2, k2)] in [
            [(pj, rkey[j as usize]), (pq, pn(j)), (q1(j), pk(j))],
            [(q1(j), pn(j)), (pq, s(j, 1)), (c, s(j, 0))],
            [(pq, pk(q)), (q1(q), s(j, 2)), (c, s(j, 1))],
            [(q1(q), u(q)), (q2(q), s(j, 3)), (c, s(j, 2))],
            [(q2(q), t(j)), (q2(j), s(j, 4)), (c, s(j, 3))],
            [(q2(j), u(j)), (q1(j), s(j, 0)), (c, s(j, 4))],
        ] {
            o.c(v0, k0);
            o.c(v1, k1);
            o.c(v2, k2);
            o.end();
        }
    }
    (0..n).map(t).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// TopMod's `faceprev` at p_i, as both steps computed it before they
    /// shared [`Base`], is the side normal of side i − 1, bit for bit.
    #[test]
    fn faceprev_is_the_previous_side_normal() {
        let p = [DVec3::new(0.0, 0.0, 0.1), DVec3::new(1.3, 0.2, 0.0), DVec3::new(1.1, 1.7, -0.2), DVec3::new(0.2, 1.4, 0.3), DVec3::new(-0.4, 0.6, 0.0)];
        for angle in [0.0, 17.0, -40.0] {
            let b = Base::new(&p, angle);
            let (nrm, _) = frame(&p);
            for i in 0..p.len() {
                let pr = (i + p.len() - 1) % p.len();
                let fprev = tilt(nrm.cross(unit(p[pr] - p[i])), nrm, -f64::to_radians(angle));
                assert_eq!(fprev.to_array().map(f64::to_bits), b.side[pr].to_array().map(f64::to_bits));
            }
        }
    }
}

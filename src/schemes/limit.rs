//! Limit positions and normals of Catmull-Clark and Loop surfaces at the
//! mesh's vertices (limit stencils), with OpenSubdiv's masks (`sdc/
//! catmarkScheme.h`, `sdc/loopScheme.h`, 3.6: Halstead, Kass & DeRose 1993
//! for the smooth Catmull-Clark tangents, Biermann, Levin & Zorin 2000 for
//! the crease tangents).
//!
//! The masks need the neighbourhood the scheme makes (quads for
//! Catmull-Clark, triangles for Loop) and no semi-sharp crease left, so the
//! mesh is first refined `1 + ⌈s⌉` levels (s the largest finite
//! sharpness); a vertex's limit point is that of its vertex point at every
//! level, so the result is the input vertices' limit. Normals are
//! `T1 × T2`, unit length, oriented like the faces around the vertex.
//! They are exact (unchanged by refining first, tested) everywhere: for
//! Catmull-Clark and smooth Loop vertices with OpenSubdiv's masks, and at
//! Loop's crease and boundary vertices with the cross tangent the plain
//! crease rules make ([`loop_cross_tangent`]: a left eigenvector of the
//! local subdivision matrix). OpenSubdiv's own Loop crease mask for more
//! than two interior edges is Biermann, Levin & Zorin's, made for their
//! modified rules, so its normals there differ from these by design (up to
//! a few degrees; topomesh subdivides with the plain rules, as OpenSubdiv
//! does). With six or more interior edges the plain rules' interior mode
//! outgrows the crease's `½` (the known lack of tangent continuity there,
//! Biermann, Levin & Zorin 2000, §3); the normal is still the eigenvectors'.

use super::creases::{ring, Creases, LevelSharpness, Rule, SubdivOptions, INFINITE};
use super::level::{Level, Request};
use crate::error::Result;
use crate::mesh::{Mesh, POINT};
use glam::DVec3;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Which surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitScheme {
    CatmullClark,
    Loop,
}

/// Limit positions and unit normals at every input vertex (a
/// point-sphere's normal is zero).
pub struct LimitPoints {
    pub positions: Vec<DVec3>,
    pub normals: Vec<DVec3>,
    /// Levels refined before the masks were applied.
    pub levels: usize,
}

pub fn limit_points(m: &Mesh, scheme: LimitScheme, creases: Option<&Creases>, options: SubdivOptions) -> Result<LimitPoints> {
    let level: fn(&Mesh, &Request) -> Result<Level> = match scheme {
        LimitScheme::CatmullClark => super::catmull_clark::catmull_clark_level,
        LimitScheme::Loop => super::loop_subdivision::loop_level,
    };
    let max_semi = creases.map_or(0.0, |c| c.edge.iter().chain(&c.vertex).copied().filter(|&s| s < INFINITE).fold(0.0, f64::max));
    let levels = 1 + max_semi.ceil() as usize;
    let mut cur = m.clone();
    let mut cr = creases.cloned();
    for _ in 0..levels {
        let lv = level(&cur, &Request { creases: cr.as_ref(), options, ..Default::default() })?;
        cur = lv.mesh;
        cr = lv.creases;
    }
    // input vertex v is vertex point `rank(v)` of every level (point-spheres go last)
    let mut rank = Vec::with_capacity(m.n_vertices());
    let mut k = 0usize;
    for &o in &m.v_out {
        rank.push(if o & POINT != 0 { usize::MAX } else { k });
        k += (o & POINT == 0) as usize;
    }
    let ls = LevelSharpness::new(&cur, cr.as_ref(), options);
    let out: Vec<(DVec3, DVec3)> = (0..m.n_vertices())
        .into_par_iter()
        .map(|v| if rank[v] == usize::MAX { (m.pos[v], DVec3::ZERO) } else { vertex_limit(&cur, &ls, rank[v], scheme, options) })
        .collect();
    crate::cancel::check()?;
    let (positions, normals) = out.into_iter().unzip();
    Ok(LimitPoints { positions, normals, levels })
}

/// Weights of Loop's cross-crease tangent at a crease vertex with `k ≥ 1`
/// interior edges `e₁ … e_k` between its two crease edges (ends `e₀`,
/// `e_{k+1}`): the symmetric left eigenvector of the local subdivision
/// matrix of the plain rules (crease vertex `(e₀ + 6v + e_{k+1}) / 8`,
/// crease edges midpoints, interior edges `3/8 3/8 1/8 1/8`) for its
/// largest eigenvalue after the crease's `½`:
/// `λ = 3/8 + ¼ cos θ`, `θ = π / (k + 1)`. Loop's 1-ring maps onto the
/// refined 1-ring, so `Σ l p` scales by exactly `λ` per level and the
/// tangent's direction does not change under refinement. The interior
/// weights are `sin iθ` (the tridiagonal interior block's eigenvector); the
/// vertex's and ends' follow from the two other columns of `l S = λ l`:
///
/// ```text
/// (1/8) l_v + (1/2 − λ) l_e = −(1/8) l₁        (column e₀)
/// (3/4 − λ) l_v +      l_e = −(3/8) Σ sin iθ   (column v)
/// ```
///
/// (determinant nonzero: it vanishes only at λ = 1 and ¼). For k = 1 and
/// 2 this is OpenSubdiv's mask; for k ≥ 3 OpenSubdiv uses Biermann, Levin
/// & Zorin's mask, made for their modified interior weights near creases,
/// which is no eigenvector of the plain rules OpenSubdiv subdivides with.
pub(crate) struct CrossWeights {
    pub vertex: f64,
    pub end: f64,
    pub interior: Vec<f64>,
}

pub(crate) fn loop_cross_tangent(k: usize) -> CrossWeights {
    let th = PI / (k + 1) as f64;
    let lambda = 0.375 + 0.25 * th.cos();
    let interior: Vec<f64> = (1..=k).map(|i| (i as f64 * th).sin()).collect();
    let sum: f64 = interior.iter().sum();
    let (a, b, c, d) = (0.125, 0.5 - lambda, 0.75 - lambda, 1.0);
    let (r1, r2) = (-0.125 * interior[0], -0.375 * sum);
    let det = a * d - b * c;
    CrossWeights { vertex: (r1 * d - b * r2) / det, end: (a * r2 - c * r1) / det, interior }
}

/// OpenSubdiv's masks at vertex `v` of a refined mesh `m`.
fn vertex_limit(m: &Mesh, ls: &LevelSharpness, v: usize, scheme: LimitScheme, options: SubdivOptions) -> (DVec3, DVec3) {
    let (next, vert, face) = m.halfedge_columns();
    let p = &m.pos;
    let hole = |h: u32| m.f_hole[face[h as usize] as usize];
    // edges counter-clockwise; at a boundary, from the edge after the hole
    let mut hs: Vec<u32> = ring(m, m.v_out[v]).collect();
    if let Some(i) = hs.iter().position(|&h| hole(h)) {
        let n = hs.len();
        hs.rotate_left((i + 1) % n);
    }
    let n_faces = hs.iter().filter(|&&h| !hole(h)).count();
    let e = |i: usize| p[vert[(hs[i] ^ 1) as usize] as usize];
    // the vertex of face i (between edges i and i + 1) opposite v
    let f = |i: usize| p[vert[next[next[hs[i] as usize] as usize] as usize] as usize];
    let pv = p[v];
    let r = ls.vertex_rule(m, v, options.crease_method);
    let mut rule = r.parent;
    let mut ends = [0usize; 2];
    if rule == Rule::Crease {
        let mut k = 0;
        for (i, &h) in hs.iter().enumerate() {
            if ls.edge[(h >> 1) as usize] > 0.0 && k < 2 {
                ends[k] = i;
                k += 1;
            }
        }
    }
    if matches!(rule, Rule::Smooth | Rule::Dart) && n_faces == 2 {
        rule = Rule::Corner;
    }
    let (pos, t1, t2) = match (scheme, rule) {
        (_, Rule::Corner) => {
            let s = if scheme == LimitScheme::Loop { 3.0 } else { 1.0 };
            (pv, (e(0) - pv) * s, (e(1) - pv) * s)
        }
        (LimitScheme::CatmullClark, Rule::Crease) => {
            let pos = pv * (2.0 / 3.0) + (e(ends[0]) + e(ends[1])) / 6.0;
            let t1 = (e(ends[0]) - e(ends[1])) * 0.5;
            let interior = ends[1] - ends[0] - 1;
            let t2 = if interior == 1 {
                pv * (-4.0 / 6.0) + (e(ends[0]) + e(ends[1])) * (-1.0 / 6.0) + e(ends[0] + 1) * (4.0 / 6.0) + (f(ends[0]) + f(ends[0] + 1)) / 6.0
            } else if interior > 1 {
                let k = (interior + 1) as f64;
                let th = PI / k;
                let denom = 1.0 / (k * (3.0 + th.cos()));
                let rr = (th.cos() + 1.0) / th.sin();
                let mut t = pv * (4.0 * rr * (th.cos() - 1.0) * denom) + (e(ends[0]) + e(ends[1])) * (-rr * (1.0 + 2.0 * th.cos()) * denom) + f(ends[0]) * (th.sin() * denom);
                for i in 1..(interior + 1) {
                    let (si, si1) = ((i as f64 * th).sin(), ((i + 1) as f64 * th).sin());
                    t += e(ends[0] + i) * (4.0 * si * denom);
                    if ends[0] + i < n_faces {
                        t += f(ends[0] + i) * ((si + si1) * denom);
                    }
                }
                t
            } else {
                pv * -6.0 + (e(ends[0]) + e(ends[1])) * 3.0
            };
            (pos, t1, t2)
        }
        (LimitScheme::Loop, Rule::Crease) => {
            let pos = pv * (4.0 / 6.0) + (e(ends[0]) + e(ends[1])) / 6.0;
            let t1 = (e(ends[0]) - e(ends[1])) * 1.5;
            let interior = ends[1] - ends[0] - 1;
            let t2 = if interior == 0 {
                pv * -6.0 + (e(ends[0]) + e(ends[1])) * 3.0
            } else {
                let w = loop_cross_tangent(interior);
                let mut t = pv * w.vertex + (e(ends[0]) + e(ends[1])) * w.end;
                for i in 1..=interior {
                    t += e(ends[0] + i) * w.interior[i - 1];
                }
                t
            };
            (pos, t1, t2)
        }
        (LimitScheme::CatmullClark, _) => {
            let n = n_faces as f64;
            let fw = 1.0 / (n * (n + 5.0));
            let ew = 4.0 * fw;
            let mut pos = pv * (1.0 - n * (ew + fw));
            let (mut t1, mut t2) = (DVec3::ZERO, DVec3::ZERO);
            let th = 2.0 * PI / n;
            let lambda = 5.0 / 16.0 + (th.cos() + (th * 0.5).cos() * (2.0 * (9.0 + th.cos())).sqrt()) / 16.0;
            let fscale = if n_faces == 4 { 1.0 } else { 1.0 / (4.0 * lambda - 1.0) };
            for i in 0..n_faces {
                pos += e(i) * ew + f(i) * fw;
                let (c0, c1) = ((i as f64 * th).cos(), ((i + 1) as f64 * th).cos());
                // T2 is T1 rotated by one edge (OpenSubdiv)
                let j = (i + 1) % n_faces;
                let (s0, s1) = ((i as f64 * th).cos(), ((i + 1) as f64 * th).cos());
                t1 += e(i) * (4.0 * c0) + f(i) * (fscale * (c0 + c1));
                t2 += e(j) * (4.0 * s0) + f(j) * (fscale * (s0 + s1));
            }
            (pos, t1, t2)
        }
        (LimitScheme::Loop, _) => {
            let n = n_faces as f64;
            let beta = 0.25 * (2.0 * PI / n).cos() + 0.375;
            let gamma = (0.625 - beta * beta) / n;
            let ew = 1.0 / (n + 3.0 / (8.0 * gamma));
            let mut pos = pv * (1.0 - ew * n);
            let (mut t1, mut t2) = (DVec3::ZERO, DVec3::ZERO);
            for i in 0..n_faces {
                let a = 2.0 * PI * i as f64 / n;
                pos += e(i) * ew;
                t1 += e(i) * a.cos();
                t2 += e(i) * a.sin();
            }
            (pos, t1, t2)
        }
    };
    // orient like the faces around v (their Newell normals)
    let mut around = DVec3::ZERO;
    for &h in &hs {
        if !hole(h) {
            around += m.face_newell(crate::mesh::FaceId(face[h as usize]));
        }
    }
    let mut nrm = t1.cross(t2);
    if nrm.dot(around) < 0.0 {
        nrm = -nrm;
    }
    (pos, nrm.normalize_or_zero())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::creases::Boundary;
    use crate::schemes::hosts::test_meshes::*;

    /// A vertex's limit point and normal do not change when the mesh is
    /// refined first: the masks are exact.
    fn invariant(m: &Mesh, scheme: LimitScheme, c: Option<&Creases>, options: SubdivOptions) {
        let a = limit_points(m, scheme, c, options).unwrap();
        let level = match scheme {
            LimitScheme::CatmullClark => crate::schemes::catmull_clark::catmull_clark_level,
            LimitScheme::Loop => crate::schemes::loop_subdivision::loop_level,
        };
        let lv = level(m, &Request { creases: c, options, ..Default::default() }).unwrap();
        let b = limit_points(&lv.mesh, scheme, lv.creases.as_ref(), options).unwrap();
        let scale = m.positions().iter().map(|p| p.length()).fold(1.0, f64::max);
        for v in 0..m.n_vertices() {
            assert!((a.positions[v] - b.positions[v]).length() < 1e-10 * scale, "{scheme:?} vertex {v}: {} vs {}", a.positions[v], b.positions[v]);
            assert!(a.normals[v].dot(b.normals[v]) > 1.0 - 1e-9, "{scheme:?} normal {v}: {} vs {}", a.normals[v], b.normals[v]);
        }
    }

    #[test]
    fn limit_points_are_invariant_under_refinement() {
        let opts = SubdivOptions::default();
        for s in [LimitScheme::CatmullClark, LimitScheme::Loop] {
            for m in [crate::primitives::cube(), crate::primitives::torus(6, 4, 1.0, 0.4).unwrap(), crate::primitives::icosahedron(), open_grid(3), open_tube(6, 2), cube_with_hole()] {
                invariant(&m, s, None, opts);
                invariant(&m, s, None, SubdivOptions { boundary: Boundary::EdgeOnly, ..opts });
            }
            let m = crate::primitives::cube();
            let mut c = Creases { edge: vec![0.0; 12], vertex: vec![0.0; 8] };
            c.edge[0] = INFINITE;
            c.edge[3] = INFINITE;
            c.edge[5] = 1.5;
            c.vertex[6] = INFINITE;
            invariant(&m, s, Some(&c), opts);
        }
    }

    /// `l S = λ l` on the local matrix of Loop's plain crease rules, built
    /// row by row (order: v, e₀ … e_{k+1}).
    #[test]
    fn loop_cross_tangent_is_a_left_eigenvector() {
        for k in 1..=9usize {
            let n = k + 3;
            let mut s = vec![vec![0.0; n]; n];
            s[0][0] = 0.75;
            s[0][1] = 0.125;
            s[0][k + 2] = 0.125;
            for j in [1, k + 2] {
                s[j][0] = 0.5;
                s[j][j] = 0.5;
            }
            for i in 2..k + 2 {
                s[i][0] = 0.375;
                s[i][i] = 0.375;
                s[i][i - 1] = 0.125;
                s[i][i + 1] = 0.125;
            }
            let w = loop_cross_tangent(k);
            let mut l = vec![w.vertex, w.end];
            l.extend(&w.interior);
            l.push(w.end);
            let lambda = 0.375 + 0.25 * (PI / (k + 1) as f64).cos();
            for c in 0..n {
                let ls: f64 = (0..n).map(|r| l[r] * s[r][c]).sum();
                assert!((ls - lambda * l[c]).abs() < 1e-12, "k = {k}, column {c}");
            }
            assert!(l.iter().sum::<f64>().abs() < 1e-12, "annihilates constants");
        }
    }

    #[test]
    fn normals_point_outward_and_limit_lies_inside_the_hull() {
        for s in [LimitScheme::CatmullClark, LimitScheme::Loop] {
            let m = crate::primitives::cube();
            let l = limit_points(&m, s, None, SubdivOptions::default()).unwrap();
            for v in 0..8 {
                // the cube's corners: normals along the diagonal, limit points pulled inside
                let d = m.positions()[v].normalize();
                assert!(l.normals[v].dot(d) > 0.999, "{s:?} {v}");
                assert!(l.positions[v].length() < m.positions()[v].length());
                assert!((l.positions[v].normalize() - d).length() < 1e-12);
            }
        }
    }
}

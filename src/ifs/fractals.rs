//! Fractals with control points (section 4).
//!
//! Given affine maps `F = {f_1..f_k}` of `R^D` and chosen control points
//! `P_1..P_m`, every image `f_i(P_j)` is written as an affine combination of
//! the control points (eq. 5); the weights are row `j` of block `S_i`. The
//! IFS `X P⁻¹ S_i P` then draws the classical fractal for the reference
//! control points and a deformed one when they move.
//!
//! The decomposition is not unique. [`affine_rule_blocks`] uses barycentric
//! coordinates with respect to `D+1` nearby control points, as the paper does
//! for the Koch curve; among the affinely independent `(D+1)`-subsets of the
//! nearest points it takes the one with the smallest `Σ|α|` (a convex
//! combination when there is one), then the nearest, then the lowest indices.
//! The gasket uses the paper's rules instead: quadratic Lagrange weights along
//! the outer edges, linear interpolation along interior edges.

use super::{invalid, Domain, Ifs, Mat};
use crate::Result;

/// An affine map `x ↦ A x + t` of `R^D` (column vectors).
pub type Affine = (Vec<Vec<f64>>, Vec<f64>);

fn apply(f: &Affine, x: &[f64]) -> Vec<f64> {
    f.0.iter().zip(&f.1).map(|(row, t)| row.iter().zip(x).map(|(a, b)| a * b).sum::<f64>() + t).collect()
}

fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Barycentric weights of `x` w.r.t. the control points `subset`, or `None`
/// if they are affinely dependent.
fn barycentric(points: &[Vec<f64>], subset: &[usize], x: &[f64]) -> Option<Vec<f64>> {
    let d = x.len();
    // columns: [p; 1] for each subset point
    let mut m = Mat::zeros(d + 1, d + 1);
    for (c, &i) in subset.iter().enumerate() {
        for r in 0..d {
            m.set(r, c, points[i][r]);
        }
        m.set(d, c, 1.0);
    }
    let inv = m.inverse()?;
    let rhs: Vec<f64> = x.iter().copied().chain(std::iter::once(1.0)).collect();
    Some((0..d + 1).map(|r| (0..d + 1).map(|c| inv.at(r, c) * rhs[c]).sum()).collect())
}

fn combinations(n: usize, k: usize) -> Vec<Vec<usize>> {
    fn rec(start: usize, n: usize, k: usize, cur: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        if cur.len() == k {
            out.push(cur.clone());
            return;
        }
        for i in start..n {
            cur.push(i);
            rec(i + 1, n, k, cur, out);
            cur.pop();
        }
    }
    let mut out = Vec::new();
    rec(0, n, k, &mut Vec::new(), &mut out);
    out
}

/// The weights of eq. 5 for one point `x` (see the module doc for the choice).
pub fn nearest_weights(points: &[Vec<f64>], x: &[f64]) -> Result<Vec<f64>> {
    let d = x.len();
    let mut order: Vec<usize> = (0..points.len()).collect();
    let dist: Vec<f64> = points.iter().map(|p| dist2(p, x).sqrt()).collect();
    let scale = dist.iter().fold(0.0f64, |a, &b| a.max(b)).max(1e-300);
    order.sort_by(|&a, &b| {
        let (da, db) = (dist[a], dist[b]);
        if (da - db).abs() <= 1e-9 * scale {
            a.cmp(&b)
        } else {
            da.partial_cmp(&db).unwrap()
        }
    });
    let k = points.len().min(2 * d + 2);
    let mut best: Option<(f64, f64, Vec<usize>, Vec<f64>)> = None;
    for comb in combinations(k, d + 1) {
        let subset: Vec<usize> = comb.iter().map(|&i| order[i]).collect();
        let Some(w) = barycentric(points, &subset, x) else { continue };
        let l1 = (w.iter().map(|v| v.abs()).sum::<f64>() * 1e9).round() / 1e9;
        let near: f64 = subset.iter().map(|&i| dist[i]).sum::<f64>();
        let near = (near / scale * 1e9).round() / 1e9;
        let mut sorted = subset.clone();
        sorted.sort();
        let better = match &best {
            None => true,
            Some((bl, bn, bs, _)) => (l1, near, &sorted) < (*bl, *bn, bs),
        };
        if better {
            best = Some((l1, near, sorted.clone(), subset.iter().zip(&w).fold(vec![0.0; points.len()], |mut acc, (&i, &v)| {
                acc[i] = v;
                acc
            })));
        }
    }
    best.map(|b| b.3).ok_or_else(|| {
        invalid("control points are not an affine basis: no D+1 of them are affinely independent")
    })
}

/// Eq. 5: block `S_i` has row `j` = weights of `f_i(P_j)` over the control
/// points (see [`nearest_weights`]).
pub fn affine_rule_blocks(maps: &[Affine], points: &[Vec<f64>]) -> Result<Vec<Mat>> {
    let n = points.len();
    let dim = points.first().map_or(0, |p| p.len());
    let mut blocks = Vec::new();
    for (i, f) in maps.iter().enumerate() {
        if f.1.len() != dim || f.0.len() != dim || f.0.iter().any(|r| r.len() != dim) {
            return Err(invalid(format!("affine map {i}: expected a {dim}x{dim} matrix and a length-{dim} vector")));
        }
        let mut s = Mat::zeros(n, n);
        for (j, p) in points.iter().enumerate() {
            let w = nearest_weights(points, &apply(f, p))?;
            s.data[j * n..(j + 1) * n].copy_from_slice(&w);
        }
        blocks.push(s);
    }
    Ok(blocks)
}

/// The subdivision IFS of eq. 5: rules derived at `reference` control points,
/// drawn with `points` (same count; pass the reference itself for the
/// classical fractal).
pub fn affine_with_control(maps: &[Affine], reference: &[Vec<f64>], points: &[Vec<f64>], name: &str) -> Result<Ifs> {
    if reference.len() != points.len() {
        return Err(invalid("reference and control points must have the same count"));
    }
    let blocks = affine_rule_blocks(maps, reference)?;
    Ifs::from_subdivision(blocks, points, name)
}

/// The classical Koch maps on the segment `[0, 1] × {0}`, in order along the curve.
pub fn koch_maps() -> Vec<Affine> {
    let (c, s) = (0.5 / 3.0, (3f64).sqrt() / 6.0);
    vec![
        (vec![vec![1.0 / 3.0, 0.0], vec![0.0, 1.0 / 3.0]], vec![0.0, 0.0]),
        (vec![vec![c, -s], vec![s, c]], vec![1.0 / 3.0, 0.0]),
        (vec![vec![c, s], vec![-s, c]], vec![0.5, s]),
        (vec![vec![1.0 / 3.0, 0.0], vec![0.0, 1.0 / 3.0]], vec![2.0 / 3.0, 0.0]),
    ]
}

/// The five natural Koch control points: the ends, the thirds and the apex.
pub fn koch_reference() -> Vec<Vec<f64>> {
    vec![vec![0.0, 0.0], vec![1.0 / 3.0, 0.0], vec![0.5, (3f64).sqrt() / 6.0], vec![2.0 / 3.0, 0.0], vec![1.0, 0.0]]
}

/// Section 4.1: the Koch curve with five control points and four maps.
pub fn koch_ifs(points: &[Vec<f64>]) -> Result<Ifs> {
    if points.len() != 5 {
        return Err(invalid(format!("koch: expected 5 control points, got {}", points.len())));
    }
    let mut ifs = affine_with_control(&koch_maps(), &koch_reference(), points, "koch")?;
    ifs.set_domain(Domain::Interval);
    Ok(ifs)
}

/// The gasket's six reference control points: corners at even indices, edge
/// midpoints between them (`P1` on `P0P2`, `P3` on `P2P4`, `P5` on `P4P0`).
pub fn gasket_reference() -> Vec<Vec<f64>> {
    let h = (3f64).sqrt() / 2.0;
    vec![vec![0.0, 0.0], vec![0.5, 0.0], vec![1.0, 0.0], vec![0.75, h / 2.0], vec![0.5, h], vec![0.25, h / 2.0]]
}

/// Section 4.2: the Sierpinski gasket with six control points. Map `i`
/// scales by ½ towards corner `2i`; the rules are derived in code: images on
/// an outer edge get quadratic Lagrange weights on that edge's three control
/// points, interior images are interpolated linearly on the shortest
/// control-point segment through them.
pub fn gasket_ifs(points: &[Vec<f64>]) -> Result<Ifs> {
    if points.len() != 6 {
        return Err(invalid(format!("gasket: expected 6 control points, got {}", points.len())));
    }
    let r = gasket_reference();
    let edges = [(0usize, 1usize, 2usize), (2, 3, 4), (4, 5, 0)];
    let mut blocks = Vec::new();
    for corner in [0usize, 2, 4] {
        let mut s = Mat::zeros(6, 6);
        for j in 0..6 {
            let x = [0.5 * (r[j][0] + r[corner][0]), 0.5 * (r[j][1] + r[corner][1])];
            let row = &mut s.data[j * 6..(j + 1) * 6];
            let on_segment = |a: usize, b: usize| -> Option<f64> {
                let (ab, ax) = ([r[b][0] - r[a][0], r[b][1] - r[a][1]], [x[0] - r[a][0], x[1] - r[a][1]]);
                let len2 = ab[0] * ab[0] + ab[1] * ab[1];
                let t = (ab[0] * ax[0] + ab[1] * ax[1]) / len2;
                let cross = ab[0] * ax[1] - ab[1] * ax[0];
                (cross.abs() < 1e-12 && (-1e-12..=1.0 + 1e-12).contains(&t)).then_some(t)
            };
            if let Some((&(a, m, b), t)) = edges.iter().find_map(|e| on_segment(e.0, e.2).map(|t| (e, t))) {
                // quadratic Lagrange interpolation at nodes 0, ½, 1 along the outer edge
                row[a] += 2.0 * (t - 0.5) * (t - 1.0);
                row[m] += -4.0 * t * (t - 1.0);
                row[b] += 2.0 * t * (t - 0.5);
            } else {
                let mut best: Option<(f64, usize, usize, f64)> = None;
                for a in 0..6 {
                    for b in a + 1..6 {
                        if let Some(t) = on_segment(a, b) {
                            let l = dist2(&r[a], &r[b]);
                            if best.map_or(true, |q| l < q.0 - 1e-12) {
                                best = Some((l, a, b, t));
                            }
                        }
                    }
                }
                let (_, a, b, t) = best.ok_or_else(|| invalid("gasket: interior image on no control segment"))?;
                row[a] += 1.0 - t;
                row[b] += t;
            }
        }
        blocks.push(s);
    }
    let mut ifs = Ifs::from_subdivision(blocks, points, "gasket")?;
    let maps = vec![([[1.0, 0.0], [0.0, 1.0]], [0.0, 0.0]), ([[1.0, 0.0], [0.0, 1.0]], [1.0, 0.0]), ([[1.0, 0.0], [0.0, 1.0]], [0.0, 1.0])];
    let mut domain = Domain::Planar {
        maps,
        scale: 2.0,
        vertices: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
        triangles: vec![[0, 1, 2]],
        lifted: Vec::new(),
    };
    let lifted = (0..3).map(|i| ifs.fixed_point(i)).collect();
    if let Domain::Planar { lifted: l, .. } = &mut domain {
        *l = lifted;
    }
    ifs.set_domain(domain);
    Ok(ifs)
}

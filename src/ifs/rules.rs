//! Subdivision blocks `S_i` derived from a scheme's rules (sections 2–3).
//!
//! A uniform scheme is given by its stencils, one per residue class of the
//! fine index modulo the arity; the blocks are the self-similar
//! sub-configurations of the refined control net: block `i` holds the fine
//! points `t_i + q` for every coarse control index `q`, so that its limit is
//! the `i`-th piece of the parameter domain. Adding a stationary scheme means
//! writing its stencils, never its matrices.
//!
//! * Curves: [`CurveRules`] (cubic B-spline eq. 4, Chaikin, four-point), with
//!   the split into blocks computed from the stencils' support and centroid.
//! * B-splines with self-similar knots by blossoming: [`bspline_blocks`]
//!   (end-point interpolating cubic on `0,0,0,1,2,2,2`, Bézier curves).
//! * Surfaces on lattices: [`LatticeRules`] — tensor products (bicubic),
//!   Loop's regular rules (the three-direction quartic box spline) and
//!   Kobbelt's √3 taken twice (a ternary split of the triangular lattice).

use super::{invalid, Domain, Ifs, Mat};
use crate::Result;
use std::collections::HashMap;

/// A uniform stationary curve scheme of arity `m`:
/// `p^{k+1}_{m i + r} = Σ_{(o, w) ∈ rules[r]} w · p^k_{i + o}`.
#[derive(Clone, Debug)]
pub struct CurveRules {
    pub arity: usize,
    pub rules: Vec<Vec<(i64, f64)>>,
}

impl CurveRules {
    /// Eq. 4: `p_{2i} = (p_{i-1} + 6 p_i + p_{i+1}) / 8`, `p_{2i+1} = (p_i + p_{i+1}) / 2`.
    pub fn cubic_bspline() -> CurveRules {
        CurveRules { arity: 2, rules: vec![vec![(-1, 0.125), (0, 0.75), (1, 0.125)], vec![(0, 0.5), (1, 0.5)]] }
    }

    /// Section 2.3, the interpolatory four-point scheme [DGL87].
    pub fn four_point() -> CurveRules {
        let w = 1.0 / 16.0;
        CurveRules { arity: 2, rules: vec![vec![(0, 1.0)], vec![(-1, -w), (0, 9.0 * w), (1, 9.0 * w), (2, -w)]] }
    }

    /// Chaikin's corner cutting (the quadratic B-spline).
    pub fn chaikin() -> CurveRules {
        CurveRules { arity: 2, rules: vec![vec![(0, 0.75), (1, 0.25)], vec![(0, 0.25), (1, 0.75)]] }
    }

    /// Checks arity, rule count and that every rule is an affine combination.
    pub fn check(&self) -> Result<()> {
        if self.arity < 2 || self.rules.len() != self.arity {
            return Err(invalid(format!(
                "curve rules: arity {} needs exactly that many stencils (got {})",
                self.arity,
                self.rules.len()
            )));
        }
        for (r, st) in self.rules.iter().enumerate() {
            let s: f64 = st.iter().map(|x| x.1).sum();
            if st.is_empty() || (s - 1.0).abs() > 1e-9 {
                return Err(invalid(format!("curve rules: stencil {r} sums to {s}, not 1")));
            }
        }
        Ok(())
    }

    /// Stencil of fine point `p` in absolute coarse indices.
    pub fn stencil(&self, p: i64) -> Vec<(i64, f64)> {
        let m = self.arity as i64;
        let (i, r) = (p.div_euclid(m), p.rem_euclid(m) as usize);
        self.rules[r].iter().map(|&(o, w)| (i + o, w)).collect()
    }

    /// Fine point `p` sits at coarse parameter `(p + σ) / m`, σ read off the
    /// stencils' centroids (schemes with linear precision).
    pub fn shift(&self) -> Result<f64> {
        let m = self.arity as f64;
        let mut sigma = None;
        for (r, st) in self.rules.iter().enumerate() {
            let c: f64 = st.iter().map(|&(o, w)| o as f64 * w).sum();
            let s = m * c - r as f64;
            match sigma {
                None => sigma = Some(s),
                Some(s0) if (s - s0).abs() > 1e-9 => {
                    return Err(invalid("curve rules: stencil centroids are not uniformly spaced"));
                }
                _ => {}
            }
        }
        Ok(sigma.unwrap_or(0.0))
    }

    /// Width of the basis function's support in coarse units:
    /// (max − min mask index) / (m − 1).
    pub fn support_width(&self) -> f64 {
        let m = self.arity as i64;
        let idx = self.rules.iter().enumerate().flat_map(|(r, st)| st.iter().map(move |&(o, _)| r as i64 - m * o));
        let (lo, hi) = idx.fold((i64::MAX, i64::MIN), |(a, b), x| (a.min(x), b.max(x)));
        (hi - lo) as f64 / (m - 1) as f64
    }

    /// The `m` square blocks for `n` control points. The limit curve is
    /// determined over `[ρ, n-1-ρ]`, `ρ = (W-2)/2` for support width `W`;
    /// block `i` is the `n` consecutive fine points whose own curve is the
    /// `i`-th of `m` equal pieces. Returns the blocks and their first fine index.
    pub fn blocks(&self, n: usize) -> Result<(Vec<Mat>, Vec<i64>)> {
        self.check()?;
        let m = self.arity as f64;
        let reach = (self.support_width() - 2.0) / 2.0;
        let (lo, hi) = (reach, n as f64 - 1.0 - reach);
        if hi - lo <= 1e-9 {
            return Err(invalid(format!(
                "{n} control points do not determine any piece of this curve (need more than {})",
                (2.0 * reach + 1.0).ceil()
            )));
        }
        let sigma = self.shift()?;
        let mut blocks = Vec::new();
        let mut starts = Vec::new();
        for i in 0..self.arity {
            let s = (m - 1.0) * lo + i as f64 * (hi - lo) - sigma;
            if (s - s.round()).abs() > 1e-9 {
                return Err(invalid(format!(
                    "{n} control points admit no self-similar split for this scheme (block {i} would start at fine index {s})"
                )));
            }
            let s = s.round() as i64;
            let mut b = Mat::zeros(n, n);
            for q in 0..n {
                for (j, w) in self.stencil(s + q as i64) {
                    if j < 0 || j >= n as i64 {
                        return Err(invalid(format!("block {i}: fine point {} needs control point {j}", s + q as i64)));
                    }
                    b.data[q * n + j as usize] += w;
                }
            }
            blocks.push(b);
            starts.push(s);
        }
        Ok((blocks, starts))
    }

    /// Plain subdivision of an open control polygon (`levels` rounds): every
    /// fine point whose stencil lies inside the polygon, in order.
    pub fn subdivide(&self, points: &[Vec<f64>], levels: usize) -> Result<Vec<Vec<f64>>> {
        self.check()?;
        let m = self.arity as i64;
        // at most (n + 8)·m points per level (the stencil range below), each a
        // Vec of `dim` floats: ~ 8·dim + 48 bytes with the allocator's header
        let dim = points.first().map_or(0, |p| p.len()) as u64;
        let (mut n, mut prev) = (points.len() as u64, points.len() as u64);
        for k in 1..=levels as u64 {
            n = n.saturating_add(8).saturating_mul(m as u64);
            let need = n.saturating_add(prev).saturating_mul(8 * dim + 48);
            crate::budget::check("subdivide_curve", &format!("level {k} of {levels}"), need)?;
            prev = n;
        }
        let mut cur = points.to_vec();
        for _ in 0..levels {
            crate::cancel::check()?;
            let n = cur.len() as i64;
            let dim = cur.first().map_or(0, |p| p.len());
            let mut next = Vec::new();
            for p in -4 * m..(n + 4) * m {
                let st = self.stencil(p);
                if st.iter().all(|&(j, _)| j >= 0 && j < n) {
                    let mut x = vec![0.0; dim];
                    for (j, w) in st {
                        x.iter_mut().zip(&cur[j as usize]).for_each(|(a, b)| *a += w * b);
                    }
                    next.push(x);
                }
            }
            if next.is_empty() {
                break;
            }
            cur = next;
        }
        Ok(cur)
    }
}

/// The curve IFS of a uniform scheme and `n` control points; its words in
/// lexicographic order run along the curve.
pub fn curve_ifs(rules: &CurveRules, points: &[Vec<f64>], name: &str) -> Result<Ifs> {
    let (blocks, _) = rules.blocks(points.len())?;
    let mut ifs = Ifs::from_subdivision(blocks, points, name)?;
    ifs.set_domain(Domain::Interval);
    Ok(ifs)
}

/// Weights over the control points of the blossom `b(u_1..u_d)` of the
/// B-spline piece on span `[k_j, k_{j+1}]` (knots without the two outer
/// dummies: control point `i` is `b(k_i, …, k_{i+d-1})`).
fn blossom(knots: &[f64], degree: usize, span: usize, args: &[f64]) -> Vec<f64> {
    let n = knots.len() + 1 - degree;
    let d = degree;
    let lo = span + 1 - d;
    let mut q: Vec<Vec<f64>> = (lo..=span + 1)
        .map(|i| {
            let mut e = vec![0.0; n];
            e[i] = 1.0;
            e
        })
        .collect();
    for (r, &u) in args.iter().enumerate() {
        let r = r + 1;
        for i in (lo + r..=span + 1).rev() {
            let (a, b) = (knots[i - 1], knots[i + d - r]);
            let t = (u - a) / (b - a);
            let (prev, cur) = (q[i - 1 - lo].clone(), &mut q[i - lo]);
            for (c, p) in cur.iter_mut().zip(prev) {
                *c = (1.0 - t) * p + t * *c;
            }
        }
    }
    q.pop().expect("non-empty")
}

/// Blocks of a degree-`d` B-spline whose knot sequence is self-similar under
/// the affine maps taking `[k_0, k_last]` onto each piece (section 2.1, by
/// blossoming [Ram89]). `knots` omits the two outer dummy knots, so there
/// are `knots.len() + 1 - d` control points; e.g. `d = 3`, knots
/// `0,0,0,1,2,2,2`, pieces `[0,1], [1,2]` gives the end-point interpolating
/// cubic, and `d = 2`, knots `0,0,1,1`, pieces `[0,½], [½,1]` a quadratic Bézier.
pub fn bspline_blocks(degree: usize, knots: &[f64], pieces: &[(f64, f64)]) -> Result<Vec<Mat>> {
    if degree == 0 || knots.len() < degree + 1 {
        return Err(invalid("B-spline: need degree >= 1 and at least degree + 1 knots"));
    }
    if knots.windows(2).any(|w| w[1] < w[0]) || knots.iter().any(|k| !k.is_finite()) {
        return Err(invalid("B-spline: knots must be finite and non-decreasing"));
    }
    let n = knots.len() + 1 - degree;
    let (k0, k1) = (knots[degree - 1], knots[n - 1]);
    if !(k1 > k0) {
        return Err(invalid("B-spline: empty parameter domain"));
    }
    let mut blocks = Vec::new();
    for &(a, b) in pieces {
        if !(a >= k0 && b <= k1 && b > a) {
            return Err(invalid(format!("B-spline: piece [{a}, {b}] is not inside the domain [{k0}, {k1}]")));
        }
        let phi = |t: f64| a + (b - a) * (t - k0) / (k1 - k0);
        let mid = 0.5 * (a + b);
        let span = (degree - 1..n - 1)
            .rev()
            .find(|&j| knots[j] <= mid && mid < knots[j + 1])
            .ok_or_else(|| invalid("B-spline: no knot span contains a piece"))?;
        let mut s = Mat::zeros(n, n);
        for r in 0..n {
            let args: Vec<f64> = (r..r + degree).map(|i| phi(knots[i])).collect();
            let w = blossom(knots, degree, span, &args);
            s.data[r * n..(r + 1) * n].copy_from_slice(&w);
        }
        blocks.push(s);
    }
    Ok(blocks)
}

/// The B-spline IFS (pieces consecutive and equal make it ordered).
pub fn bspline_ifs(degree: usize, knots: &[f64], pieces: &[(f64, f64)], points: &[Vec<f64>], name: &str) -> Result<Ifs> {
    let blocks = bspline_blocks(degree, knots, pieces)?;
    let mut ifs = Ifs::from_subdivision(blocks, points, name)?;
    let ordered = pieces.windows(2).all(|w| (w[0].1 - w[1].0).abs() < 1e-12 && ((w[0].1 - w[0].0) - (w[1].1 - w[1].0)).abs() < 1e-12);
    if ordered && pieces.first().map(|p| p.0) == Some(knots[degree - 1]) && pieces.last().map(|p| p.1) == Some(knots[knots.len() - degree]) {
        ifs.set_domain(Domain::Interval);
    }
    Ok(ifs)
}

/// A Bézier curve of degree `n-1` with `n` control points: halves by de Casteljau.
pub fn bezier_ifs(points: &[Vec<f64>]) -> Result<Ifs> {
    let d = points.len().saturating_sub(1);
    if d == 0 {
        return Err(invalid("Bézier: need at least two control points"));
    }
    let knots: Vec<f64> = std::iter::repeat(0.0).take(d).chain(std::iter::repeat(1.0).take(d)).collect();
    bspline_ifs(d, &knots, &[(0.0, 0.5), (0.5, 1.0)], points, "bezier")
}

/// Lattice subdivision rules in 2D: fine point `p` (in fine lattice
/// coordinates, `m` times the coarse ones) is `Σ w · coarse[c]`.
#[derive(Clone, Debug)]
pub enum LatticeRules {
    /// Tensor product of a curve scheme on the square lattice (bicubic from eq. 4).
    Tensor(CurveRules),
    /// Loop's regular rules = three-direction quartic box spline, on the
    /// triangular lattice with basis `e_0 = (1, 0)`, `e_1 = (½, √3/2)`.
    Loop,
    /// Two rounds of Kobbelt's √3 (α = 1/3 at valence 6): a ternary split.
    Sqrt3,
}

/// The six neighbour offsets on the triangular lattice, counter-clockwise.
pub const HEX_DIRS: [[i64; 2]; 6] = [[1, 0], [0, 1], [-1, 1], [-1, 0], [0, -1], [1, -1]];

fn add(a: [i64; 2], b: [i64; 2]) -> [i64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

/// Hexagonal (lattice) distance of `(a, b)` from the origin.
pub fn hex_norm(p: [i64; 2]) -> i64 {
    let (a, b) = (p[0], p[1]);
    if (a >= 0) == (b >= 0) {
        (a + b).abs()
    } else {
        a.abs().max(b.abs())
    }
}

/// Lattice points of hex radius `r`, ring by ring (center first, each ring
/// counter-clockwise from `r e_0`). `1 + 3r(r+1)` points.
pub fn hex_lattice(r: i64) -> Vec<[i64; 2]> {
    let mut out = vec![[0, 0]];
    for k in 1..=r {
        let mut p = [k, 0];
        for side in 0..6 {
            let d = HEX_DIRS[(side + 2) % 6];
            for _ in 0..k {
                out.push(p);
                p = add(p, d);
            }
        }
    }
    out
}

/// Cartesian position of a triangular-lattice point.
pub fn hex_to_xy(p: [f64; 2]) -> [f64; 2] {
    [p[0] + 0.5 * p[1], p[1] * 3f64.sqrt() / 2.0]
}

impl LatticeRules {
    pub fn arity(&self) -> i64 {
        match self {
            LatticeRules::Tensor(c) => c.arity as i64,
            LatticeRules::Loop => 2,
            LatticeRules::Sqrt3 => 3,
        }
    }

    pub fn stencil(&self, p: [i64; 2]) -> Vec<([i64; 2], f64)> {
        match self {
            LatticeRules::Tensor(c) => {
                let (u, v) = (c.stencil(p[0]), c.stencil(p[1]));
                v.iter().flat_map(|&(j, wj)| u.iter().map(move |&(i, wi)| ([i, j], wi * wj))).collect()
            }
            LatticeRules::Loop => {
                let c = [p[0].div_euclid(2), p[1].div_euclid(2)];
                let at = |o: [i64; 2], w: f64| (add(c, o), w);
                match (p[0].rem_euclid(2), p[1].rem_euclid(2)) {
                    // vertex rule: (1 - 6β) v + β Σ neighbours, β = 1/16 at valence 6
                    (0, 0) => std::iter::once(at([0, 0], 0.625)).chain(HEX_DIRS.iter().map(|&d| at(d, 0.0625))).collect(),
                    // edge rule: 3/8 on the edge's ends, 1/8 on the two opposite vertices
                    (1, 0) => vec![at([0, 0], 0.375), at([1, 0], 0.375), at([0, 1], 0.125), at([1, -1], 0.125)],
                    (0, 1) => vec![at([0, 0], 0.375), at([0, 1], 0.375), at([1, 0], 0.125), at([-1, 1], 0.125)],
                    _ => vec![at([1, 0], 0.375), at([0, 1], 0.375), at([0, 0], 0.125), at([1, 1], 0.125)],
                }
            }
            LatticeRules::Sqrt3 => sqrt3_two_steps(p),
        }
    }
}

/// One √3 step, in level-2 coordinates (coarse = 3×): a point of the
/// intermediate lattice `L1 = {x : x_0 ≡ x_1 mod 3}` from coarse points.
fn sqrt3_step1(x: [i64; 2]) -> Vec<([i64; 2], f64)> {
    let r = [x[0].rem_euclid(3), x[1].rem_euclid(3)];
    let c = [(x[0] - r[0]) / 3, (x[1] - r[1]) / 3];
    match r {
        // relaxed old vertex: (1 - α) v + α/6 Σ neighbours, α = (4 - 2cos(2π/6))/9 = 1/3
        [0, 0] => std::iter::once((c, 2.0 / 3.0)).chain(HEX_DIRS.iter().map(|&d| (add(c, d), 1.0 / 18.0))).collect(),
        // face centre of the upward triangle (c, c+e0, c+e1)
        [1, 1] => vec![(c, 1.0 / 3.0), (add(c, [1, 0]), 1.0 / 3.0), (add(c, [0, 1]), 1.0 / 3.0)],
        // face centre of the downward triangle (c+e0, c+e0+e1, c+e1)
        _ => vec![(add(c, [1, 0]), 1.0 / 3.0), (add(c, [1, 1]), 1.0 / 3.0), (add(c, [0, 1]), 1.0 / 3.0)],
    }
}

/// The second √3 step: any level-2 point from `L1` points, then expanded.
fn sqrt3_two_steps(p: [i64; 2]) -> Vec<([i64; 2], f64)> {
    const L1_DIRS: [[i64; 2]; 6] = [[1, 1], [-1, 2], [-2, 1], [-1, -1], [1, -2], [2, -1]];
    let mid: Vec<([i64; 2], f64)> = match (p[0] - p[1]).rem_euclid(3) {
        0 => std::iter::once((p, 2.0 / 3.0)).chain(L1_DIRS.iter().map(|&d| (add(p, d), 1.0 / 18.0))).collect(),
        2 => [[0, -1], [1, 0], [-1, 1]].iter().map(|&d| (add(p, d), 1.0 / 3.0)).collect(),
        _ => [[-1, 0], [1, -1], [0, 1]].iter().map(|&d| (add(p, d), 1.0 / 3.0)).collect(),
    };
    let mut acc: HashMap<[i64; 2], f64> = HashMap::new();
    for (x, w) in mid {
        for (c, v) in sqrt3_step1(x) {
            *acc.entry(c).or_insert(0.0) += w * v;
        }
    }
    let mut out: Vec<_> = acc.into_iter().collect();
    out.sort_by_key(|a| a.0);
    out
}

/// A surface patch on a lattice: control points at lattice points `control`
/// (same order as `points`), one map per fine offset `t_k` (block `k` = fine
/// points `t_k + q`), parameter maps `g_k(u) = (u + t_k) / m`, and a base
/// triangulation of the parameter domain (lattice coordinates).
pub fn lattice_ifs(
    rules: &LatticeRules,
    control: &[[i64; 2]],
    offsets: &[[i64; 2]],
    points: &[Vec<f64>],
    base_vertices: &[[f64; 2]],
    base_triangles: &[[usize; 3]],
    name: &str,
) -> Result<Ifs> {
    let n = control.len();
    if points.len() != n {
        return Err(invalid(format!("{name}: expected {n} control points, got {}", points.len())));
    }
    let index: HashMap<[i64; 2], usize> = control.iter().enumerate().map(|(i, &c)| (c, i)).collect();
    let mut blocks = Vec::new();
    for (k, &t) in offsets.iter().enumerate() {
        let mut s = Mat::zeros(n, n);
        for (j, &q) in control.iter().enumerate() {
            for (c, w) in rules.stencil(add(t, q)) {
                let Some(&col) = index.get(&c) else {
                    return Err(invalid(format!(
                        "{name}: block {k} needs coarse lattice point {c:?}, outside the control net (use a larger one)"
                    )));
                };
                s.data[j * n + col] += w;
            }
        }
        blocks.push(s);
    }
    let mut ifs = Ifs::from_subdivision(blocks, points, name)?;
    let m = rules.arity() as f64;
    let maps = offsets.iter().map(|t| ([[1.0, 0.0], [0.0, 1.0]], [t[0] as f64, t[1] as f64])).collect();
    let mut domain = Domain::Planar {
        maps,
        scale: m,
        vertices: base_vertices.to_vec(),
        triangles: base_triangles.to_vec(),
        lifted: Vec::new(),
    };
    let lifted = base_vertices.iter().map(|&u| super::render::point_at(&ifs, &domain, u)).collect();
    if let Domain::Planar { lifted: l, .. } = &mut domain {
        *l = lifted;
    }
    ifs.set_domain(domain);
    Ok(ifs)
}

fn hexagon_base() -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let mut v = vec![[0.0, 0.0]];
    v.extend(HEX_DIRS.iter().map(|d| [d[0] as f64, d[1] as f64]));
    let t = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
    (v, t)
}

fn hex_radius_for(n: usize, name: &str) -> Result<i64> {
    (1..64)
        .find(|&r| 1 + 3 * r * (r + 1) == n as i64)
        .ok_or_else(|| invalid(format!("{name}: {n} control points do not fill a hexagonal net (1 + 3r(r+1) points, ordered as hex_lattice(r))")))
}

/// Section 3.1: bicubic B-spline patch from a 4×4 control grid (row `j`,
/// column `i` at index `4j + i`); four maps over the square `[1, 2]²`.
pub fn bicubic_ifs(points: &[Vec<f64>]) -> Result<Ifs> {
    let control: Vec<[i64; 2]> = (0..4).flat_map(|j| (0..4).map(move |i| [i, j])).collect();
    let offsets = [[1, 1], [2, 1], [1, 2], [2, 2]];
    let verts = [[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]];
    lattice_ifs(
        &LatticeRules::Tensor(CurveRules::cubic_bspline()),
        &control,
        &offsets,
        points,
        &verts,
        &[[0, 1, 2], [0, 2, 3]],
        "bicubic",
    )
}

/// Section 3.2: the three-direction quartic box spline (Loop, regular case)
/// over a hexagon. Control points on `hex_lattice(2)` (19 points); six maps
/// `g_k(u) = (u + e_k)/2`, each scaling the hexagon by ½ towards a corner.
pub fn loop_hexagon_ifs(points: &[Vec<f64>]) -> Result<Ifs> {
    let r = hex_radius_for(points.len(), "loop")?;
    let control = hex_lattice(r);
    let offsets: Vec<[i64; 2]> = HEX_DIRS.iter().map(|d| [d[0] * (r - 1), d[1] * (r - 1)]).collect();
    let (v, t) = hexagon_base();
    let s = (r - 1) as f64;
    let v: Vec<[f64; 2]> = v.iter().map(|p| [p[0] * s, p[1] * s]).collect();
    lattice_ifs(&LatticeRules::Loop, &control, &offsets, points, &v, &t, "loop")
}

/// Section 3.3: Kobbelt's √3 over the unit hexagon, two steps per level (a
/// ternary split): 19 maps `g_t(u) = (u + t)/3` for the fine lattice points
/// `|t| ≤ 2`, whose images cover the hexagon. Needs control points on
/// `hex_lattice(4)` (61 points): the two-step stencils reach that far.
pub fn sqrt3_hexagon_ifs(points: &[Vec<f64>]) -> Result<Ifs> {
    let r = hex_radius_for(points.len(), "sqrt3")?;
    let control = hex_lattice(r);
    let offsets = hex_lattice(2);
    let (v, t) = hexagon_base();
    lattice_ifs(&LatticeRules::Sqrt3, &control, &offsets, points, &v, &t, "sqrt3")
}

/// Lattice sites and the positions at them.
pub type LatticeNet = (Vec<[i64; 2]>, Vec<Vec<f64>>);

/// Plain subdivision of a lattice net: fine points whose stencils stay
/// inside the current net, `levels` times. Returns fine lattice points and
/// their positions.
pub fn lattice_subdivide(
    rules: &LatticeRules,
    control: &[[i64; 2]],
    points: &[Vec<f64>],
    levels: usize,
) -> Result<LatticeNet> {
    if control.len() != points.len() {
        return Err(invalid("lattice subdivision: one point per lattice site"));
    }
    let m = rules.arity();
    // the bounding box of the sites grows w -> w·m + 2m + 1 per level; every
    // fine site is a lattice point in it: its coordinates, position (a Vec of
    // `dim` floats) and index-map entry, ~ 8·dim + 120 bytes
    let dim = points.first().map_or(0, |p| p.len()) as u64;
    let span = |i: usize| control.iter().map(|c| c[i]).max().unwrap_or(0) - control.iter().map(|c| c[i]).min().unwrap_or(0) + 1;
    let (mut w0, mut w1) = (span(0).max(1) as u64, span(1).max(1) as u64);
    let mu = m as u64;
    for k in 1..=levels as u64 {
        w0 = w0.saturating_mul(mu).saturating_add(2 * mu + 1);
        w1 = w1.saturating_mul(mu).saturating_add(2 * mu + 1);
        let need = w0.saturating_mul(w1).saturating_mul(2).saturating_mul(8 * dim + 120);
        crate::budget::check("subdivide_surface", &format!("level {k} of {levels}"), need)?;
    }
    let mut sites = control.to_vec();
    let mut pos = points.to_vec();
    for _ in 0..levels {
        crate::cancel::check()?;
        let index: HashMap<[i64; 2], usize> = sites.iter().enumerate().map(|(i, &c)| (c, i)).collect();
        let (lo0, hi0) = sites.iter().fold((i64::MAX, i64::MIN), |a, s| (a.0.min(s[0]), a.1.max(s[0])));
        let (lo1, hi1) = sites.iter().fold((i64::MAX, i64::MIN), |a, s| (a.0.min(s[1]), a.1.max(s[1])));
        let dim = pos[0].len();
        let (mut ns, mut np) = (Vec::new(), Vec::new());
        for b in lo1 * m - m..=hi1 * m + m {
            for a in lo0 * m - m..=hi0 * m + m {
                let st = rules.stencil([a, b]);
                if st.iter().all(|(c, _)| index.contains_key(c)) {
                    let mut x = vec![0.0; dim];
                    for (c, w) in st {
                        x.iter_mut().zip(&pos[index[&c]]).for_each(|(p, q)| *p += w * q);
                    }
                    ns.push([a, b]);
                    np.push(x);
                }
            }
        }
        if ns.is_empty() {
            break;
        }
        sites = ns;
        pos = np;
    }
    Ok((sites, pos))
}

/// Triangles of a set of lattice sites: `(c, c+e0, c+e1)` and
/// `(c+e0, c+e0+e1, c+e1)` when all three sites are present (triangular
/// lattice faces, or split quads of the square lattice), counter-clockwise.
pub fn lattice_triangles(sites: &[[i64; 2]]) -> Vec<[u32; 3]> {
    let index: HashMap<[i64; 2], u32> = sites.iter().enumerate().map(|(i, &c)| (c, i as u32)).collect();
    let mut out = Vec::new();
    for &c in sites {
        let (a, b, d) = (index.get(&add(c, [1, 0])), index.get(&add(c, [0, 1])), index.get(&add(c, [1, 1])));
        if let (Some(&a), Some(&b)) = (a, b) {
            out.push([index[&c], a, b]);
            if let Some(&d) = d {
                out.push([a, d, b]);
            }
        }
    }
    out
}

/// The lattice sites of a named surface scheme's control net with `n` points:
/// `"bicubic"` (4×4 grid, index `4j + i`), `"loop"` / `"sqrt3"` (`hex_lattice(r)`).
pub fn surface_control_sites(scheme: &str, n: usize) -> Result<(LatticeRules, Vec<[i64; 2]>)> {
    match scheme {
        "bicubic" => {
            if n != 16 {
                return Err(invalid(format!("bicubic: expected 16 control points (a 4x4 grid), got {n}")));
            }
            Ok((LatticeRules::Tensor(CurveRules::cubic_bspline()), (0..4).flat_map(|j| (0..4).map(move |i| [i, j])).collect()))
        }
        "loop" => Ok((LatticeRules::Loop, hex_lattice(hex_radius_for(n, "loop")?))),
        "sqrt3" => Ok((LatticeRules::Sqrt3, hex_lattice(hex_radius_for(n, "sqrt3")?))),
        _ => Err(invalid(format!("unknown surface scheme {scheme:?} (expected 'bicubic', 'loop' or 'sqrt3')"))),
    }
}

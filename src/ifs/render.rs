//! Rendering an attractor: deterministic iteration `X_{k+1} = F(X_k)` from
//! any compact start set, the chaos game, ordered polylines of curves and
//! triangle meshes of surface patches.
//!
//! All work happens in reduced coordinates (the lifted ones without the
//! homogeneous entries), where each map is `y ↦ y A_i + b_i`. Output points
//! carry the drawn coordinates of every component, `c·D` numbers per point.

use super::{invalid, Domain, Ifs};
use crate::Result;
use std::collections::{HashMap, HashSet};

/// Largest number of points (or triangles) one call may produce.
pub const MAX_OUTPUT: usize = 100_000_000;

/// Largest number of levels of deterministic iteration or meshing.
pub const MAX_LEVELS: usize = 64;

/// xoshiro256++ seeded by splitmix64: small, fast and reproducible.
#[derive(Clone, Debug)]
pub struct Rng {
    s: [u64; 4],
}

impl Rng {
    pub fn new(seed: u64) -> Rng {
        let mut x = seed;
        let mut sm = || {
            x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = x;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        };
        Rng { s: [sm(), sm(), sm(), sm()] }
    }

    #[inline(always)]
    pub fn next_u64(&mut self) -> u64 {
        let s = &mut self.s;
        let result = s[0].wrapping_add(s[3]).rotate_left(23).wrapping_add(s[0]);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        result
    }
}

/// How the chaos game picks a map.
enum Picker {
    Uniform(u64),
    /// Cumulative thresholds on the full `u64` range.
    Weighted(Vec<u64>),
}

impl Picker {
    #[inline(always)]
    fn pick(&self, rng: &mut Rng) -> usize {
        let r = rng.next_u64();
        match self {
            Picker::Uniform(k) => (((r >> 32) * k) >> 32) as usize,
            Picker::Weighted(th) => th.iter().position(|&t| r < t).unwrap_or(th.len() - 1),
        }
    }
}

fn chaos_fixed<const D: usize>(ifs: &Ifs, start: &[f64], rng: &mut Rng, picker: &Picker, draw: &[usize], out: &mut [f64]) {
    let lin: Vec<[[f64; D]; D]> = ifs
        .lin
        .iter()
        .map(|a| std::array::from_fn(|r| std::array::from_fn(|c| a[r * D + c])))
        .collect();
    let trans: Vec<[f64; D]> = ifs.trans.iter().map(|b| std::array::from_fn(|c| b[c])).collect();
    let mut y: [f64; D] = std::array::from_fn(|c| start[c]);
    for chunk in out.chunks_exact_mut(draw.len()) {
        let i = picker.pick(rng);
        let a = &lin[i];
        let mut z = trans[i];
        for r in 0..D {
            let yr = y[r];
            for c in 0..D {
                z[c] += yr * a[r][c];
            }
        }
        y = z;
        for (o, &c) in chunk.iter_mut().zip(draw) {
            *o = y[c];
        }
    }
}

fn chaos_dyn(ifs: &Ifs, start: &[f64], rng: &mut Rng, picker: &Picker, draw: &[usize], out: &mut [f64]) {
    let mut y = start.to_vec();
    let mut z = vec![0.0; y.len()];
    for chunk in out.chunks_exact_mut(draw.len()) {
        let i = picker.pick(rng);
        ifs.apply_reduced(i, &y, &mut z);
        std::mem::swap(&mut y, &mut z);
        for (o, &c) in chunk.iter_mut().zip(draw) {
            *o = y[c];
        }
    }
}

/// The attractor point at parameter `u` of a planar domain: follow an
/// address `u ∈ g_{i1}(D)`, `g_{i1}⁻¹(u) ∈ g_{i2}(D)`, … and compose
/// `f_{i1} ∘ f_{i2} ∘ …` until the contraction is below round-off.
pub(crate) fn point_at(ifs: &Ifs, domain: &Domain, u: [f64; 2]) -> Vec<f64> {
    let Domain::Planar { maps, scale, vertices, triangles, .. } = domain else {
        panic!("point_at needs a planar domain");
    };
    let outside = |v: [f64; 2]| -> f64 {
        triangles
            .iter()
            .map(|t| {
                let (a, b, c) = (vertices[t[0]], vertices[t[1]], vertices[t[2]]);
                let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
                let l1 = ((v[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (v[1] - a[1])) / det;
                let l2 = ((b[0] - a[0]) * (v[1] - a[1]) - (v[0] - a[0]) * (b[1] - a[1])) / det;
                let l0 = 1.0 - l1 - l2;
                (-l0).max(-l1).max(-l2).max(0.0)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let inv: Vec<([[f64; 2]; 2], [f64; 2])> = maps
        .iter()
        .map(|(l, t)| {
            let det = l[0][0] * l[1][1] - l[0][1] * l[1][0];
            ([[l[1][1] / det, -l[0][1] / det], [-l[1][0] / det, l[0][0] / det]], *t)
        })
        .collect();
    let rho = ifs.radius.iter().fold(0.0f64, |a, &b| a.max(b)).max(1e-3);
    let steps = ((-40.0 / rho.ln()).ceil() as usize).clamp(20, 400);
    let mut address = Vec::with_capacity(steps);
    let mut cur = u;
    for _ in 0..steps {
        let (best, next) = inv
            .iter()
            .enumerate()
            .map(|(i, (li, t))| {
                let w = [scale * cur[0] - t[0], scale * cur[1] - t[1]];
                (i, [li[0][0] * w[0] + li[0][1] * w[1], li[1][0] * w[0] + li[1][1] * w[1]])
            })
            .min_by(|a, b| outside(a.1).partial_cmp(&outside(b.1)).unwrap())
            .expect("at least one map");
        address.push(best);
        cur = next;
    }
    let d = ifs.reduced_dim();
    let mut y = vec![0.0; d];
    let mut z = vec![0.0; d];
    for &i in address.iter().rev() {
        ifs.apply_reduced(i, &y, &mut z);
        std::mem::swap(&mut y, &mut z);
    }
    ifs.unreduce(&y)
}

impl Ifs {
    /// Start points given by their first lifted coordinates (`k ≤ n` columns;
    /// missing coordinates are 0, homogeneous ones are set to 1) → reduced, flat.
    pub fn start_points(&self, rows: &[Vec<f64>]) -> Result<Vec<f64>> {
        let mut flat = Vec::with_capacity(rows.len() * self.reduced_dim());
        for (i, r) in rows.iter().enumerate() {
            if r.len() > self.n {
                return Err(invalid(format!("start point {i} has {} coordinates, the IFS lives in {}", r.len(), self.n)));
            }
            if r.iter().any(|x| !x.is_finite()) {
                return Err(invalid(format!("start point {i} has a NaN or infinite coordinate")));
            }
            let mut x = r.clone();
            x.resize(self.n, 0.0);
            flat.extend(self.reduce(&x));
        }
        Ok(flat)
    }

    /// The drawn coordinates (`c·D` per point) of reduced points.
    pub fn draw(&self, reduced: &[f64]) -> Vec<f64> {
        let idx: Vec<usize> = self.drawn().concat();
        let d = self.reduced_dim();
        reduced.chunks_exact(d).flat_map(|y| idx.iter().map(move |&c| y[c])).collect()
    }

    /// `levels` rounds of `X ↦ ∪_i f_i(X)` on reduced points: point
    /// `i·|X| + j` of the next level is `f_i(X_j)`, so the outermost map is
    /// the most significant digit of the index (curves come out in order).
    pub fn iterate_reduced(&self, start: &[f64], levels: usize) -> Result<Vec<f64>> {
        if levels > MAX_LEVELS {
            return Err(invalid(format!("{levels} levels exceed the limit {MAX_LEVELS}")));
        }
        let d = self.reduced_dim();
        let count = start.len() / d.max(1);
        let k = self.maps.len();
        let total = (k as f64).powi(levels as i32) * count as f64;
        if total > MAX_OUTPUT as f64 {
            return Err(invalid(format!("{levels} levels of {k} maps would give {total:.3e} points (limit {MAX_OUTPUT})")));
        }
        // the last level and the one before it, plus the drawn copy
        crate::budget::check("iterate", &format!("{levels} levels"), (total * (d.max(1) * 8 * 3) as f64) as u64)?;
        let mut cur = start.to_vec();
        let mut z = vec![0.0; d];
        for _ in 0..levels {
            crate::cancel::check()?;
            let mut next = Vec::with_capacity(cur.len() * k);
            for i in 0..k {
                for y in cur.chunks_exact(d) {
                    self.apply_reduced(i, y, &mut z);
                    next.extend_from_slice(&z);
                }
            }
            cur = next;
        }
        Ok(cur)
    }

    /// Deterministic iteration from start points (see [`Ifs::start_points`]):
    /// `k^levels · m` points, image `w` of start point `j` at `w·m + j`.
    pub fn iterate(&self, start: &[Vec<f64>], levels: usize) -> Result<Vec<f64>> {
        if start.is_empty() {
            return Err(invalid("iterate: the start set is empty"));
        }
        let s = self.start_points(start)?;
        Ok(self.draw(&self.iterate_reduced(&s, levels)?))
    }

    /// Plain subdivision through the IFS: `F^levels(P)` from the control
    /// points, i.e. every block `S_{w} P` (`n` points each) in word order.
    pub fn subdivide(&self, levels: usize) -> Result<Vec<f64>> {
        let p = self.control.as_ref().ok_or_else(|| invalid("subdivide: this IFS has no control points"))?;
        let rows: Vec<Vec<f64>> = (0..p.rows).map(|r| p.row(r).to_vec()).collect();
        self.iterate(&rows, levels)
    }

    /// The chaos game: `n_points` points of the attractor, starting at the
    /// fixed point of map 0 (already on the attractor, no burn-in needed).
    /// `probabilities` (one per map, summing to 1) default to uniform.
    pub fn chaos_game(&self, n_points: usize, seed: u64, probabilities: Option<&[f64]>) -> Result<Vec<f64>> {
        if n_points > MAX_OUTPUT {
            return Err(invalid(format!("chaos game: {n_points} points exceed the limit {MAX_OUTPUT}")));
        }
        let k = self.maps.len();
        let picker = match probabilities {
            None => Picker::Uniform(k as u64),
            Some(p) => {
                if p.len() != k || p.iter().any(|&x| !(x >= 0.0) || !x.is_finite()) {
                    return Err(invalid(format!("chaos game: expected {k} non-negative probabilities")));
                }
                let total: f64 = p.iter().sum();
                if !(total > 0.0) {
                    return Err(invalid("chaos game: probabilities sum to 0"));
                }
                let mut acc = 0.0;
                let th = p
                    .iter()
                    .map(|&x| {
                        acc += x / total;
                        if acc >= 1.0 { u64::MAX } else { (acc * 18446744073709551616.0) as u64 }
                    })
                    .collect();
                Picker::Weighted(th)
            }
        };
        let draw: Vec<usize> = self.drawn().concat();
        let start = self.reduce(&self.fixed_point(0));
        let mut out = vec![0.0; n_points * draw.len()];
        let mut rng = Rng::new(seed);
        macro_rules! go {
            ($($d:literal)*) => {
                match self.reduced_dim() {
                    $($d => chaos_fixed::<$d>(self, &start, &mut rng, &picker, &draw, &mut out),)*
                    _ => chaos_dyn(self, &start, &mut rng, &picker, &draw, &mut out),
                }
            };
        }
        go!(1 2 3 4 5 6 7 8 9 10 11 12);
        Ok(out)
    }

    /// An ordered polyline on a curve attractor: `k^levels + 1` points, the
    /// images of the curve's start under all words in order, then its end.
    /// Every vertex lies on the attractor.
    pub fn polyline(&self, levels: usize) -> Result<Vec<f64>> {
        if self.domain != Some(Domain::Interval) {
            return Err(invalid(format!("polyline: {} is not an ordered curve IFS", self.name)));
        }
        let first = self.reduce(&self.fixed_point(0));
        let last = self.reduce(&self.fixed_point(self.maps.len() - 1));
        let mut pts = self.iterate_reduced(&first, levels)?;
        pts.extend(last);
        Ok(self.draw(&pts))
    }

    /// A triangle mesh of a surface patch at `levels`: the images of the base
    /// triangulation of the parameter domain under all words, vertices merged
    /// by parameter value (duplicate triangles of overlapping maps dropped).
    /// Every vertex lies on the attractor. Returns drawn vertex coordinates and
    /// triangles.
    pub fn mesh(&self, levels: usize) -> Result<(Vec<f64>, Vec<[u32; 3]>)> {
        let Some(Domain::Planar { maps, scale, vertices, triangles, lifted }) = &self.domain else {
            return Err(invalid(format!("mesh: {} has no planar parameter domain", self.name)));
        };
        if self.components.len() != 1 {
            return Err(invalid("mesh: only single-component IFSs"));
        }
        if levels > MAX_LEVELS {
            return Err(invalid(format!("{levels} levels exceed the limit {MAX_LEVELS}")));
        }
        let est = (maps.len() as f64).powi(levels as i32) * triangles.len() as f64;
        if est > MAX_OUTPUT as f64 {
            return Err(invalid(format!("mesh: {levels} levels would give up to {est:.3e} triangles")));
        }
        let d = self.reduced_dim();
        // per triangle: its indices, hash-set entry and up to three vertices' data
        crate::budget::check("mesh", &format!("{levels} levels"), (est * (64 + 24 * d) as f64) as u64)?;
        let mut us: Vec<[f64; 2]> = vertices.clone();
        let mut ys: Vec<f64> = lifted.iter().flat_map(|x| self.reduce(x)).collect();
        let mut tris: Vec<[u32; 3]> = triangles.iter().map(|t| [t[0] as u32, t[1] as u32, t[2] as u32]).collect();
        let mut factor = 6.0;
        let mut z = vec![0.0; d];
        for _ in 0..levels {
            crate::cancel::check()?;
            factor *= scale;
            let mut keys: HashMap<(i64, i64), u32> = HashMap::new();
            let (mut nu, mut ny, mut nt) = (Vec::new(), Vec::new(), Vec::new());
            let mut seen: HashSet<[u32; 3]> = HashSet::new();
            for (i, (l, t)) in maps.iter().enumerate() {
                let mut remap = Vec::with_capacity(us.len());
                for (v, u) in us.iter().enumerate() {
                    let g = [
                        (l[0][0] * u[0] + l[0][1] * u[1] + t[0]) / scale,
                        (l[1][0] * u[0] + l[1][1] * u[1] + t[1]) / scale,
                    ];
                    let key = ((g[0] * factor).round() as i64, (g[1] * factor).round() as i64);
                    let id = *keys.entry(key).or_insert_with(|| {
                        self.apply_reduced(i, &ys[v * d..(v + 1) * d], &mut z);
                        ny.extend_from_slice(&z);
                        nu.push(g);
                        (nu.len() - 1) as u32
                    });
                    remap.push(id);
                }
                for tr in &tris {
                    let m = [remap[tr[0] as usize], remap[tr[1] as usize], remap[tr[2] as usize]];
                    let mut key = m;
                    key.sort_unstable();
                    if m[0] != m[1] && m[1] != m[2] && m[0] != m[2] && seen.insert(key) {
                        nt.push(m);
                    }
                }
            }
            us = nu;
            ys = ny;
            tris = nt;
        }
        Ok((self.draw(&ys), tris))
    }
}

/// Hausdorff distance between two point sets of dimension `dim` (brute force
/// on a uniform grid of cells; for tests and small sets).
pub fn hausdorff(a: &[f64], b: &[f64], dim: usize) -> f64 {
    fn one_sided(a: &[f64], b: &[f64], dim: usize) -> f64 {
        // bucket b in a grid sized by its bounding box
        let nb = b.len() / dim;
        let (mut lo, mut hi) = (vec![f64::INFINITY; dim], vec![f64::NEG_INFINITY; dim]);
        for p in b.chunks_exact(dim) {
            for c in 0..dim {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        let ext = (0..dim).map(|c| hi[c] - lo[c]).fold(0.0f64, f64::max).max(1e-12);
        let cell = ext / (nb as f64).powf(1.0 / dim as f64).max(1.0);
        let key = |p: &[f64]| -> Vec<i64> { (0..dim).map(|c| ((p[c] - lo[c]) / cell).floor() as i64).collect() };
        let mut grid: HashMap<Vec<i64>, Vec<usize>> = HashMap::new();
        for (i, p) in b.chunks_exact(dim).enumerate() {
            grid.entry(key(p)).or_default().push(i);
        }
        let mut worst = 0.0f64;
        for p in a.chunks_exact(dim) {
            let k = key(p);
            let mut best = f64::INFINITY;
            let mut r = 0i64;
            loop {
                // search shells of cells until the best is provably found
                let mut visit = |cellk: &Vec<i64>| {
                    if let Some(ids) = grid.get(cellk) {
                        for &i in ids {
                            let q = &b[i * dim..(i + 1) * dim];
                            best = best.min(p.iter().zip(q).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt());
                        }
                    }
                };
                let mut off = vec![-r; dim];
                loop {
                    if off.iter().any(|&o| o.abs() == r) {
                        let ck: Vec<i64> = k.iter().zip(&off).map(|(a, b)| a + b).collect();
                        visit(&ck);
                    }
                    let mut c = 0;
                    while c < dim {
                        off[c] += 1;
                        if off[c] > r {
                            off[c] = -r;
                            c += 1;
                        } else {
                            break;
                        }
                    }
                    if c == dim {
                        break;
                    }
                }
                if best <= r as f64 * cell || r > 4 * (nb as i64 + 2) {
                    break;
                }
                r += 1;
            }
            worst = worst.max(best);
        }
        worst
    }
    one_sided(a, b, dim).max(one_sided(b, a, dim))
}

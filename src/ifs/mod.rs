//! Subdivision curves and surfaces as attractors of iterated function systems.
//!
//! Schaefer, Levin, Goldman, *Subdivision Schemes and Attractors* (SGP 2005).
//! A stationary subdivision scheme with control points `P` (one point per row)
//! and square subdivision blocks `S_1..S_k` defines the IFS (eq. 2)
//!
//! ```text
//! f_i(X) = X P⁻¹ S_i P,
//! ```
//!
//! acting on row vectors in a lifted space: `P` is made square and invertible
//! exactly as in section 2 — identity columns are appended to the coordinates
//! (rows `0..n-1-D` get the unit vectors), then a homogeneous column of ones.
//! Its attractor, projected to the first `D` coordinates, is the subdivision
//! limit `p^∞`, whatever compact set the iteration starts from.
//!
//! * [`Ifs::from_subdivision`] builds the IFS from blocks and control points,
//!   checks that `P` is an affine basis and that every map is contractive
//!   (spectral radius of its linear part below one, section 2).
//! * [`rules`] derives the blocks from a scheme's rules — stencils per residue
//!   class on a lattice and a self-similar choice of sub-configurations — for
//!   the uniform cubic B-spline (eq. 4), Chaikin, the four-point scheme
//!   (section 2.3), B-splines with self-similar knots by blossoming (the
//!   end-point interpolating cubic, Bézier curves; sections 2.1–2.2), the
//!   bicubic tensor product (3.1), the three-direction quartic box spline /
//!   Loop (3.2, six maps on a hexagon) and Kobbelt's √3 (3.3).
//! * [`fractals`] goes the other way (section 4, eq. 5): affine maps plus chosen
//!   control points give subdivision rules; the Koch curve and the Sierpinski
//!   gasket with the paper's rules.
//! * [`render`]: deterministic iteration `X_{k+1} = F(X_k)`, the chaos game,
//!   ordered polylines for curves and triangle meshes for surface patches.
//!
//! Unions (section 2.2) are block-diagonal: [`Ifs::union`] keeps one
//! homogeneous coordinate per component and renders each component.

pub mod fractals;
pub mod linalg;
pub mod render;
pub mod rules;

use crate::{MeshError, Result};
pub use linalg::Mat;

fn invalid(msg: impl Into<String>) -> MeshError {
    MeshError::InvalidArgument(msg.into())
}

/// One rendered piece of the attractor: which lifted coordinates are drawn
/// and which one is its homogeneous coordinate (always 1).
#[derive(Clone, Debug, PartialEq)]
pub struct Component {
    pub coords: Vec<usize>,
    pub homogeneous: usize,
}

/// The parameter domain of a curve or surface IFS, used to order output.
#[derive(Clone, Debug, PartialEq)]
pub enum Domain {
    /// A curve over `[0, 1]`; map `i` covers `[i/k, (i+1)/k]` in order, so the
    /// words in lexicographic order run along the curve. Its ends are the
    /// fixed points of the first and the last map.
    Interval,
    /// A surface patch over a planar domain. Map `i` acts on parameters by
    /// `g_i(u) = (L_i u + t_i) / scale`; `lifted` holds the attractor point of
    /// each base vertex, so level-`k` meshes are images of the base triangles.
    Planar {
        maps: Vec<([[f64; 2]; 2], [f64; 2])>,
        scale: f64,
        vertices: Vec<[f64; 2]>,
        triangles: Vec<[usize; 3]>,
        lifted: Vec<Vec<f64>>,
    },
}

/// An IFS of affine maps in lifted homogeneous coordinates (row vectors,
/// `x ↦ x M_i`), with the data needed to render it.
#[derive(Clone, Debug)]
pub struct Ifs {
    /// Lifted dimension `n` (the maps are `n × n`).
    n: usize,
    maps: Vec<Mat>,
    components: Vec<Component>,
    /// Lifted → reduced (non-homogeneous) coordinate index.
    reduced: Vec<Option<usize>>,
    /// Reduced affine form of each map: `y ↦ y A_i + b_i`, `A_i` row-major `d × d`.
    lin: Vec<Vec<f64>>,
    trans: Vec<Vec<f64>>,
    radius: Vec<f64>,
    /// Lifted control points (the rows of `P`), when built from subdivision.
    control: Option<Mat>,
    /// The subdivision blocks `S_i`, when built from subdivision.
    blocks: Option<Vec<Mat>>,
    domain: Option<Domain>,
    name: String,
}

/// Lifts `n` control points of dimension `D` to the square matrix of
/// section 2: `[X | E | 1]` with `E` the first `n-1-D` columns of the
/// identity. When that matrix is singular although the points span `R^D`
/// (the last `D+1` points are affinely dependent), the unit vectors are put on
/// other rows instead, keeping `D+1` affinely independent points free.
pub fn lift_control_points(points: &[Vec<f64>]) -> Result<Mat> {
    let n = points.len();
    let dim = points.first().map_or(0, |p| p.len());
    if dim == 0 || points.iter().any(|p| p.len() != dim) {
        return Err(invalid("control points: expected an (n, D) array with D >= 1"));
    }
    if points.iter().flatten().any(|x| !x.is_finite()) {
        return Err(invalid("control points: NaN or infinite coordinate"));
    }
    if n < dim + 1 {
        return Err(invalid(format!(
            "control points: {n} points in R^{dim} cannot form an affine basis (need at least {})",
            dim + 1
        )));
    }
    let build = |free: &[usize]| -> Mat {
        let mut p = Mat::zeros(n, n);
        let mut e = dim;
        for (r, pt) in points.iter().enumerate() {
            for (c, &x) in pt.iter().enumerate() {
                p.set(r, c, x);
            }
            if !free.contains(&r) {
                p.set(r, e, 1.0);
                e += 1;
            }
            p.set(r, n - 1, 1.0);
        }
        p
    };
    // the paper's layout: unit vectors on the first rows
    let paper: Vec<usize> = (n - 1 - dim..n).collect();
    let p = build(&paper);
    if p.inverse().is_some() {
        return Ok(p);
    }
    // otherwise keep a greedy affinely independent set of D+1 points free
    let scale = points.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    let mut free = vec![0usize];
    let mut basis: Vec<Vec<f64>> = Vec::new(); // orthonormalized differences
    for (r, pt) in points.iter().enumerate().skip(1) {
        if free.len() == dim + 1 {
            break;
        }
        let mut v: Vec<f64> = pt.iter().zip(&points[0]).map(|(a, b)| a - b).collect();
        for b in &basis {
            let d: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
            v.iter_mut().zip(b).for_each(|(x, y)| *x -= d * y);
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 1e-9 * scale {
            v.iter_mut().for_each(|x| *x /= norm);
            basis.push(v);
            free.push(r);
        }
    }
    if free.len() < dim + 1 {
        return Err(invalid(format!(
            "control points are not an affine basis: all {n} points lie in a {}-dimensional affine subspace of R^{dim}",
            free.len() - 1
        )));
    }
    let p = build(&free);
    if p.inverse().is_none() {
        return Err(invalid("control points: lifted matrix P is numerically singular"));
    }
    Ok(p)
}

impl Ifs {
    /// The general constructor: lifted `n × n` maps (`x ↦ x M_i`) and the
    /// components to draw. Checks that every homogeneous coordinate is kept
    /// at 1 and that every map is contractive.
    pub fn from_lifted_maps(maps: Vec<Mat>, components: Vec<Component>, name: &str) -> Result<Ifs> {
        if maps.is_empty() {
            return Err(invalid("an IFS needs at least one map"));
        }
        let n = maps[0].rows;
        for (i, m) in maps.iter().enumerate() {
            if m.rows != n || m.cols != n {
                return Err(invalid(format!("map {i} is {}x{}, expected {n}x{n}", m.rows, m.cols)));
            }
            if m.data.iter().any(|x| !x.is_finite()) {
                return Err(invalid(format!("map {i} has a NaN or infinite entry")));
            }
        }
        if components.is_empty() {
            return Err(invalid("an IFS needs at least one component"));
        }
        let mut is_h = vec![false; n];
        for c in &components {
            if c.homogeneous >= n || c.coords.iter().any(|&x| x >= n) {
                return Err(invalid("component coordinate out of range"));
            }
            is_h[c.homogeneous] = true;
        }
        if components.iter().any(|c| c.coords.iter().any(|&x| is_h[x])) {
            return Err(invalid("a drawn coordinate cannot be homogeneous"));
        }
        let mut reduced = vec![None; n];
        let mut d = 0;
        for j in 0..n {
            if !is_h[j] {
                reduced[j] = Some(d);
                d += 1;
            }
        }
        let mut lin = Vec::with_capacity(maps.len());
        let mut trans = Vec::with_capacity(maps.len());
        let mut radius = Vec::with_capacity(maps.len());
        for (i, m) in maps.iter().enumerate() {
            let tol = 1e-9 * m.max_abs().max(1.0);
            // homogeneous columns must be unit columns: x_h stays 1
            for h in (0..n).filter(|&h| is_h[h]) {
                for r in 0..n {
                    let want = if r == h { 1.0 } else { 0.0 };
                    if (m.at(r, h) - want).abs() > tol {
                        return Err(invalid(format!(
                            "map {i} does not keep homogeneous coordinate {h} equal to 1 \
                             (entry ({r}, {h}) = {}); subdivision rules must be affine: every row of S_i sums to 1",
                            m.at(r, h)
                        )));
                    }
                }
            }
            let mut a = Mat::zeros(d, d);
            let mut b = vec![0.0; d];
            for r in 0..n {
                for c in 0..n {
                    let Some(cc) = reduced[c] else { continue };
                    match reduced[r] {
                        Some(rr) => a.set(rr, cc, m.at(r, c)),
                        None => b[cc] += m.at(r, c),
                    }
                }
            }
            let rho = linalg::spectral_radius(&a);
            if !(rho < 1.0 - 1e-9) {
                return Err(invalid(format!(
                    "map {i} is not contractive: the spectral radius of its linear part is {rho:.6} >= 1"
                )));
            }
            radius.push(rho);
            lin.push(a.data);
            trans.push(b);
        }
        Ok(Ifs {
            n,
            maps,
            components,
            reduced,
            lin,
            trans,
            radius,
            control: None,
            blocks: None,
            domain: None,
            name: name.to_string(),
        })
    }

    /// Eq. 2: `f_i(X) = X P⁻¹ S_i P` from square subdivision blocks `S_i`
    /// (`n × n`, rows summing to 1) and `n` control points in `R^D`.
    ///
    /// Errors when the blocks are not square of size `n`, a row does not sum
    /// to 1, the control points are not an affine basis, or a map is not
    /// contractive.
    pub fn from_subdivision(blocks: Vec<Mat>, points: &[Vec<f64>], name: &str) -> Result<Ifs> {
        let n = points.len();
        for (i, s) in blocks.iter().enumerate() {
            if s.rows != n || s.cols != n {
                return Err(invalid(format!(
                    "subdivision block {i} is {}x{}, expected {n}x{n} for {n} control points",
                    s.rows, s.cols
                )));
            }
            for r in 0..n {
                let sum: f64 = s.row(r).iter().sum();
                if (sum - 1.0).abs() > 1e-9 {
                    return Err(invalid(format!(
                        "subdivision block {i}, row {r} sums to {sum}, not 1 (rules must be affine combinations)"
                    )));
                }
            }
        }
        let p = lift_control_points(points)?;
        let pinv = p.inverse().expect("lift_control_points returns an invertible matrix");
        let maps = blocks.iter().map(|s| pinv.mul(s).mul(&p)).collect();
        let dim = points[0].len();
        let comp = Component { coords: (0..dim).collect(), homogeneous: n - 1 };
        let mut ifs = Ifs::from_lifted_maps(maps, vec![comp], name)?;
        ifs.control = Some(p);
        ifs.blocks = Some(blocks);
        Ok(ifs)
    }

    /// The classical IFS of affine maps `x ↦ A_i x + t_i` of `R^D` (column
    /// vectors, as usually written), lifted to `D+1` homogeneous coordinates.
    pub fn from_affine(maps: &[(Vec<Vec<f64>>, Vec<f64>)], name: &str) -> Result<Ifs> {
        let dim = maps.first().map_or(0, |m| m.1.len());
        if dim == 0 {
            return Err(invalid("affine maps: expected at least one map of dimension >= 1"));
        }
        let mut lifted = Vec::new();
        for (i, (a, t)) in maps.iter().enumerate() {
            if t.len() != dim || a.len() != dim || a.iter().any(|r| r.len() != dim) {
                return Err(invalid(format!("affine map {i}: expected a {dim}x{dim} matrix and a length-{dim} vector")));
            }
            let mut m = Mat::zeros(dim + 1, dim + 1);
            for r in 0..dim {
                for c in 0..dim {
                    m.set(c, r, a[r][c]); // row-vector convention: M = Aᵀ
                }
                m.set(dim, r, t[r]);
            }
            m.set(dim, dim, 1.0);
            lifted.push(m);
        }
        Ifs::from_lifted_maps(lifted, vec![Component { coords: (0..dim).collect(), homogeneous: dim }], name)
    }

    /// Section 2.2: the IFS whose attractor is the union of both attractors,
    /// with block-diagonal maps `diag(M_i, N_i)` and one homogeneous
    /// coordinate per part. Both IFSs need the same number of maps.
    pub fn union(&self, other: &Ifs) -> Result<Ifs> {
        if self.maps.len() != other.maps.len() {
            return Err(invalid(format!(
                "union: both IFSs need the same number of maps ({} vs {})",
                self.maps.len(),
                other.maps.len()
            )));
        }
        let maps = self.maps.iter().zip(&other.maps).map(|(a, b)| a.block_diag(b)).collect();
        let mut comps = self.components.clone();
        comps.extend(other.components.iter().map(|c| Component {
            coords: c.coords.iter().map(|x| x + self.n).collect(),
            homogeneous: c.homogeneous + self.n,
        }));
        let mut u = Ifs::from_lifted_maps(maps, comps, &format!("{} ∪ {}", self.name, other.name))?;
        if self.domain == Some(Domain::Interval) && other.domain == Some(Domain::Interval) {
            u.domain = Some(Domain::Interval);
        }
        // paired control points [P | Q]: iterating them subdivides both at once
        if let (Some(p), Some(q)) = (&self.control, &other.control) {
            if p.rows == q.rows {
                let mut c = Mat::zeros(p.rows, p.cols + q.cols);
                for r in 0..p.rows {
                    c.data[r * c.cols..r * c.cols + p.cols].copy_from_slice(p.row(r));
                    c.data[r * c.cols + p.cols..(r + 1) * c.cols].copy_from_slice(q.row(r));
                }
                u.control = Some(c);
            }
        }
        Ok(u)
    }

    /// The IFS made of the maps listed in `keep` (Fig. 9): its attractor is a
    /// subset of this one's. A planar domain is kept, so meshes of the subset
    /// still lie on the original surface.
    pub fn subset(&self, keep: &[usize]) -> Result<Ifs> {
        if keep.is_empty() {
            return Err(invalid("subset: keep at least one map"));
        }
        if let Some(&bad) = keep.iter().find(|&&i| i >= self.maps.len()) {
            return Err(invalid(format!("subset: map {bad} out of range (IFS has {} maps)", self.maps.len())));
        }
        let mut s = self.clone();
        s.maps = keep.iter().map(|&i| self.maps[i].clone()).collect();
        s.lin = keep.iter().map(|&i| self.lin[i].clone()).collect();
        s.trans = keep.iter().map(|&i| self.trans[i].clone()).collect();
        s.radius = keep.iter().map(|&i| self.radius[i]).collect();
        s.blocks = self.blocks.as_ref().map(|b| keep.iter().map(|&i| b[i].clone()).collect());
        s.domain = match &self.domain {
            Some(Domain::Planar { maps, scale, vertices, triangles, lifted }) => Some(Domain::Planar {
                maps: keep.iter().map(|&i| maps[i]).collect(),
                scale: *scale,
                vertices: vertices.clone(),
                triangles: triangles.clone(),
                lifted: lifted.clone(),
            }),
            _ => None, // a subset of a curve is not ordered along [0, 1] any more
        };
        s.name = format!("{} (maps {:?})", self.name, keep);
        Ok(s)
    }

    pub fn name(&self) -> &str {
        &self.name
    }
    /// Number of maps.
    pub fn n_maps(&self) -> usize {
        self.maps.len()
    }
    /// Lifted dimension `n`.
    pub fn dim(&self) -> usize {
        self.n
    }
    /// Dimension of each drawn component (2 or 3 in practice).
    pub fn ambient_dim(&self) -> usize {
        self.components[0].coords.len()
    }
    pub fn components(&self) -> &[Component] {
        &self.components
    }
    /// The lifted maps `M_i = P⁻¹ S_i P` (row-vector convention).
    pub fn maps(&self) -> &[Mat] {
        &self.maps
    }
    /// The subdivision blocks `S_i`, if built from a scheme.
    pub fn blocks(&self) -> Option<&[Mat]> {
        self.blocks.as_deref()
    }
    /// The lifted control-point matrix `P`, if built from a scheme (for a
    /// union of two IFSs with equally many control points, the rows `[P | Q]`).
    pub fn control(&self) -> Option<&Mat> {
        self.control.as_ref()
    }
    /// Spectral radius of each map's linear part (all below 1).
    pub fn contraction(&self) -> &[f64] {
        &self.radius
    }
    pub fn domain(&self) -> Option<&Domain> {
        self.domain.as_ref()
    }

    pub(crate) fn set_domain(&mut self, d: Domain) {
        self.domain = Some(d);
    }

    /// Reduced dimension `d` (lifted minus homogeneous coordinates).
    pub(crate) fn reduced_dim(&self) -> usize {
        self.lin.first().map_or(0, |a| (a.len() as f64).sqrt() as usize)
    }

    /// Applies map `i` to a reduced point.
    #[inline]
    pub(crate) fn apply_reduced(&self, i: usize, y: &[f64], out: &mut [f64]) {
        let d = y.len();
        out.copy_from_slice(&self.trans[i]);
        let a = &self.lin[i];
        for r in 0..d {
            let yr = y[r];
            let row = &a[r * d..(r + 1) * d];
            for (o, &x) in out.iter_mut().zip(row) {
                *o += yr * x;
            }
        }
    }

    /// Reduced coordinates of a lifted point (homogeneous entries dropped).
    pub(crate) fn reduce(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.reduced_dim()];
        for (j, &v) in x.iter().enumerate() {
            if let Some(r) = self.reduced[j] {
                y[r] = v;
            }
        }
        y
    }

    /// Lifted coordinates of a reduced point (homogeneous entries set to 1).
    pub(crate) fn unreduce(&self, y: &[f64]) -> Vec<f64> {
        (0..self.n).map(|j| self.reduced[j].map_or(1.0, |r| y[r])).collect()
    }

    /// Reduced-coordinate index of each drawn coordinate, per component.
    pub(crate) fn drawn(&self) -> Vec<Vec<usize>> {
        self.components
            .iter()
            .map(|c| c.coords.iter().map(|&j| self.reduced[j].expect("drawn coords are not homogeneous")).collect())
            .collect()
    }

    /// The fixed point of map `i` (a point of the attractor), lifted.
    pub fn fixed_point(&self, i: usize) -> Vec<f64> {
        let d = self.reduced_dim();
        // y (I - A) = b  ⇔  y = b (I - A)⁻¹
        let mut m = Mat::identity(d);
        for (k, v) in self.lin[i].iter().enumerate() {
            m.data[k] -= v;
        }
        let inv = m.inverse().expect("I - A is invertible for a contractive map");
        let b = Mat { rows: 1, cols: d, data: self.trans[i].clone() };
        self.unreduce(&b.mul(&inv).data)
    }
}

#[cfg(test)]
mod tests;

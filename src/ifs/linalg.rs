//! Small dense matrices for the IFS module: products, Kronecker and block
//! sums, an LU inverse with partial pivoting, and a spectral-radius estimate.
//! Sizes here are at most a few dozen rows, so plain loops are the right tool.

/// A dense row-major `rows × cols` matrix of `f64`.
#[derive(Clone, Debug, PartialEq)]
pub struct Mat {
    pub rows: usize,
    pub cols: usize,
    pub data: Vec<f64>,
}

impl Mat {
    pub fn zeros(rows: usize, cols: usize) -> Mat {
        Mat { rows, cols, data: vec![0.0; rows * cols] }
    }

    pub fn identity(n: usize) -> Mat {
        let mut m = Mat::zeros(n, n);
        for i in 0..n {
            m.data[i * n + i] = 1.0;
        }
        m
    }

    /// Builds a matrix from equal-length rows; `None` if the rows are ragged.
    pub fn from_rows(rows: &[Vec<f64>]) -> Option<Mat> {
        let cols = rows.first().map_or(0, |r| r.len());
        if rows.iter().any(|r| r.len() != cols) {
            return None;
        }
        Some(Mat { rows: rows.len(), cols, data: rows.iter().flatten().copied().collect() })
    }

    #[inline]
    pub fn at(&self, r: usize, c: usize) -> f64 {
        self.data[r * self.cols + c]
    }

    #[inline]
    pub fn set(&mut self, r: usize, c: usize, v: f64) {
        self.data[r * self.cols + c] = v;
    }

    pub fn row(&self, r: usize) -> &[f64] {
        &self.data[r * self.cols..(r + 1) * self.cols]
    }

    pub fn mul(&self, o: &Mat) -> Mat {
        assert_eq!(self.cols, o.rows, "matrix product shape mismatch");
        let mut out = Mat::zeros(self.rows, o.cols);
        for i in 0..self.rows {
            for k in 0..self.cols {
                let a = self.at(i, k);
                if a == 0.0 {
                    continue;
                }
                let orow = o.row(k);
                let dst = &mut out.data[i * o.cols..(i + 1) * o.cols];
                for (d, &b) in dst.iter_mut().zip(orow) {
                    *d += a * b;
                }
            }
        }
        out
    }

    /// Kronecker product `self ⊗ o`.
    pub fn kron(&self, o: &Mat) -> Mat {
        let mut out = Mat::zeros(self.rows * o.rows, self.cols * o.cols);
        for i in 0..self.rows {
            for j in 0..self.cols {
                let a = self.at(i, j);
                for k in 0..o.rows {
                    for l in 0..o.cols {
                        out.set(i * o.rows + k, j * o.cols + l, a * o.at(k, l));
                    }
                }
            }
        }
        out
    }

    /// Block-diagonal sum `diag(self, o)`.
    pub fn block_diag(&self, o: &Mat) -> Mat {
        let mut out = Mat::zeros(self.rows + o.rows, self.cols + o.cols);
        for i in 0..self.rows {
            for j in 0..self.cols {
                out.set(i, j, self.at(i, j));
            }
        }
        for i in 0..o.rows {
            for j in 0..o.cols {
                out.set(self.rows + i, self.cols + j, o.at(i, j));
            }
        }
        out
    }

    /// Largest absolute entry.
    pub fn max_abs(&self) -> f64 {
        self.data.iter().fold(0.0, |m, &x| m.max(x.abs()))
    }

    /// Inverse by LU with partial pivoting; `None` when a pivot falls below
    /// `1e-12` times the largest entry (numerically singular).
    pub fn inverse(&self) -> Option<Mat> {
        assert_eq!(self.rows, self.cols, "inverse of a non-square matrix");
        let n = self.rows;
        let scale = self.max_abs();
        if scale == 0.0 || !scale.is_finite() {
            return None;
        }
        let mut a = self.clone();
        let mut inv = Mat::identity(n);
        for col in 0..n {
            let (piv, pv) = (col..n)
                .map(|r| (r, a.at(r, col).abs()))
                .fold((col, -1.0), |best, x| if x.1 > best.1 { x } else { best });
            if pv <= 1e-12 * scale {
                return None;
            }
            if piv != col {
                for c in 0..n {
                    a.data.swap(piv * n + c, col * n + c);
                    inv.data.swap(piv * n + c, col * n + c);
                }
            }
            let d = a.at(col, col);
            for c in 0..n {
                a.data[col * n + c] /= d;
                inv.data[col * n + c] /= d;
            }
            for r in 0..n {
                if r == col {
                    continue;
                }
                let f = a.at(r, col);
                if f == 0.0 {
                    continue;
                }
                for c in 0..n {
                    a.data[r * n + c] -= f * a.data[col * n + c];
                    inv.data[r * n + c] -= f * inv.data[col * n + c];
                }
            }
        }
        Some(inv)
    }
}

/// Spectral radius by Gelfand's formula ρ(A) = lim ‖A^k‖^{1/k}, with
/// k = 2^40 reached by 40 normalized squarings (no overflow, exact zero for
/// nilpotent matrices). The estimate approaches ρ from above.
pub fn spectral_radius(a: &Mat) -> f64 {
    assert_eq!(a.rows, a.cols);
    if a.rows == 0 {
        return 0.0;
    }
    let mut b = a.clone();
    let mut log_scale = 0.0f64; // log ‖A^k‖ accumulated as k doubles
    let mut k = 1.0f64;
    let s = b.max_abs();
    if s == 0.0 {
        return 0.0;
    }
    b.data.iter_mut().for_each(|x| *x /= s);
    log_scale += s.ln();
    for _ in 0..40 {
        let sq = b.mul(&b);
        let s = sq.max_abs();
        if s == 0.0 {
            return 0.0;
        }
        log_scale = 2.0 * log_scale + s.ln();
        k *= 2.0;
        b = sq;
        b.data.iter_mut().for_each(|x| *x /= s);
    }
    (log_scale / k).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_roundtrip() {
        let a = Mat::from_rows(&[vec![2.0, 1.0, 0.0], vec![1.0, 3.0, 1.0], vec![0.0, 1.0, 4.0]]).unwrap();
        let p = a.mul(&a.inverse().unwrap());
        for i in 0..3 {
            for j in 0..3 {
                assert!((p.at(i, j) - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14);
            }
        }
        let s = Mat::from_rows(&[vec![1.0, 2.0], vec![2.0, 4.0]]).unwrap();
        assert!(s.inverse().is_none());
    }

    #[test]
    fn spectral_radius_of_triangular_and_rotation() {
        let t = Mat::from_rows(&[vec![0.5, 7.0], vec![0.0, 0.25]]).unwrap();
        assert!((spectral_radius(&t) - 0.5).abs() < 1e-9);
        let (c, s) = (0.3f64.cos() * 0.9, 0.3f64.sin() * 0.9);
        let r = Mat::from_rows(&[vec![c, -s], vec![s, c]]).unwrap();
        assert!((spectral_radius(&r) - 0.9).abs() < 1e-9);
        let nil = Mat::from_rows(&[vec![0.0, 1.0], vec![0.0, 0.0]]).unwrap();
        assert_eq!(spectral_radius(&nil), 0.0);
    }
}

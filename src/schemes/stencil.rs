//! Subdivision stencils: the output points of a linear scheme as weighted
//! sums of input points, one sparse row per output vertex (CSR). The rows
//! are the subdivision matrix `S` (output V × input V): `S @ P` is the
//! output positions, and `S @ A` interpolates any per-vertex attribute `A`
//! with the scheme's own weights.
//!
//! Rows may list a column more than once (a vertex seen through two faces);
//! applying a row sums the terms, and SciPy sums duplicates on conversion.
//! Rows are built in parallel blocks and concatenated, so building is
//! linear in the number of terms.

use crate::error::Result;
use glam::DVec3;
use rayon::prelude::*;

/// Sparse rows: row `i` is `col[off[i]..off[i + 1]]` with weights `w[..]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stencils {
    pub off: Vec<usize>,
    pub col: Vec<u32>,
    pub w: Vec<f64>,
    /// Number of input vertices (columns).
    pub n_cols: usize,
}

/// One row being written: `add(col, weight)`. Either stored as terms, or,
/// when only the points are wanted, applied as it is written: each term
/// added to the point in the order given, as applying the stored row sums
/// them (the same bits, without the term lists).
pub struct Row<'a> {
    col: &'a mut Vec<u32>,
    w: &'a mut Vec<f64>,
    /// The points the terms are applied to at once (no terms stored).
    apply: Option<&'a [DVec3]>,
    point: DVec3,
}

impl Row<'_> {
    /// Whether the terms are applied as they come (positions only, no
    /// rows stored): then [`Row::add_applied`] may add a point directly.
    #[inline]
    pub fn applying(&self) -> bool {
        self.apply.is_some()
    }

    /// Adds `x · w` to the point of a row that is applied as it comes (a
    /// point already combined from the columns, e.g. a large face's mean).
    #[inline]
    pub fn add_applied(&mut self, x: DVec3, w: f64) {
        debug_assert!(self.applying(), "add_applied on a stored row");
        self.point += x * w;
    }

    #[inline]
    pub fn add(&mut self, col: u32, w: f64) {
        match self.apply {
            Some(p) => self.point += p[col as usize] * w,
            None => {
                self.col.push(col);
                self.w.push(w);
            }
        }
    }
    /// Number of terms stored so far in this block (a mark for merging a
    /// row's duplicates); rows applied as written store none.
    #[inline]
    pub fn len(&self) -> usize {
        self.col.len()
    }
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.col.is_empty()
    }
}

const BLOCK: usize = 4096;

impl Stencils {
    /// Builds `n_rows` rows with `fill(i, row)`, in parallel blocks of rows.
    /// Fails only when cancelled.
    pub fn build(n_rows: usize, n_cols: usize, fill: impl Fn(usize, &mut Row) + Sync) -> Result<Stencils> {
        let blocks: Vec<(Vec<usize>, Vec<u32>, Vec<f64>)> = (0..n_rows.div_ceil(BLOCK))
            .into_par_iter()
            .map(|b| {
                let (s, e) = (b * BLOCK, ((b + 1) * BLOCK).min(n_rows));
                let mut lens = Vec::with_capacity(e - s);
                let (mut col, mut w) = (Vec::new(), Vec::new());
                if crate::cancel::requested() {
                    return (vec![0; e - s], col, w);
                }
                for i in s..e {
                    let before = col.len();
                    fill(i, &mut Row { col: &mut col, w: &mut w, apply: None, point: DVec3::ZERO });
                    lens.push(col.len() - before);
                }
                (lens, col, w)
            })
            .collect();
        crate::cancel::check()?;
        let nnz: usize = blocks.iter().map(|b| b.1.len()).sum();
        let mut st = Stencils { off: Vec::with_capacity(n_rows + 1), col: Vec::with_capacity(nnz), w: Vec::with_capacity(nnz), n_cols };
        st.off.push(0);
        for (lens, col, w) in blocks {
            for l in lens {
                let last = *st.off.last().unwrap();
                st.off.push(last + l);
            }
            st.col.extend_from_slice(&col);
            st.w.extend_from_slice(&w);
        }
        Ok(st)
    }

    /// The identity on `n` points.
    pub fn identity(n: usize) -> Stencils {
        Stencils { off: (0..=n).collect(), col: (0..n as u32).collect(), w: vec![1.0; n], n_cols: n }
    }

    pub fn n_rows(&self) -> usize {
        self.off.len() - 1
    }

    pub fn nnz(&self) -> usize {
        self.col.len()
    }

    #[inline]
    pub fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let (s, e) = (self.off[i], self.off[i + 1]);
        (&self.col[s..e], &self.w[s..e])
    }

    /// `S @ p` for points.
    pub fn apply_points(&self, p: &[DVec3]) -> Result<Vec<DVec3>> {
        debug_assert_eq!(p.len(), self.n_cols);
        let out: Vec<DVec3> = (0..self.n_rows())
            .into_par_iter()
            .with_min_len(super::hosts::MIN_LEN)
            .map(|i| {
                let (c, w) = self.row(i);
                c.iter().zip(w).map(|(&c, &w)| p[c as usize] * w).sum()
            })
            .collect();
        crate::cancel::check()?;
        Ok(out)
    }

    /// `S @ p` without storing `S`: row `i` is applied as `fill(i, row)`
    /// writes it (as for [`Stencils::build`]), term by term.
    /// The result is [`Stencils::build`] then [`Stencils::apply_points`]
    /// bit for bit (same terms, summed in the same order), without the rows'
    /// memory (issue 19: for open meshes and creases, about 12 bytes per
    /// term and 8 per row, several times the output, only to place points).
    pub fn apply_rows_points(n_rows: usize, p: &[DVec3], fill: impl Fn(usize, &mut Row) + Sync) -> Result<Vec<DVec3>> {
        // the row is applied as it is written: ZERO plus each term in order,
        // what summing the stored terms (`apply_points`) computes
        let out: Vec<DVec3> = (0..n_rows)
            .into_par_iter()
            .with_min_len(super::hosts::MIN_LEN)
            .map(|i| {
                // cancelled: zeros, the check below reports it
                if crate::cancel::requested() {
                    return DVec3::ZERO;
                }
                // no terms are stored: the lists stay empty (no allocation)
                let (mut col, mut w) = (Vec::new(), Vec::new());
                let mut row = Row { col: &mut col, w: &mut w, apply: Some(p), point: DVec3::ZERO };
                fill(i, &mut row);
                row.point
            })
            .collect();
        crate::cancel::check()?;
        Ok(out)
    }

    /// The points of the rows `fill` applied to `p`, and the rows when
    /// `keep` (a level asked for its stencils): [`Stencils::build`] then
    /// [`Stencils::apply_points`], or else [`Stencils::apply_rows_points`],
    /// the same bits without storing the rows.
    pub fn points_and_rows(n_rows: usize, n_cols: usize, p: &[DVec3], keep: bool, fill: impl Fn(usize, &mut Row) + Sync) -> Result<(Vec<DVec3>, Option<Stencils>)> {
        if keep {
            let s = Stencils::build(n_rows, n_cols, &fill)?;
            Ok((s.apply_points(p)?, Some(s)))
        } else {
            Ok((Stencils::apply_rows_points(n_rows, p, &fill)?, None))
        }
    }

    /// `S @ a` for a row-major `(n_cols, k)` array.
    pub fn apply(&self, a: &[f64], k: usize) -> Result<Vec<f64>> {
        debug_assert_eq!(a.len(), self.n_cols * k);
        let mut out = vec![0.0; self.n_rows() * k];
        if k == 0 {
            return Ok(out);
        }
        out.par_chunks_mut(k).with_min_len(super::hosts::MIN_LEN).enumerate().for_each(|(i, o)| {
            let (c, w) = self.row(i);
            for (&c, &w) in c.iter().zip(w) {
                let src = &a[c as usize * k..(c as usize + 1) * k];
                for (o, s) in o.iter_mut().zip(src) {
                    *o += w * s;
                }
            }
        });
        crate::cancel::check()?;
        Ok(out)
    }

    /// `self ∘ prev`: the stencils of two levels in a row (`S₂ S₁`), in terms
    /// of `prev`'s columns. Duplicate columns of a row are merged.
    pub fn compose(&self, prev: &Stencils) -> Result<Stencils> {
        debug_assert_eq!(self.n_cols, prev.n_rows());
        Stencils::build(self.n_rows(), prev.n_cols, |i, row| {
            let (c, w) = self.row(i);
            let start = row.len();
            for (&c, &w) in c.iter().zip(w) {
                let (pc, pw) = prev.row(c as usize);
                for (&pc, &pw) in pc.iter().zip(pw) {
                    row.add(pc, w * pw);
                }
            }
            merge_duplicates(row, start);
        })
    }
}

/// Sorts the terms of the row written since `start` by column and merges
/// equal columns (rows are short: insertion sort).
fn merge_duplicates(row: &mut Row, start: usize) {
    let n = row.col.len();
    for i in start + 1..n {
        let mut j = i;
        while j > start && row.col[j - 1] > row.col[j] {
            row.col.swap(j - 1, j);
            row.w.swap(j - 1, j);
            j -= 1;
        }
    }
    let mut k = start;
    for i in start..n {
        if k > start && row.col[k - 1] == row.col[i] {
            row.w[k - 1] += row.w[i];
        } else {
            row.col[k] = row.col[i];
            row.w[k] = row.w[i];
            k += 1;
        }
    }
    row.col.truncate(k);
    row.w.truncate(k);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows applied as they are built give the stored rows' points bit for
    /// bit: rows of 0–40 terms, repeated and scaled columns, more rows than
    /// one parallel task takes.
    #[test]
    fn rows_applied_unstored_equal_the_stored_rows() {
        let p: Vec<DVec3> = (0..97).map(|i| DVec3::new((i as f64 * 0.37).sin(), (i as f64).sqrt() * 1e-3, 1.0 / (1.0 + i as f64))).collect();
        let fill = |i: usize, r: &mut Row| {
            for j in 0..(i * 7) % 41 {
                r.add(((i * 31 + j * 17) % 97) as u32, 1.0 / (1.0 + j as f64) + (i as f64) * 1e-7);
            }
            if i % 3 == 0 {
                // a negative zero term: the sums start from +0 either way
                r.add((i % 97) as u32, -0.0);
            }
        };
        let n = 20_000;
        let s = Stencils::build(n, p.len(), fill).unwrap();
        let want = s.apply_points(&p).unwrap();
        let got = Stencils::apply_rows_points(n, &p, fill).unwrap();
        assert_eq!(got.len(), want.len());
        for (i, (a, b)) in got.iter().zip(&want).enumerate() {
            assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits), "row {i}");
        }
        let (pts, rows) = Stencils::points_and_rows(n, p.len(), &p, false, fill).unwrap();
        assert!(rows.is_none());
        assert_eq!(pts, want);
        let (pts, rows) = Stencils::points_and_rows(n, p.len(), &p, true, fill).unwrap();
        assert_eq!(rows.as_ref(), Some(&s));
        assert_eq!(pts, want);
    }

    #[test]
    fn compose_equals_applying_twice() {
        let a = Stencils::build(3, 2, |i, r| {
            r.add(0, 0.5 + i as f64);
            r.add(1, 0.25);
            r.add(0, 0.125);
        })
        .unwrap();
        let b = Stencils::build(2, 3, |i, r| {
            r.add(i as u32, 1.0);
            r.add(2, -0.5);
        })
        .unwrap();
        let p = [DVec3::new(1.0, 2.0, 3.0), DVec3::new(-1.0, 0.5, 4.0)];
        let twice = b.apply_points(&a.apply_points(&p).unwrap()).unwrap();
        let c = b.compose(&a).unwrap();
        let once = c.apply_points(&p).unwrap();
        for (x, y) in twice.iter().zip(&once) {
            assert!((*x - *y).length() < 1e-14);
        }
        // merged: at most one term per column
        for i in 0..c.n_rows() {
            let (cols, _) = c.row(i);
            assert!(cols.windows(2).all(|w| w[0] < w[1]));
        }
        let flat: Vec<f64> = p.iter().flat_map(|q| [q.x, q.y, q.z]).collect();
        let k = c.apply(&flat, 3).unwrap();
        for (i, q) in once.iter().enumerate() {
            assert!((k[3 * i] - q.x).abs() + (k[3 * i + 1] - q.y).abs() + (k[3 * i + 2] - q.z).abs() < 1e-14);
        }
    }
}

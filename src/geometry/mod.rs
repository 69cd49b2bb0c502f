//! Geometry shared by several schemes, operators and exports: one
//! implementation each, called by all of them. The triangulation every
//! export, peer check and crossing check uses; the exact crossing checks;
//! wall thickness by ray casting (printability).

pub mod crossing;
pub mod thickness;
pub mod triangulate;

pub use triangulate::Triangulation;

use crate::mesh::Mesh;
use glam::DVec3;

/// The unit Newell normal of the polygon whose corners `corners()` gives
/// (in cycle order),
/// computed where the plain formula fails: coordinates past ~1e154 (the
/// cross products or the squared length leave f64) or below ~1e-154 (they
/// underflow to zero). The corners are taken relative to the first and
/// divided by their largest coordinate, which leaves the direction
/// unchanged. Zero for a degenerate polygon. Callers use it only when the
/// plain normal came out zero or non-finite, so the bits of ordinary
/// inputs do not change.
#[cold]
pub fn scaled_unit_normal<I: Iterator<Item = DVec3>>(corners: impl Fn() -> I) -> DVec3 {
    let Some(o) = corners().next() else { return DVec3::ZERO };
    let s = corners().map(|p| (p - o).abs().max_element()).fold(0.0, f64::max);
    if !(s > 0.0 && s.is_finite()) {
        return DVec3::ZERO;
    }
    let q: Vec<DVec3> = corners().map(|p| (p - o) / s).collect();
    let n: DVec3 = (0..q.len()).map(|i| q[i].cross(q[(i + 1) % q.len()])).sum();
    n.normalize_or_zero()
}

/// `n.normalize_or_zero()` for a Newell vector `n` of the polygon
/// `corners`, falling back to [`scaled_unit_normal`] when that is zero or
/// `n` is not finite while the polygon may still have an area.
#[inline]
pub fn unit_newell<I: Iterator<Item = DVec3>>(n: DVec3, corners: impl Fn() -> I) -> DVec3 {
    let u = n.normalize_or_zero();
    if u != DVec3::ZERO || (n == DVec3::ZERO && !tiny_or_huge(corners())) {
        return u;
    }
    scaled_unit_normal(corners)
}

/// Whether a magnitude `m` is past the range where its square (a squared
/// length, a cross product) stays a normal f64.
#[inline]
pub fn squares_leave_f64(m: f64) -> bool {
    m > 1e150 || (m != 0.0 && m < 1e-150)
}

/// Whether some coordinate of `corners` is past that range.
#[inline]
fn tiny_or_huge(mut corners: impl Iterator<Item = DVec3>) -> bool {
    corners.any(|p| squares_leave_f64(p.abs().max_element()))
}

/// The smallest nonzero and the largest magnitude of the coordinates'
/// largest components (`(inf, 0)` for none): one parallel pass.
pub fn coordinate_range(pos: &[DVec3]) -> (f64, f64) {
    use rayon::prelude::*;
    pos.par_iter()
        .map(|p| p.abs().max_element())
        .fold(|| (f64::INFINITY, 0.0f64), |(lo, hi), m| (if m > 0.0 { lo.min(m) } else { lo }, hi.max(m)))
        .reduce(|| (f64::INFINITY, 0.0), |a, b| (a.0.min(b.0), a.1.max(b.1)))
}

/// Coordinates whose largest magnitude lies outside `[2^-200, 2^200]`:
/// there squared lengths and cross products leave f64 (overflow to
/// infinity or underflow to zero). Returns the power of two `s` that
/// brings the largest magnitude into `[1, 2)`, `None` for ordinary
/// coordinates (and for all-zero or non-finite ones).
pub fn extreme_scale(pos: &[DVec3]) -> Option<f64> {
    let top = coordinate_range(pos).1;
    if top == 0.0 || !top.is_finite() || (2f64.powi(-200)..=2f64.powi(200)).contains(&top) {
        return None;
    }
    // 2^k is exact for |k| <= 1000; a subnormal top stays far above underflow
    Some(2f64.powi((top.log2().floor() as i32).clamp(-1000, 1000)))
}

/// Runs a similarity-equivariant `op` on `m` divided by [`extreme_scale`]'s
/// power of two (exact: only exponents change) and multiplies its output
/// back, so meshes at 1e±300 get the same answer as at unit size. `op`
/// receives the factor the mesh was divided by (1 for ordinary meshes,
/// which are passed through untouched), to divide its absolute lengths by.
pub fn scale_free(m: &Mesh, op: impl FnOnce(&Mesh, f64) -> crate::Result<Mesh>) -> crate::Result<Mesh> {
    Ok(scale_free_with(m, |m, s| Ok((op(m, s)?, ())))?.0)
}

/// [`scale_free`] for an operation that returns more than the mesh.
pub fn scale_free_with<T>(m: &Mesh, op: impl FnOnce(&Mesh, f64) -> crate::Result<(Mesh, T)>) -> crate::Result<(Mesh, T)> {
    let Some(s) = extreme_scale(m.positions()) else { return op(m, 1.0) };
    let mut scaled = m.clone();
    scaled.positions_mut().iter_mut().for_each(|p| *p /= s);
    let (mut out, extra) = op(&scaled, s)?;
    out.positions_mut().iter_mut().for_each(|p| *p *= s);
    if let Some(v) = out.positions().iter().position(|p| !p.is_finite()) {
        return Err(crate::MeshError::Precondition(format!(
            "output vertex {v} lies beyond float64's range at this mesh's scale; scale the mesh down first"
        )));
    }
    Ok((out, extra))
}

/// The mesh's triangulation and the positions its triangles index: the
/// vertices, then the points the triangulation adds (owned by no vertex).
pub fn triangles_with_points(m: &Mesh) -> (Vec<[u32; 3]>, Vec<DVec3>) {
    let t = m.triangulate();
    let mut p = m.positions().to_vec();
    p.extend_from_slice(&t.points);
    (t.tris, p)
}

/// What keeps a triangle list from being a closed 2-manifold, as printers
/// and slicers need ([`triangle_defects`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TriangleDefects {
    /// Sides that do not meet exactly one opposite side, or join a vertex
    /// to itself.
    pub unpaired_sides: usize,
    /// Vertices whose triangles form more than one fan (two sheets touching
    /// at a point, as the triangulation of a self-loop gives); counted only
    /// when every side is paired.
    pub pinched_vertices: usize,
}

/// The defects of `tris`: both counts are 0 exactly when the triangles form
/// a closed, consistently oriented 2-manifold. One parallel sort of the
/// sides by their vertex pair (a side pairs when its pair occurs exactly
/// twice, once each way), then one walk around every vertex
/// (`next(twin(c))` turns corner `c` about its vertex).
pub fn triangle_defects(tris: &[[u32; 3]]) -> TriangleDefects {
    use rayon::prelude::*;
    let ends = |c: usize| {
        let t = tris[c / 3];
        (t[c % 3], t[(c % 3 + 1) % 3])
    };
    let mut sides: Vec<(u64, u32)> = (0..3 * tris.len())
        .into_par_iter()
        .map(|c| {
            let (a, b) = ends(c);
            (((a.min(b) as u64) << 32) | a.max(b) as u64, c as u32)
        })
        .collect();
    sides.par_sort_unstable();
    // the opposite corner of every corner, or u32::MAX
    let mut twin = vec![u32::MAX; 3 * tris.len()];
    let mut i = 0;
    while i < sides.len() {
        let mut j = i + 1;
        while j < sides.len() && sides[j].0 == sides[i].0 {
            j += 1;
        }
        if j - i == 2 {
            let (c, d) = (sides[i].1, sides[i + 1].1);
            let ((a, b), (x, _)) = (ends(c as usize), ends(d as usize));
            if a != b && a != x {
                twin[c as usize] = d;
                twin[d as usize] = c;
            }
        }
        i = j;
    }
    let unpaired_sides = twin.iter().filter(|&&t| t == u32::MAX).count();
    let mut pinched_vertices = 0;
    if unpaired_sides == 0 && !tris.is_empty() {
        let nv = tris.iter().flatten().map(|&v| v as usize + 1).max().unwrap_or(0);
        let mut fans = vec![0u32; nv];
        let mut seen = vec![false; 3 * tris.len()];
        for c0 in 0..3 * tris.len() {
            if seen[c0] {
                continue;
            }
            fans[tris[c0 / 3][c0 % 3] as usize] += 1;
            let mut c = c0;
            while !seen[c] {
                seen[c] = true;
                let t = twin[c] as usize;
                c = t - t % 3 + (t % 3 + 1) % 3;
            }
        }
        pinched_vertices = fans.iter().filter(|&&k| k > 1).count();
    }
    TriangleDefects { unpaired_sides, pinched_vertices }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defects_of_closed_open_and_pinched_triangles() {
        let unpaired_sides = |t: &[[u32; 3]]| triangle_defects(t).unpaired_sides;
        let tet = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert_eq!(triangle_defects(&tet), TriangleDefects { unpaired_sides: 0, pinched_vertices: 0 });
        assert_eq!(unpaired_sides(&tet), 0);
        assert_eq!(unpaired_sides(&tet[..3]), 3); // one triangle missing: its three sides
        // a flipped triangle: its sides meet sides of the same direction
        let flipped = [[0, 2, 1], [0, 1, 3], [1, 3, 2], [0, 3, 2]];
        assert!(unpaired_sides(&flipped) > 0);
        // the same tetrahedron twice: every side has two copies
        let twice: Vec<[u32; 3]> = tet.iter().chain(&tet).copied().collect();
        assert_eq!(unpaired_sides(&twice), 24);
        // a triangle with a repeated corner: its side 0-0 (its other two pair each other)
        assert_eq!(unpaired_sides(&[[0, 0, 1]]), 1);
        // two tetrahedra sharing only vertex 0: one pinch
        let two: Vec<[u32; 3]> = tet.iter().chain(&tet.map(|t| t.map(|v| if v == 0 { 0 } else { v + 3 }))).copied().collect();
        assert_eq!(triangle_defects(&two), TriangleDefects { unpaired_sides: 0, pinched_vertices: 1 });
        // a Sierpinski polyhedron pinches at every self-loop; a sponge nowhere
        let s = crate::schemes::sierpinski::sierpinski_iterated(&crate::primitives::tetrahedron(), 2).unwrap();
        let d = triangle_defects(&s.triangulate().tris);
        assert_eq!((d.unpaired_sides, d.pinched_vertices), (0, s.n_self_loops()));
        let sponge = crate::schemes::menger_sponge::menger_sponge(2).unwrap();
        assert_eq!(triangle_defects(&sponge.triangulate().tris), TriangleDefects { unpaired_sides: 0, pinched_vertices: 0 });
    }
}

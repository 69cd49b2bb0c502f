//! Corner (face-varying) data under OpenSubdiv's default
//! `FVAR_LINEAR_ALL` through a Catmull-Clark or Loop level, read straight
//! off the level's output numbering (issue 15: attributes at the cost of
//! their bytes).
//!
//! "Linear everywhere" makes the data bilinear inside every face: a child
//! corner at a vertex point takes its parent corner's value, one at an edge
//! point the mean of the edge's two corner values in that face, one at a
//! face point the mean of the face's corner values. That is what
//! subdividing the face-varying mesh ([`super::face_varying`]) with every
//! edge and vertex infinitely sharp gives (DeRose, Kass & Truong 1998 §3:
//! a sharp edge point is the midpoint, a corner stays put; the face point
//! is the centroid in both schemes' masks), without building that mesh,
//! its stencils or a second level.
//!
//! The output corners are matched to their parents by the primal host's
//! numbering ([`super::primal_columns`]): input face `f` of degree `n`
//! owns the output faces `fbase(f)..`, in corner order; Catmull-Clark's
//! face `fbase + k` starts at `[v(h), e(h), fp, e(prev h)]` for the face's
//! `k`-th corner `h`; Loop's triangle `fbase + k` at `[v(h), e(h),
//! e(prev h)]` and its middle triangle `fbase + 3` at `[e(h₀), e(h₁),
//! e(h₂)]`; a hole owns one (unexported) hole face. Every output corner's
//! vertex is checked against that layout, so a mesh the layout does not
//! describe (a point-sphere, a face Loop does not split into four) is
//! reported as `None` and the caller takes the face-varying-mesh path.

use super::hosts::{FaceLayout, MIN_LEN};
use crate::error::Result;
use crate::mesh::{Mesh, POINT};
use rayon::prelude::*;

/// Which primal level produced `out`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primal {
    /// Catmull-Clark: every real `n`-gon into `n` quads around a face point.
    Quads,
    /// Loop: every real triangle into four; other faces are first fanned
    /// around their centroid, as Loop's level does (`hosts::fan_triangulate`),
    /// the centroid's value the mean of the face's.
    Triangles,
    /// Midpoint: triangles into four (as Loop), every other face into n
    /// quads around its centroid (as Catmull-Clark).
    Mixed,
}

/// The exported corner rows (`(C', k)` row-major) of `out`, one level of
/// `scheme` on `input`, from `rows`, the exported corner rows of `input`
/// (`(C, k)`), linear in every face; `None` when `out` does not follow the
/// layout (see the module docs). Fails only when cancelled.
pub fn level(input: &Mesh, out: &Mesh, scheme: Primal, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    if input.v_out.iter().any(|&o| o & POINT != 0) || input.f_start.iter().any(|&s| s & POINT != 0) {
        return Ok(None);
    }
    let fl = FaceLayout::new(input)?;
    let (nv, ne, nf) = (input.n_vertices() as u32, input.n_edges() as u32, input.n_faces());
    if scheme == Primal::Triangles && (0..nf).any(|f| !input.f_hole[f] && fl.degree(f) != 3) {
        return fanned(input, &fl, out, rows, k);
    }
    // per input face: first exported input corner, first output face, first exported output corner
    let mut starts = Vec::with_capacity(nf);
    let (mut ci, mut fo, mut co) = (0usize, 0usize, 0usize);
    for f in 0..nf {
        crate::cancel::poll(f)?;
        starts.push((ci, fo, co));
        let n = fl.degree(f);
        if input.f_hole[f] {
            fo += 1;
            continue;
        }
        if n == 3 && scheme != Primal::Quads {
            (fo, co) = (fo + 4, co + 12);
        } else if scheme != Primal::Triangles {
            (fo, co) = (fo + n, co + 4 * n);
        } else {
            return Ok(None);
        }
        ci += n;
    }
    if rows.len() != ci * k || fo != out.n_faces() {
        return Ok(None);
    }
    let mut res = vec![0.0; co * k];
    if k == 0 {
        return Ok(Some(res));
    }
    let (next, vert, _) = out.halfedge_columns();
    let (ivert, iprev) = (&input.he_vert, &input.he_prev);
    let row = |c: usize| &rows[c * k..(c + 1) * k];
    // The output rows of each face are one contiguous block: hand them out by face.
    let mut blocks: Vec<(usize, &mut [f64])> = Vec::with_capacity(nf);
    let mut rest: &mut [f64] = &mut res;
    for f in 0..nf {
        if input.f_hole[f] {
            continue;
        }
        let n = fl.degree(f);
        let len = if n == 3 && scheme != Primal::Quads { 12 } else { 4 * n } * k;
        let (a, b) = std::mem::take(&mut rest).split_at_mut(len);
        blocks.push((f, a));
        rest = b;
    }
    let ok = blocks.into_par_iter().with_min_len(MIN_LEN).all(|(f, o)| {
        if crate::cancel::requested() {
            return true; // the check below reports it
        }
        let (ci, fo, _) = starts[f];
        let hs = fl.corners(f);
        let n = hs.len();
        // the output face's corner vertices from its first corner, if it has `len` of them
        let corners = |g: usize, want: &mut [u32]| -> bool {
            let s = out.f_start[g];
            if s & POINT != 0 || out.f_hole[g] {
                return false;
            }
            let mut h = s;
            for w in want.iter_mut() {
                *w = vert[h as usize];
                h = next[h as usize];
            }
            h == s
        };
        let mid = |o: &mut [f64], a: usize, b: usize| {
            for ((o, x), y) in o.iter_mut().zip(row(ci + a)).zip(row(ci + b)) {
                *o = (x + y) * 0.5;
            }
        };
        match n == 3 && scheme != Primal::Quads {
            false => {
                let w = 1.0 / n as f64;
                let mut fp = vec![0.0; k];
                for c in 0..n {
                    fp.iter_mut().zip(row(ci + c)).for_each(|(s, x)| *s += x * w);
                }
                let mut got = [0u32; 4];
                for (j, &h) in hs.iter().enumerate() {
                    let p = iprev[h as usize];
                    if !corners(fo + j, &mut got) || got[0] != ivert[h as usize] || got[1] != nv + (h >> 1) || got[2] < nv + ne || got[3] != nv + (p >> 1) {
                        return false;
                    }
                    let q = &mut o[4 * j * k..4 * (j + 1) * k];
                    q[..k].copy_from_slice(row(ci + j));
                    mid(&mut q[k..2 * k], j, (j + 1) % n);
                    q[2 * k..3 * k].copy_from_slice(&fp);
                    mid(&mut q[3 * k..], (j + n - 1) % n, j);
                }
                true
            }
            true => {
                let mut got = [0u32; 3];
                for (j, &h) in hs.iter().enumerate() {
                    let p = iprev[h as usize];
                    if !corners(fo + j, &mut got) || got[0] != ivert[h as usize] || got[1] != nv + (h >> 1) || got[2] != nv + (p >> 1) {
                        return false;
                    }
                    let q = &mut o[3 * j * k..3 * (j + 1) * k];
                    q[..k].copy_from_slice(row(ci + j));
                    mid(&mut q[k..2 * k], j, (j + 1) % 3);
                    mid(&mut q[2 * k..], (j + 2) % 3, j);
                }
                if !corners(fo + 3, &mut got) || (0..3).any(|j| got[j] != nv + (hs[j] >> 1)) {
                    return false;
                }
                let q = &mut o[9 * k..];
                for j in 0..3 {
                    mid(&mut q[j * k..(j + 1) * k], j, (j + 1) % 3);
                }
                true
            }
        }
    });
    crate::cancel::check()?;
    Ok(ok.then_some(res))
}

/// Loop on a mesh with non-triangles: its level runs on the fan
/// (`hosts::fan_triangulate`: a triangle kept, an n-gon's triangle `j`
/// `[x_j, x_{j+1}, centroid]`), so the rows are fanned the same way, the
/// centroid taking the mean of its face's corners (bilinear: the face
/// point's value), and read off the fan's level.
fn fanned(input: &Mesh, fl: &FaceLayout, out: &Mesh, rows: &[f64], k: usize) -> Result<Option<Vec<f64>>> {
    let Some(fan) = super::hosts::fan_triangulate(input)? else { return Ok(None) };
    let real: usize = (0..input.n_faces()).filter(|&f| !input.f_hole[f]).map(|f| fl.degree(f)).sum();
    if rows.len() != real * k {
        return Ok(None);
    }
    let mut fr = Vec::with_capacity(3 * real * k);
    let mut mean = vec![0.0; k];
    let mut ci = 0;
    for f in 0..input.n_faces() {
        crate::cancel::poll(f)?;
        if input.f_hole[f] {
            continue;
        }
        let n = fl.degree(f);
        let r = &rows[ci * k..(ci + n) * k];
        ci += n;
        if n == 3 {
            fr.extend_from_slice(r);
            continue;
        }
        mean.iter_mut().for_each(|x| *x = 0.0);
        for c in r.chunks_exact(k.max(1)) {
            mean.iter_mut().zip(c).for_each(|(m, x)| *m += x / n as f64);
        }
        for j in 0..n {
            fr.extend_from_slice(&r[j * k..(j + 1) * k]);
            fr.extend_from_slice(&r[(j + 1) % n * k..((j + 1) % n + 1) * k]);
            fr.extend_from_slice(&mean);
        }
    }
    level(&fan, out, Primal::Triangles, &fr, k)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::face_varying::{FaceVarying, Interpolation};
    use crate::schemes::level::Request;
    use crate::schemes::{catmull_clark::catmull_clark_level, loop_subdivision::loop_level};

    /// A value per (face, corner) that differs across every edge: all seams.
    fn seamed_rows(m: &Mesh, k: usize) -> Vec<f64> {
        let n = m.to_polygons().indices.len();
        (0..n * k).map(|i| ((i * 7919) % 1013) as f64 * 0.37 - (i % 5) as f64).collect()
    }

    /// Per-vertex values read through the corners: no seams.
    fn smooth_rows(m: &Mesh, k: usize) -> Vec<f64> {
        let idx = m.to_polygons().indices;
        idx.iter().flat_map(|&v| (0..k).map(move |j| (v as f64 + 1.0) * (j as f64 + 0.5))).collect()
    }

    /// The face-varying-mesh path (every edge and vertex infinitely sharp).
    fn by_fv_mesh(m: &Mesh, scheme: Primal, rows: &[f64], k: usize) -> (Mesh, Vec<f64>) {
        let n = rows.len() / k;
        let ids: Vec<u32> = (0..n as u32).collect();
        let fv = FaceVarying::new(m, &ids, rows, k, None).unwrap();
        let lvf = |m: &Mesh, r: &Request| match scheme {
            Primal::Quads => catmull_clark_level(m, r),
            Primal::Triangles => loop_level(m, r),
            Primal::Mixed => unreachable!("midpoint has no face-varying mesh path"),
        };
        let out = lvf(m, &Request::default()).unwrap().mesh;
        let fv = fv.with_creases(m, None, Default::default()).unwrap().level(lvf, Interpolation::All, Default::default()).unwrap();
        let vals = fv.corner_rows().unwrap().iter().flat_map(|&r| fv.values[r as usize * k..(r as usize + 1) * k].to_vec()).collect();
        (out, vals)
    }

    fn check(m: &Mesh, scheme: Primal) {
        for (rows, k) in [(seamed_rows(m, 2), 2), (smooth_rows(m, 3), 3), (seamed_rows(m, 1), 1)] {
            let (out, want) = by_fv_mesh(m, scheme, &rows, k);
            let got = level(m, &out, scheme, &rows, k).unwrap().expect("the layout holds");
            assert_eq!(got.len(), want.len());
            for (i, (a, b)) in got.iter().zip(&want).enumerate() {
                assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "corner value {i}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn catmull_clark_equals_the_face_varying_mesh_path_on_the_corpus() {
        let mut n = 0;
        for (_, m) in crate::schemes::hosts::test_meshes::corpus().into_iter().chain(crate::schemes::hosts::test_meshes::open_meshes()).chain([("handle", crate::schemes::hosts::test_meshes::handle_cube())]) {
            if m.v_out.iter().any(|&o| o & POINT != 0) {
                continue;
            }
            check(&m, Primal::Quads);
            // and one level on: the quads of a level
            let m1 = catmull_clark_level(&m, &Request::default()).unwrap().mesh;
            check(&m1, Primal::Quads);
            n += 1;
        }
        assert!(n >= 5, "{n} corpus meshes");
    }

    /// Triangle meshes, and the others through Loop's fan.
    #[test]
    fn loop_equals_the_face_varying_mesh_path_on_the_corpus() {
        let (mut tri, mut fanned) = (0, 0);
        for (_, m) in crate::schemes::hosts::test_meshes::corpus().into_iter().chain(crate::schemes::hosts::test_meshes::open_meshes()) {
            if m.v_out.iter().any(|&o| o & POINT != 0) {
                continue;
            }
            let fl = FaceLayout::new(&m).unwrap();
            let all_tri = (0..m.n_faces()).all(|f| m.f_hole[f] || fl.degree(f) == 3);
            if all_tri {
                check(&m, Primal::Triangles);
                tri += 1;
            } else {
                check_fanned(&m);
                fanned += 1;
            }
        }
        let ico = crate::primitives::icosahedron();
        check(&ico, Primal::Triangles);
        assert!(tri >= 1 && fanned >= 5, "{tri} triangle meshes, {fanned} others in the corpus");
    }

    /// Loop on a mesh with non-triangles: linear everywhere on its fan, so
    /// corner data equal to the corner's position comes out as the positions
    /// of the fan's midpoint refinement (the same vertex numbering as Loop's
    /// level on the fan: vertices, then edge points).
    fn check_fanned(m: &Mesh) {
        let fan = crate::schemes::hosts::fan_triangulate(m).unwrap().expect("not all triangles");
        let lin = crate::schemes::midpoint::midpoint_level(&fan, &Request::default()).unwrap().mesh;
        let out = loop_level(m, &Request::default()).unwrap().mesh;
        assert_eq!(out.n_vertices(), lin.n_vertices());
        let idx = m.to_polygons().indices;
        let rows: Vec<f64> = idx.iter().flat_map(|&v| m.pos[v as usize].to_array()).collect();
        let got = level(m, &out, Primal::Triangles, &rows, 3).unwrap().expect("the fan's layout holds");
        let oidx = out.to_polygons().indices;
        assert_eq!(got.len(), 3 * oidx.len());
        for (c, &v) in oidx.iter().enumerate() {
            let want = lin.pos[v as usize].to_array();
            for j in 0..3 {
                assert!((got[3 * c + j] - want[j]).abs() < 1e-12, "corner {c}: {:?} vs {want:?}", &got[3 * c..3 * c + 3]);
            }
        }
    }

    /// Midpoint's mixed split against the generic corner transfer (data per
    /// (face, vertex), on which the two agree by definition), two levels.
    #[test]
    fn midpoint_equals_the_generic_transfer() {
        use crate::schemes::hosts::test_meshes as tm;
        let mut n = 0;
        for (name, m0) in tm::corpus().into_iter().chain(tm::open_meshes()) {
            if m0.v_out.iter().any(|&o| o & POINT != 0) {
                continue;
            }
            let mut m = m0;
            for depth in 0..2 {
                let lv = crate::schemes::midpoint::midpoint_level(&m, &tm::full_request()).unwrap();
                let p = m.to_polygons();
                let mut rows = Vec::new();
                let mut at = 0;
                for (f, &sz) in p.sizes.iter().enumerate() {
                    for &v in &p.indices[at..at + sz as usize] {
                        rows.extend([(f * 31 + v as usize * 7) as f64, (f as f64).sin() - v as f64]);
                    }
                    at += sz as usize;
                }
                let mut want = vec![(rows.clone(), 2)];
                crate::schemes::corner_transfer::transfer(&m, &lv.mesh, lv.stencils.as_ref().unwrap(), lv.origins.as_ref().unwrap(), &mut want).unwrap();
                let got = level(&m, &lv.mesh, Primal::Mixed, &rows, 2).unwrap().unwrap_or_else(|| panic!("{name} level {depth}: the layout holds"));
                assert_eq!(got.len(), want[0].0.len(), "{name}");
                for (a, b) in got.iter().zip(&want[0].0) {
                    assert!((a - b).abs() <= 1e-12 * (1.0 + b.abs()), "{name} level {depth}: {a} vs {b}");
                }
                m = lv.mesh;
                n += 1;
            }
        }
        assert!(n >= 20, "{n} levels");
    }

    #[test]
    fn a_mismatched_layout_is_none() {
        let cube = crate::primitives::cube();
        let rows = smooth_rows(&cube, 1);
        let out = catmull_clark_level(&cube, &Request::default()).unwrap().mesh;
        // Loop's layout on quads: not a triangle mesh
        assert!(level(&cube, &out, Primal::Triangles, &rows, 1).unwrap().is_none());
        // the wrong output for the input
        let out2 = catmull_clark_level(&out, &Request::default()).unwrap().mesh;
        assert!(level(&cube, &out2, Primal::Quads, &rows, 1).unwrap().is_none());
    }
}

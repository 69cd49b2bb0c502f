use super::fractals::*;
use super::render::hausdorff;
use super::rules::*;
use super::*;

fn mat(rows: &[&[f64]]) -> Mat {
    Mat::from_rows(&rows.iter().map(|r| r.to_vec()).collect::<Vec<_>>()).unwrap()
}

fn assert_mat_eq(a: &Mat, b: &Mat, tol: f64) {
    assert_eq!((a.rows, a.cols), (b.rows, b.cols));
    for (i, (x, y)) in a.data.iter().zip(&b.data).enumerate() {
        assert!((x - y).abs() < tol, "entry ({}, {}): {x} vs {y}", i / a.cols, i % a.cols);
    }
}

fn bspline_points() -> Vec<Vec<f64>> {
    vec![vec![0.0, 0.0], vec![1.0, 2.0], vec![2.5, 2.2], vec![3.5, 0.5], vec![5.0, 1.5]]
}

/// Exact uniform cubic B-spline at global parameter s ∈ [0, n-3].
fn cubic_eval(p: &[Vec<f64>], s: f64) -> [f64; 2] {
    let j = (s.floor() as usize).min(p.len() - 4);
    let t = s - j as f64;
    let b = [
        (1.0 - t).powi(3) / 6.0,
        (3.0 * t.powi(3) - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t.powi(3) + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t.powi(3) / 6.0,
    ];
    let mut x = [0.0; 2];
    for k in 0..4 {
        x[0] += b[k] * p[j + k][0];
        x[1] += b[k] * p[j + k][1];
    }
    x
}

#[test]
fn cubic_bspline_blocks_are_eq4_split() {
    let (b, starts) = CurveRules::cubic_bspline().blocks(5).unwrap();
    let (e, h, o) = (0.125, 0.75, 0.5);
    let s1 = mat(&[&[o, o, 0., 0., 0.], &[e, h, e, 0., 0.], &[0., o, o, 0., 0.], &[0., e, h, e, 0.], &[0., 0., o, o, 0.]]);
    let s2 = mat(&[&[0., o, o, 0., 0.], &[0., e, h, e, 0.], &[0., 0., o, o, 0.], &[0., 0., e, h, e], &[0., 0., 0., o, o]]);
    assert_mat_eq(&b[0], &s1, 1e-15);
    assert_mat_eq(&b[1], &s2, 1e-15);
    assert_eq!(starts, vec![1, 3]);
    // the same blocks by blossoming uniform knots
    let knots: Vec<f64> = (0..7).map(|k| k as f64).collect();
    let bl = bspline_blocks(3, &knots, &[(2.0, 3.0), (3.0, 4.0)]).unwrap();
    assert_mat_eq(&bl[0], &s1, 1e-14);
    assert_mat_eq(&bl[1], &s2, 1e-14);
}

#[test]
fn four_point_blocks_match_section_2_3() {
    let (b, _) = CurveRules::four_point().blocks(7).unwrap();
    let (a, c) = (-1.0 / 16.0, 9.0 / 16.0);
    let s1 = mat(&[
        &[0., 1., 0., 0., 0., 0., 0.],
        &[a, c, c, a, 0., 0., 0.],
        &[0., 0., 1., 0., 0., 0., 0.],
        &[0., a, c, c, a, 0., 0.],
        &[0., 0., 0., 1., 0., 0., 0.],
        &[0., 0., a, c, c, a, 0.],
        &[0., 0., 0., 0., 1., 0., 0.],
    ]);
    assert_mat_eq(&b[0], &s1, 1e-15);
    assert_eq!(b[1].row(6), &[0., 0., 0., 0., 0., 1., 0.]);
    assert_eq!(b[1].row(5), &[0., 0., 0., a, c, c, a]);
}

#[test]
fn endpoint_and_bezier_blocks_by_blossoming() {
    let b = bspline_blocks(3, &[0., 0., 0., 1., 2., 2., 2.], &[(0., 1.), (1., 2.)]).unwrap();
    let s1 = mat(&[
        &[1., 0., 0., 0., 0.],
        &[0.5, 0.5, 0., 0., 0.],
        &[0., 0.75, 0.25, 0., 0.],
        &[0., 0.375, 0.5, 0.125, 0.],
        &[0., 0.25, 0.5, 0.25, 0.],
    ]);
    assert_mat_eq(&b[0], &s1, 1e-15);
    // S2 is S1 read backwards (the knots are symmetric)
    for r in 0..5 {
        for c in 0..5 {
            assert!((b[1].at(r, c) - s1.at(4 - r, 4 - c)).abs() < 1e-15);
        }
    }
    let q = bspline_blocks(2, &[0., 0., 1., 1.], &[(0., 0.5), (0.5, 1.)]).unwrap();
    assert_mat_eq(&q[0], &mat(&[&[1., 0., 0.], &[0.5, 0.5, 0.], &[0.25, 0.5, 0.25]]), 1e-15);
    assert_mat_eq(&q[1], &mat(&[&[0.25, 0.5, 0.25], &[0., 0.5, 0.5], &[0., 0., 1.]]), 1e-15);
}

#[test]
fn lifted_p_is_the_papers_matrix() {
    let p = lift_control_points(&bspline_points()).unwrap();
    assert_eq!(p.row(0)[2..], [1., 0., 1.]);
    assert_eq!(p.row(1)[2..], [0., 1., 1.]);
    assert_eq!(p.row(4)[2..], [0., 0., 1.]);
    // eq. 3: P⁻¹ S_i P has last column e_n
    let ifs = curve_ifs(&CurveRules::cubic_bspline(), &bspline_points(), "b").unwrap();
    for m in ifs.maps() {
        for r in 0..5 {
            assert!((m.at(r, 4) - if r == 4 { 1.0 } else { 0.0 }).abs() < 1e-12);
        }
    }
    assert!(ifs.contraction().iter().all(|&r| (r - 0.5).abs() < 1e-6));
}

#[test]
fn cubic_bspline_attractor_is_the_limit_curve() {
    let p = bspline_points();
    let ifs = curve_ifs(&CurveRules::cubic_bspline(), &p, "b").unwrap();
    let levels = 12;
    let pts = ifs.polyline(levels).unwrap();
    let n = pts.len() / 2;
    assert_eq!(n, (1 << levels) + 1);
    let mut worst = 0.0f64;
    for (w, x) in pts.chunks_exact(2).enumerate() {
        let c = cubic_eval(&p, 2.0 * w as f64 / (1 << levels) as f64);
        worst = worst.max((x[0] - c[0]).hypot(x[1] - c[1]));
    }
    assert!(worst < 1e-9, "distance to the exact cubic {worst}");
    // iterating from an arbitrary point for 40 levels' worth of contraction
    let it = ifs.iterate(&[vec![7.0, -3.0, 0.4, 2.0]], 16).unwrap();
    let mut worst = 0.0f64;
    for (w, x) in it.chunks_exact(2).enumerate() {
        let c = cubic_eval(&p, 2.0 * (w as f64 + 0.5) / (1 << 16) as f64);
        worst = worst.max((x[0] - c[0]).hypot(x[1] - c[1]));
    }
    assert!(worst < 1e-3, "{worst}");
}

#[test]
fn attractor_does_not_depend_on_the_start_set() {
    let ifs = bspline_ifs(3, &[0., 0., 0., 1., 2., 2., 2.], &[(0., 1.), (1., 2.)], &bspline_points(), "end").unwrap();
    let a = ifs.iterate(&[vec![10.0, 10.0]], 16).unwrap();
    let b = ifs.iterate(&[vec![-5.0, 0.0], vec![0.0, 8.0], vec![3.0, -4.0, 1.0]], 16).unwrap();
    let h = hausdorff(&a, &b, 2);
    assert!(h < 5e-4, "Hausdorff {h}");
    // and the end points are interpolated
    let poly = ifs.polyline(6).unwrap();
    let last = poly.len() - 2;
    assert!((poly[0]).abs() < 1e-12 && poly[1].abs() < 1e-12);
    assert!((poly[last] - 5.0).abs() < 1e-12 && (poly[last + 1] - 1.5).abs() < 1e-12);
}

#[test]
fn four_point_interpolates_and_reproduces_cubics() {
    let cubic = |x: f64| 0.1 * x * x * x - 0.7 * x * x + x + 2.0;
    let p: Vec<Vec<f64>> = (0..7).map(|i| vec![i as f64, cubic(i as f64)]).collect();
    let ifs = curve_ifs(&CurveRules::four_point(), &p, "4pt").unwrap();
    let poly = ifs.polyline(10).unwrap();
    for x in poly.chunks_exact(2) {
        assert!((x[1] - cubic(x[0])).abs() < 1e-9);
    }
    // control points 2, 3, 4 are on the curve, at parameters 0, ½, 1
    let n = poly.len() / 2;
    for (k, idx) in [0, n / 2, n - 1].into_iter().enumerate() {
        assert!((poly[2 * idx] - p[2 + k][0]).abs() < 1e-12 && (poly[2 * idx + 1] - p[2 + k][1]).abs() < 1e-12);
    }
    // wiggly points too
    let q: Vec<Vec<f64>> = (0..7).map(|i| vec![i as f64, if i % 2 == 0 { 1.0 } else { -1.0 }]).collect();
    let poly = curve_ifs(&CurveRules::four_point(), &q, "4pt").unwrap().polyline(8).unwrap();
    let n = poly.len() / 2;
    assert!((poly[2 * (n / 2) + 1] - q[3][1]).abs() < 1e-12);
}

#[test]
fn chaikin_is_the_quadratic_bspline() {
    let p = bspline_points();
    let ifs = curve_ifs(&CurveRules::chaikin(), &p, "chaikin").unwrap();
    let poly = ifs.polyline(6).unwrap();
    // starts at the midpoint of the first leg, ends at the midpoint of the last
    assert!((poly[0] - 0.5).abs() < 1e-12 && (poly[1] - 1.0).abs() < 1e-12);
    let l = poly.len() - 2;
    assert!((poly[l] - 4.25).abs() < 1e-12 && (poly[l + 1] - 1.0).abs() < 1e-12);
    // and plain subdivision converges to the same points
    let sub = CurveRules::chaikin().subdivide(&p, 10).unwrap();
    let flat: Vec<f64> = sub.concat();
    let fine = ifs.polyline(12).unwrap();
    assert!(hausdorff(&flat, &fine, 2) < 0.01);
}

#[test]
fn union_of_two_beziers_draws_both() {
    let a = bezier_ifs(&[vec![0., 0.], vec![1., 2.], vec![2., 0.]]).unwrap();
    let b = bezier_ifs(&[vec![3., 0.], vec![4., -2.], vec![5., 1.]]).unwrap();
    let u = a.union(&b).unwrap();
    assert_eq!(u.dim(), 6);
    assert_eq!(u.components().len(), 2);
    let poly = u.polyline(5).unwrap(); // per vertex: x1 y1 x2 y2
    let pa = a.polyline(5).unwrap();
    let pb = b.polyline(5).unwrap();
    for (k, x) in poly.chunks_exact(4).enumerate() {
        assert!((x[0] - pa[2 * k]).abs() < 1e-12 && (x[1] - pa[2 * k + 1]).abs() < 1e-12);
        assert!((x[2] - pb[2 * k]).abs() < 1e-12 && (x[3] - pb[2 * k + 1]).abs() < 1e-12);
    }
    // the quadratic Bézier at t = ½
    let mid = &pa[pa.len() / 2 - 1..pa.len() / 2 + 1];
    assert!((mid[0] - 1.0).abs() < 1e-12 && (mid[1] - 1.0).abs() < 1e-12);
}

#[test]
fn errors_for_bad_control_points_and_maps() {
    let collinear = vec![vec![0., 0.], vec![1., 1.], vec![2., 2.], vec![3., 3.], vec![4., 4.]];
    let e = curve_ifs(&CurveRules::cubic_bspline(), &collinear, "b").unwrap_err();
    assert!(e.to_string().contains("not an affine basis"), "{e}");
    // last three collinear, first two not: the paper's layout is singular, the fallback works
    let p = vec![vec![0., 1.], vec![1., 3.], vec![2., 0.], vec![3., 0.], vec![4., 0.]];
    assert!(curve_ifs(&CurveRules::cubic_bspline(), &p, "b").is_ok());
    let id = Mat::identity(5);
    let e = Ifs::from_subdivision(vec![id], &bspline_points(), "id").unwrap_err();
    assert!(e.to_string().contains("not contractive"), "{e}");
    let mut bad = Mat::identity(5);
    bad.set(0, 1, 0.5);
    let e = Ifs::from_subdivision(vec![bad], &bspline_points(), "x").unwrap_err();
    assert!(e.to_string().contains("sums to"), "{e}");
    assert!(curve_ifs(&CurveRules::cubic_bspline(), &bspline_points()[..3], "b").is_err());
}

#[test]
fn koch_rules_and_locality() {
    let r = koch_reference();
    let ifs = koch_ifs(&r).unwrap();
    let b = ifs.blocks().unwrap();
    let t = 1.0 / 3.0;
    assert_mat_eq(
        &b[0],
        &mat(&[&[1., 0., 0., 0., 0.], &[2. * t, t, 0., 0., 0.], &[2. * t, 0., t, 0., 0.], &[t, 2. * t, 0., 0., 0.], &[0., 1., 0., 0., 0.]]),
        1e-12,
    );
    for (i, s) in b.iter().enumerate() {
        let (zero_cols, name) = if i < 2 { ([3, 4], "left") } else { ([0, 1], "right") };
        for r in 0..5 {
            for &c in &zero_cols {
                assert!(s.at(r, c).abs() < 1e-12, "{name} block {i} uses control point {c}");
            }
        }
    }
    // the reference control points give the classical Koch curve
    let std = Ifs::from_affine(&koch_maps(), "koch").unwrap();
    let a = ifs.polyline(6).unwrap();
    let s = std.iterate(&[vec![0.0, 0.0]], 6).unwrap();
    assert!(a[..a.len() - 2].iter().zip(&s).all(|(x, y)| (x - y).abs() < 1e-12));
    // moving P1 deforms the left half only
    let mut moved = r.clone();
    moved[1] = vec![0.3, 0.15];
    let m = koch_ifs(&moved).unwrap().polyline(6).unwrap();
    let half = (a.len() / 2 - 1) / 2 * 2; // first vertex of the right half
    let right: f64 = a[half..].iter().zip(&m[half..]).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    let left: f64 = a[..half].iter().zip(&m[..half]).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    assert!(right < 1e-12, "right half moved by {right}");
    assert!(left > 1e-2, "left half did not move");
}

#[test]
fn gasket_rules_match_section_4_2() {
    let ifs = gasket_ifs(&gasket_reference()).unwrap();
    let b = ifs.blocks().unwrap();
    let (a, c, m) = (3.0 / 8.0, 3.0 / 4.0, -1.0 / 8.0);
    let s1 = mat(&[
        &[1., 0., 0., 0., 0., 0.],
        &[a, c, m, 0., 0., 0.],
        &[0., 1., 0., 0., 0., 0.],
        &[0., 0.5, 0., 0., 0., 0.5],
        &[0., 0., 0., 0., 0., 1.],
        &[a, 0., 0., 0., m, c],
    ]);
    assert_mat_eq(&b[0], &s1, 1e-12);
    let s3 = mat(&[
        &[0., 0., 0., 0., 0., 1.],
        &[0., 0., 0., 0.5, 0., 0.5],
        &[0., 0., 0., 1., 0., 0.],
        &[0., 0., m, c, a, 0.],
        &[0., 0., 0., 0., 1., 0.],
        &[m, 0., 0., 0., a, c],
    ]);
    assert_mat_eq(&b[2], &s3, 1e-12);
    // the reference points draw the classical gasket
    let std = Ifs::from_affine(
        &[
            (vec![vec![0.5, 0.], vec![0., 0.5]], vec![0., 0.]),
            (vec![vec![0.5, 0.], vec![0., 0.5]], vec![0.5, 0.]),
            (vec![vec![0.5, 0.], vec![0., 0.5]], vec![0.25, 3f64.sqrt() / 4.0]),
        ],
        "g",
    )
    .unwrap();
    let x = ifs.iterate(&[vec![0.3, 0.2]], 7).unwrap();
    let y = std.iterate(&[vec![0.3, 0.2]], 7).unwrap();
    assert!(x.iter().zip(&y).all(|(p, q)| (p - q).abs() < 1e-9));
    let (v, t) = ifs.mesh(4).unwrap();
    assert_eq!(t.len(), 81);
    assert_eq!(v.len() / 2, 3 * (81 + 1) / 2); // (3^{k+1} + 3) / 2 vertices
}

#[test]
fn chaos_game_points_lie_on_the_curve() {
    let p = bspline_points();
    let ifs = curve_ifs(&CurveRules::cubic_bspline(), &p, "b").unwrap();
    let pts = ifs.chaos_game(2000, 7, None).unwrap();
    let poly = ifs.polyline(14).unwrap();
    assert!(hausdorff(&pts, &poly, 2) < 0.05);
    // one-sided: every chaos point within 1e-6 of the fine polyline vertices
    let again = ifs.chaos_game(2000, 7, None).unwrap();
    assert_eq!(pts, again);
    let w = ifs.chaos_game(100, 1, Some(&[1.0, 0.0])).unwrap();
    // only map 0: stays at its fixed point, the curve's start
    assert!((w[198] - poly[0]).abs() < 1e-12);
}

fn bumpy(xy: [f64; 2]) -> Vec<f64> {
    vec![xy[0], xy[1], 0.3 * (1.3 * xy[0]).sin() + 0.2 * (0.7 * xy[1] + 0.4).cos() + 0.05 * xy[0] * xy[1]]
}

#[test]
fn bicubic_mesh_is_the_tensor_spline() {
    let pts: Vec<Vec<f64>> = (0..4).flat_map(|j| (0..4).map(move |i| bumpy([i as f64, j as f64]))).collect();
    let ifs = bicubic_ifs(&pts).unwrap();
    assert_eq!(ifs.n_maps(), 4);
    let (v, t) = ifs.mesh(4).unwrap();
    assert_eq!(v.len() / 3, 17 * 17);
    assert_eq!(t.len(), 2 * 16 * 16);
    let basis = |t: f64| [(1.0 - t).powi(3) / 6.0, (3.0 * t.powi(3) - 6.0 * t * t + 4.0) / 6.0, (-3.0 * t.powi(3) + 3.0 * t * t + 3.0 * t + 1.0) / 6.0, t.powi(3) / 6.0];
    // every vertex is S(u, v) for some (u, v) on the 17×17 grid: check z given x, y parameters
    let mut worst = 0.0f64;
    for x in v.chunks_exact(3) {
        // x, y of this grid are affine in (u, v): x = i-parameter, y = j-parameter? no: z only
        let mut best = f64::INFINITY;
        for a in 0..=16 {
            for b in 0..=16 {
                let (bu, bv) = (basis(a as f64 / 16.0), basis(b as f64 / 16.0));
                let mut s = [0.0; 3];
                for j in 0..4 {
                    for i in 0..4 {
                        for c in 0..3 {
                            s[c] += bu[i] * bv[j] * pts[4 * j + i][c];
                        }
                    }
                }
                best = best.min(((x[0] - s[0]).powi(2) + (x[1] - s[1]).powi(2) + (x[2] - s[2]).powi(2)).sqrt());
            }
        }
        worst = worst.max(best);
    }
    assert!(worst < 1e-9, "{worst}");
}

#[test]
fn loop_and_sqrt3_hexagons() {
    let hex2: Vec<Vec<f64>> = hex_lattice(2).iter().map(|&p| bumpy(hex_to_xy([p[0] as f64, p[1] as f64]))).collect();
    let lp = loop_hexagon_ifs(&hex2).unwrap();
    assert_eq!(lp.n_maps(), 6);
    let (v, t) = lp.mesh(3).unwrap();
    let r = 8;
    assert_eq!(v.len() / 3, (1 + 3 * r * (r + 1)) as usize);
    assert_eq!(t.len(), 6 * (r * r) as usize);
    // the centre vertex is Loop's limit position ½ v + 1/12 Σ neighbours
    let mut want = [0.0; 3];
    for c in 0..3 {
        want[c] = 0.5 * hex2[0][c] + hex2[1..7].iter().map(|p| p[c] / 12.0).sum::<f64>();
    }
    let centre = v
        .chunks_exact(3)
        .map(|x| ((x[0] - want[0]).powi(2) + (x[1] - want[1]).powi(2) + (x[2] - want[2]).powi(2)).sqrt())
        .fold(f64::INFINITY, f64::min);
    assert!(centre < 1e-12, "{centre}");
    // plain subdivision converges to the same surface
    let (_, sub) = lattice_subdivide(&LatticeRules::Loop, &hex_lattice(2), &hex2, 5).unwrap();
    let flat: Vec<f64> = sub.concat();
    assert!(hausdorff(&flat, &v, 3) < 0.1);
    // the subset IFS (Fig. 9) stays on the surface
    let sub4 = lp.subset(&[0, 1, 3, 4]).unwrap();
    let (sv, _) = sub4.mesh(3).unwrap();
    for x in sv.chunks_exact(3) {
        let d = v.chunks_exact(3).map(|y| (x[0] - y[0]).abs() + (x[1] - y[1]).abs() + (x[2] - y[2]).abs()).fold(f64::INFINITY, f64::min);
        assert!(d < 1e-9);
    }
    // √3: needs the radius-4 net; radius 2 says so
    let hex4: Vec<Vec<f64>> = hex_lattice(4).iter().map(|&p| bumpy(hex_to_xy([p[0] as f64, p[1] as f64]))).collect();
    let e = sqrt3_hexagon_ifs(&hex2).unwrap_err();
    assert!(e.to_string().contains("outside the control net"), "{e}");
    let s3 = sqrt3_hexagon_ifs(&hex4).unwrap();
    assert_eq!(s3.n_maps(), 19);
    let (v3, t3) = s3.mesh(2).unwrap();
    assert_eq!(t3.len(), 6 * 81);
    assert_eq!(v3.len() / 3, 1 + 3 * 9 * 10);
    let (_, sub) = lattice_subdivide(&LatticeRules::Sqrt3, &hex_lattice(4), &hex4, 3).unwrap();
    let flat: Vec<f64> = sub.concat();
    // one-sided: mesh vertices are close to the subdivided net
    let near = v3
        .chunks_exact(3)
        .map(|x| flat.chunks_exact(3).map(|y| ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()).fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max);
    assert!(near < 0.05, "{near}");
}


use super::*;
use crate::primitives;

/// Positions and flat faces of a mesh's export.
fn polys(m: &Mesh) -> (Vec<DVec3>, Vec<i64>, Vec<i64>) {
    let (sizes, idx) = m.to_polygons().to_i64();
    (m.positions().to_vec(), sizes, idx)
}

/// Every corner gets its own vertex (an STL-like soup).
fn soup(pos: &[DVec3], sizes: &[i64], idx: &[i64]) -> (Vec<DVec3>, Vec<i64>, Vec<i64>) {
    (idx.iter().map(|&i| pos[i as usize]).collect(), sizes.to_vec(), (0..idx.len() as i64).collect())
}

fn reversed(sizes: &[i64], idx: &[i64], which: impl Fn(usize) -> bool) -> Vec<i64> {
    let mut out = Vec::new();
    let mut s = 0;
    for (f, &k) in sizes.iter().enumerate() {
        let mut face = idx[s..s + k as usize].to_vec();
        if which(f) {
            face.reverse();
        }
        out.extend(face);
        s += k as usize;
    }
    out
}

fn fixed(p: &[DVec3], s: &[i64], i: &[i64], close: bool) -> (Mesh, RepairReport) {
    let (m, r) = repair_mesh(p, s, i, None, close).expect("repair");
    m.validate().expect("valid");
    (m, r)
}

#[test]
fn cube_soup_welds_back_to_the_cube() {
    let (p, s, i) = polys(&primitives::cube());
    let (p, s, i) = soup(&p, &s, &i);
    let (m, r) = fixed(&p, &s, &i, false);
    assert_eq!((m.n_vertices(), m.n_edges(), m.n_faces(), m.genus()), (8, 12, 6, 0));
    assert_eq!(r.vertices_merged, 24 - 8);
    assert_eq!(r.boundary_loops, 0);
    assert!((m.signed_volume() - 8.0).abs() < 1e-12);
}

#[test]
fn flipped_faces_are_turned_to_the_majority_and_outward() {
    let (p, s, i) = polys(&primitives::torus(12, 8, 2.0, 0.5).unwrap());
    let some = reversed(&s, &i, |f| f % 3 == 0);
    let (m, r) = fixed(&p, &s, &some, false);
    assert_eq!(r.faces_flipped, s.len().div_ceil(3));
    assert_eq!(r.components_flipped, 0);
    assert_eq!(m.genus(), 1);
    assert!(m.signed_volume() > 0.0);
    let all = reversed(&s, &i, |_| true);
    assert!(inside_out_components(&Mesh::from_polygons(p.clone(), &s, &all, BuildOptions::default()).unwrap()).len() == 1);
    let (m2, r2) = fixed(&p, &s, &all, false);
    assert_eq!((r2.faces_flipped, r2.components_flipped), (0, 1));
    assert!((m2.signed_volume() - m.signed_volume()).abs() < 1e-9);
    assert!(inside_out_components(&m2).is_empty());
}

#[test]
fn duplicates_and_degenerates_are_dropped() {
    let (p, mut s, mut i) = polys(&primitives::cube());
    // face 0 again, rotated and reversed; face 1 again as is
    let f0: Vec<i64> = i[0..4].to_vec();
    i.extend([f0[2], f0[1], f0[0], f0[3]]);
    i.extend(i[4..8].to_vec());
    // a two-gon, a face with a repeated vertex collapsing to an edge, a collinear triangle
    let mut p = p;
    p.push((p[0] + p[1]) * 0.5);
    let mid = p.len() as i64 - 1;
    i.extend([0, 1, 0, 0, 1, 1, 0, mid, 1]);
    s.extend([4, 4, 2, 4, 3]);
    let (m, r) = fixed(&p, &s, &i, false);
    assert_eq!(r.duplicate_faces_dropped, 2);
    assert_eq!(r.degenerate_faces_dropped, 3);
    assert_eq!(r.unreferenced_vertices_removed, 1);
    assert_eq!((m.n_vertices(), m.n_faces()), (8, 6));
}

fn shifted(p: &[DVec3], d: DVec3) -> Vec<DVec3> {
    p.iter().map(|&q| q + d).collect()
}

/// Two cubes, the second moved by `d`, in one vertex list.
fn two_cubes(d: DVec3) -> (Vec<DVec3>, Vec<i64>, Vec<i64>) {
    let (p, s, i) = polys(&primitives::cube());
    let mut p2 = p.clone();
    p2.extend(shifted(&p, d));
    let mut s2 = s.clone();
    s2.extend(&s);
    let mut i2 = i.clone();
    i2.extend(i.iter().map(|&x| x + 8));
    (p2, s2, i2)
}

#[test]
fn cubes_sharing_a_vertex_are_split_into_two_components() {
    let (p, s, i) = two_cubes(DVec3::splat(2.0));
    let (m, r) = fixed(&p, &s, &i, false);
    assert_eq!(r.vertices_merged, 1);
    assert_eq!(r.pinched_vertices_split, 1);
    assert_eq!((m.n_vertices(), m.n_components(), m.component_genera()), (16, 2, vec![0, 0]));
}

#[test]
fn cubes_sharing_an_edge_keep_their_own_pairs() {
    let (p, s, i) = two_cubes(DVec3::new(2.0, 2.0, 0.0));
    let (m, r) = fixed(&p, &s, &i, false);
    assert_eq!(r.vertices_merged, 2);
    assert_eq!(r.non_manifold_edges_split, 1);
    assert_eq!(r.pinched_vertices_split, 2);
    assert_eq!((m.n_vertices(), m.n_components(), m.genus()), (16, 2, 0));
}

#[test]
fn a_fin_on_an_edge_is_detached_and_left_open() {
    let (mut p, mut s, mut i) = polys(&primitives::cube());
    // a triangle on the cube edge (0, 1), sticking out
    let (a, b) = (i[0], i[1]);
    p.push((p[a as usize] + p[b as usize]) * 0.5 + DVec3::new(0.0, 0.0, 5.0));
    i.extend([a, b, 8]);
    s.push(3);
    assert!(repair_mesh(&p, &s, &i, None, false).is_err());
    let (m, r) = fixed(&p, &s, &i, true);
    assert_eq!(r.non_manifold_edges_split, 1);
    assert_eq!(r.boundary_loops, 1);
    assert_eq!((m.n_components(), m.n_holes()), (2, 1));
}

#[test]
fn a_mobius_band_is_cut_once() {
    // 8 quads around a half-twisted loop
    let n = 8;
    let mut p = Vec::new();
    for k in 0..n {
        let t = std::f64::consts::TAU * k as f64 / n as f64;
        let (c, s) = (t.cos(), t.sin());
        let w = DVec3::new(c * (t / 2.0).cos(), s * (t / 2.0).cos(), (t / 2.0).sin()) * 0.3;
        let o = DVec3::new(2.0 * c, 2.0 * s, 0.0);
        p.push(o + w);
        p.push(o - w);
    }
    let mut i = Vec::new();
    for k in 0..n {
        let (a, b) = (2 * k as i64, 2 * k as i64 + 1);
        let (c, d) = if k + 1 < n { (a + 2, b + 2) } else { (1, 0) };
        i.extend([a, b, d, c]);
    }
    let s = vec![4i64; n];
    let (m, r) = fixed(&p, &s, &i, true);
    assert_eq!(r.non_orientable_edges_cut, 1);
    assert_eq!(r.boundary_loops, 1);
    assert_eq!(m.n_holes(), 1);
    assert_eq!(m.genus(), 0);
}

#[test]
fn tolerance_welds_a_jittered_soup() {
    let (p, s, i) = polys(&primitives::icosahedron());
    let (mut p, s, i) = soup(&p, &s, &i);
    for (k, q) in p.iter_mut().enumerate() {
        *q += DVec3::splat(((k * 7919) % 13) as f64 * 1e-13);
    }
    let exact = repair(&p, &s, &i, Some(0.0)).unwrap();
    assert_eq!(exact.report.boundary_loops, 20);
    let (m, r) = repair_mesh(&p, &s, &i, Some(1e-9), false).unwrap();
    assert_eq!((m.n_vertices(), m.n_faces(), m.genus()), (12, 20, 0));
    assert_eq!(r.tolerance, 1e-9);
}

#[test]
fn bad_input_is_named() {
    let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let e = repair(&p, &[3], &[0, 1, 3], None).unwrap_err();
    assert!(matches!(e, MeshError::IndexOutOfRange { face: 0, position: 2, index: 3, .. }), "{e}");
    assert!(matches!(repair(&p, &[3, 0], &[0, 1, 2], None).unwrap_err(), MeshError::EmptyFace { face: 1 }));
    assert!(repair(&p, &[i64::MAX, i64::MAX, 3], &[0, 1, 2], None).is_err());
    assert!(repair(&p, &[3], &[0, 1, 2], Some(-1.0)).unwrap_err().to_string().contains("tolerance"));
    assert!(repair(&p, &[3], &[0, 1, 2], Some(f64::NAN)).is_err());
    let bad = vec![DVec3::ZERO, DVec3::X, DVec3::new(f64::NAN, 0.0, 0.0)];
    assert!(matches!(repair(&bad, &[3], &[0, 1, 2], None).unwrap_err(), MeshError::NonFinite { vertex: 2 }));
    // an open triangle: a boundary loop, an error unless closed
    assert_eq!(repair(&p, &[3], &[0, 1, 2], None).unwrap().report.boundary_loops, 1);
    assert!(matches!(repair_mesh(&p, &[3], &[0, 1, 2], None, false).unwrap_err(), MeshError::Boundary { .. }));
}

#[test]
fn canonical_cycles_match_up_to_rotation_and_direction() {
    let read = |f: &[u32]| {
        let (s, d) = canonical(f);
        let k = f.len();
        (0..k).map(|i| if d { f[(s + i) % k] } else { f[(s + k - i) % k] }).collect::<Vec<_>>()
    };
    let a = read(&[5, 0, 3, 0, 2]);
    assert_eq!(a, read(&[3, 0, 2, 5, 0]));
    assert_eq!(a, read(&[2, 0, 3, 0, 5]));
    assert_ne!(a, read(&[5, 0, 2, 0, 3]));
    assert_eq!(a, vec![0, 2, 5, 0, 3]);
    assert_eq!(least_rotation(6, |i| [1u32, 0, 1, 0, 1, 0][i % 6]) % 2, 1);
}

/// By hand: `cargo test --release big_soup_timing -- --ignored --nocapture`
/// (a 1.3M-triangle soup of a quad torus).
#[test]
#[ignore]
fn big_soup_timing() {
    let m = primitives::torus(1024, 640, 2.0, 0.5).unwrap();
    let (p, s, i) = polys(&m);
    // triangulate quads into a soup
    let mut tp = Vec::new();
    for f in 0..s.len() {
        let q = &i[4 * f..4 * f + 4];
        for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            tp.extend(t.iter().map(|&x| p[x as usize]));
        }
    }
    let n = tp.len() / 3;
    let sizes = vec![3i64; n];
    let idx: Vec<i64> = (0..tp.len() as i64).collect();
    let t = std::time::Instant::now();
    let r = repair(&tp, &sizes, &idx, None).unwrap();
    eprintln!("{n} triangles: repair {:?}", t.elapsed());
    let t = std::time::Instant::now();
    let m = Mesh::from_polygons(r.positions, &r.sizes, &r.indices, BuildOptions::default()).unwrap();
    eprintln!("from_polygons {:?}", t.elapsed());
    assert_eq!((m.n_vertices(), m.genus()), (1024 * 640, 1));
}

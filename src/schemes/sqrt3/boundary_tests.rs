//! Kobbelt's boundary rule of √3 on the open test meshes: counts, χ,
//! boundary loops, S·P, origins, and the trisected boundary after two steps.

use super::*;
use crate::schemes::hosts::test_meshes::*;
use glam::DVec3;

fn req(level: usize) -> Request<'static> {
    Request { level, ..full_request() }
}

fn n_boundary_edges(m: &Mesh) -> usize {
    (0..m.n_halfedges()).filter(|&h| m.f_hole[m.he_face[h] as usize]).count()
}

/// The boundary loops as point lists, in hole order.
fn boundary_points(m: &Mesh) -> Vec<Vec<DVec3>> {
    (0..m.n_faces())
        .filter(|&f| m.f_hole[f])
        .map(|f| m.face_vertices(crate::mesh::FaceId(f as u32)).map(|v| m.pos[v.idx()]).collect())
        .collect()
}

#[test]
fn odd_then_even_counts_chi_and_loops() {
    for (name, m) in open_meshes().into_iter().chain([("grid2", open_grid(2))]) {
        let (v, e, f) = counts(&m);
        let (h, eb, holes) = (2 * e, n_boundary_edges(&m), m.n_holes());
        let fr = f - holes;
        let a = sqrt3_level(&m, &req(0)).unwrap();
        check_level(name, &m, &a);
        assert_eq!(counts(&a.mesh), (v + fr, 3 * e - eb, h - eb + holes), "{name} odd");
        assert_eq!(n_boundary_edges(&a.mesh), eb, "{name}: odd steps keep the boundary edges");
        assert_eq!(open_euler(&a.mesh), open_euler(&m), "{name} χ");
        assert_eq!(a.mesh.n_holes(), holes, "{name}");
        // boundary vertices do not move in odd steps
        assert_eq!(boundary_points(&a.mesh), boundary_points(&m), "{name}");
        let (v1, e1, f1) = counts(&a.mesh);
        let fr1 = f1 - holes;
        let b = sqrt3_level(&a.mesh, &req(1)).unwrap();
        check_level(name, &a.mesh, &b);
        assert_eq!(counts(&b.mesh), (v1 + fr1 + eb, 3 * e1, 2 * e1 - eb + holes), "{name} even");
        assert_eq!(n_boundary_edges(&b.mesh), 3 * eb, "{name}: even steps trisect the boundary");
        assert_eq!(open_euler(&b.mesh), open_euler(&m), "{name} χ");
        assert!((0..b.mesh.n_faces()).all(|f| b.mesh.f_hole[f] || b.mesh.face_degree(crate::mesh::FaceId(f as u32)) == 3), "{name}: triangles");
    }
}

/// Two levels on a flat open grid: the boundary stays on its line and is
/// trisected with the ternary cubic B-spline rule (reproduces a straight
/// line with uniform spacing away from the corners).
#[test]
fn straight_boundary_is_trisected_uniformly() {
    let n = 6;
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            pos.push(DVec3::new(i as f64, j as f64, 0.0));
        }
    }
    let mut idx = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = (j * (n + 1) + i) as i64;
            let w = (n + 1) as i64;
            idx.extend_from_slice(&[a, a + 1, a + w + 1, a + w]);
        }
    }
    let opts = crate::mesh::BuildOptions { close_boundaries: true, ..Default::default() };
    let m = Mesh::from_polygons(pos, &vec![4i64; n * n], &idx, opts).unwrap();
    let a = sqrt3_level(&m, &req(0)).unwrap().mesh;
    let b = sqrt3_level(&a, &req(1)).unwrap().mesh;
    let loops = boundary_points(&b);
    assert_eq!(loops.len(), 1);
    // on the bottom side y = 0, between x = 1 and x = 5 (away from the
    // corners, where the curve rule sees a kink), points are 1/3 apart
    let mut xs: Vec<f64> = loops[0].iter().filter(|p| p.y.abs() < 1e-12 && p.x > 0.99 && p.x < 5.01).map(|p| p.x).collect();
    xs.sort_by(f64::total_cmp);
    assert_eq!(xs.len(), 13, "{xs:?}");
    for w in xs.windows(2) {
        assert!((w[1] - w[0] - 1.0 / 3.0).abs() < 1e-12, "{xs:?}");
    }
    // and every boundary point of the flat grid stays in its plane
    assert!(b.pos.iter().all(|p| p.z.abs() < 1e-12));
}

#[test]
fn even_step_refuses_a_face_with_two_boundary_edges() {
    // the grid's corner quads have two boundary edges (and are quads)
    match sqrt3_level(&open_grid(3), &req(1)) {
        Err(crate::error::MeshError::Precondition(msg)) => assert!(msg.starts_with("sqrt3") && msg.contains("iterations=2"), "{msg}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn origins_name_the_boundary() {
    let m = cube_with_hole();
    let a = sqrt3_level(&m, &req(0)).unwrap();
    let b = sqrt3_level(&a.mesh, &req(1)).unwrap();
    let o = b.origins.as_ref().unwrap();
    // the two new points of every boundary edge come from that edge
    let nb = n_boundary_edges(&a.mesh);
    let edge_points = o.vertex_kind.iter().filter(|&&k| k == EDGE).count();
    assert_eq!(edge_points, 2 * nb);
    // every hole face of the output comes from the hole of the input
    for f in 0..b.mesh.n_faces() {
        if b.mesh.f_hole[f] {
            assert_eq!(o.face_kind[f], FACE);
            assert!(a.mesh.f_hole[o.face[f] as usize]);
        }
    }
    // boundary edges of the output come from boundary edges of the input
    for h in 0..b.mesh.n_halfedges() {
        if b.mesh.f_hole[b.mesh.he_face[h] as usize] {
            let e = h >> 1;
            assert_eq!(o.edge_kind[e], EDGE);
            let ie = o.edge[e] as usize;
            let boundary = [2 * ie, 2 * ie + 1].iter().any(|&k| a.mesh.f_hole[a.mesh.he_face[k] as usize]);
            assert!(boundary, "output boundary edge {e} from interior input edge {ie}");
        }
    }
}

#[test]
fn closed_meshes_unchanged_by_the_level_index() {
    let m = crate::primitives::icosahedron();
    let a = sqrt3_level(&m, &req(0)).unwrap().mesh;
    let b = sqrt3_level(&m, &req(1)).unwrap().mesh;
    assert_eq!(a.pos, b.pos);
    assert_eq!(a.to_polygons(), b.to_polygons());
}

/// The columns written from the corner groups equal the list build
/// (`Mesh::from_trusted_twins` over the same groups' corner and twin lists)
/// element for element, at both parities, with and without the
/// correspondence; a torus with many holes too.
#[test]
fn direct_columns_equal_the_list_build() {
    let mut cases: Vec<(String, Mesh)> = open_meshes().into_iter().map(|(n, m)| (n.to_string(), m)).collect();
    cases.push(("grid2".into(), open_grid(2)));
    let t = crate::primitives::torus(12, 8, 3.0, 1.0).unwrap();
    // faces of a torus removed apart from each other: 16 holes, and one of two faces
    let keep: Vec<bool> = (0..t.n_faces()).map(|f| !((f / 8) % 3 == 1 && (f % 8) % 4 == 1) && f != 10).collect();
    let p = t.to_polygons();
    let (mut sizes, mut idx, mut at) = (Vec::new(), Vec::new(), 0usize);
    for (f, &n) in p.sizes.iter().enumerate() {
        if keep[f] {
            sizes.push(n as i64);
            idx.extend(p.indices[at..at + n as usize].iter().map(|&i| i as i64));
        }
        at += n as usize;
    }
    let opts = crate::BuildOptions { close_boundaries: true, ..Default::default() };
    cases.push(("torus with holes".into(), Mesh::from_polygons(t.positions().to_vec(), &sizes, &idx, opts).unwrap()));
    let by_lists = |m: &Mesh, r: &Request| {
        super::boundary::LIST_BUILD.with(|b| b.set(true));
        let l = sqrt3_level(m, r);
        super::boundary::LIST_BUILD.with(|b| b.set(false));
        l.unwrap()
    };
    for (name, m) in cases {
        for r in [req(0), Request { level: 0, ..Request::plain() }] {
            let (a, b) = (sqrt3_level(&m, &r).unwrap(), by_lists(&m, &r));
            assert_eq!(a.mesh, b.mesh, "{name} odd");
            assert_eq!(a.origins, b.origins, "{name} odd origins");
            // the even step on the odd step's output
            let r1 = Request { level: 1, ..r };
            let (c, d) = (sqrt3_level(&a.mesh, &r1).unwrap(), by_lists(&a.mesh, &r1));
            assert_eq!(c.mesh, d.mesh, "{name} even");
            assert_eq!(c.origins, d.origins, "{name} even origins");
        }
    }
}

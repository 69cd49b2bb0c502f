//! Operator contracts and invariants on degenerate and random cases.

use super::*;
use crate::error::MeshError;
use crate::primitives;

/// SplitMix64: a tiny deterministic generator for the random sequences.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

#[derive(Debug, PartialEq, Clone, Copy)]
struct Topo {
    v: usize,
    e: usize,
    f: usize,
    chi: i64,
    comps: usize,
    genus: i64,
}

fn topo(m: &Mesh) -> Topo {
    Topo {
        v: m.n_vertices(),
        e: m.n_edges(),
        f: m.n_faces(),
        chi: m.euler_characteristic(),
        comps: m.n_components(),
        genus: m.genus(),
    }
}

fn random_corner(m: &Mesh, rng: &mut Rng) -> Corner {
    let f = FaceId::new(rng.below(m.n_faces()));
    let k = rng.below(m.face_degree(f));
    m.corner(f, k).unwrap()
}

/// Applies one random operator and checks its contract.
fn random_step(m: &mut Mesh, rng: &mut Rng) {
    let before = topo(m);
    match rng.below(10) {
        0 => {
            let (v, f) = m.create_vertex(DVec3::new(rng.below(7) as f64, 0.0, 1.0)).unwrap();
            assert_eq!(m.point_sphere_face(v), Some(f));
            let a = topo(m);
            assert_eq!((a.v, a.e, a.f, a.comps, a.genus), (before.v + 1, before.e, before.f + 1, before.comps + 1, before.genus));
        }
        1 => {
            let points: Vec<VertexId> = m.vertices().filter(|&v| m.point_sphere_face(v).is_some()).collect();
            let v = m.vertices().nth(rng.below(m.n_vertices())).unwrap();
            if points.is_empty() {
                if m.valence(v) > 0 {
                    assert!(matches!(m.delete_vertex(v), Err(MeshError::Precondition(_))));
                    assert_eq!(topo(m), before, "a refused DeleteVertex changes nothing");
                }
                return;
            }
            m.delete_vertex(points[rng.below(points.len())]).unwrap();
            let a = topo(m);
            assert_eq!((a.v, a.f, a.comps, a.genus), (before.v - 1, before.f - 1, before.comps - 1, before.genus));
        }
        2..=6 => {
            let (c1, c2) = (random_corner(m, rng), random_corner(m, rng));
            let same_face = m.corner_face(c1) == m.corner_face(c2);
            let (labels, _) = m.vertex_components();
            let same_comp = labels[m.corner_vertex(c1).idx()] == labels[m.corner_vertex(c2).idx()];
            let e = m.insert_edge(c1, c2).unwrap();
            assert_eq!(e.idx(), before.e);
            assert_eq!(m.vertex(e.halfedge()), m.corner_vertex(c1));
            let a = topo(m);
            assert_eq!(a.e, before.e + 1);
            if same_face {
                assert_eq!((a.f, a.chi, a.comps, a.genus), (before.f + 1, before.chi, before.comps, before.genus));
            } else if same_comp {
                assert_eq!((a.f, a.comps, a.genus), (before.f - 1, before.comps, before.genus + 1));
            } else {
                assert_eq!((a.f, a.comps, a.genus), (before.f - 1, before.comps - 1, before.genus));
            }
        }
        _ => {
            if m.n_edges() == 0 {
                return;
            }
            let e = EdgeId::new(rng.below(m.n_edges()));
            let same_face = m.face(e.halfedge()) == m.face(e.halfedge().twin());
            m.delete_edge(e).unwrap();
            let a = topo(m);
            assert_eq!(a.e, before.e - 1);
            if !same_face {
                assert_eq!((a.f, a.chi, a.comps, a.genus), (before.f - 1, before.chi, before.comps, before.genus));
            } else {
                assert_eq!((a.f, a.chi), (before.f + 1, before.chi + 2));
                let cut_handle = a.genus == before.genus - 1 && a.comps == before.comps;
                let split = a.genus == before.genus && a.comps == before.comps + 1;
                assert!(cut_handle || split, "{before:?} -> {a:?}");
            }
        }
    }
}

#[test]
fn random_operator_sequences_keep_contracts() {
    let starts: Vec<Mesh> = vec![
        Mesh::new(),
        primitives::tetrahedron(),
        primitives::cube(),
        primitives::torus(4, 3, 2.0, 0.5).unwrap(),
        primitives::genus_surface(2).unwrap(),
    ];
    for (k, start) in starts.iter().enumerate() {
        for seed in 0..40u64 {
            let mut rng = Rng(seed * 31 + k as u64);
            let mut m = start.clone();
            if m.n_faces() == 0 {
                m.create_vertex(DVec3::ZERO).unwrap();
            }
            for step in 0..60 {
                if m.n_faces() == 0 {
                    m.create_vertex(DVec3::ZERO).unwrap();
                }
                random_step(&mut m, &mut rng);
                if let Err(e) = m.validate() {
                    panic!("start {k} seed {seed} step {step}: {e}");
                }
                // rebuilding from the exported twins gives the same topology
                let (sizes, idx) = m.to_polygons().to_i64();
                let rebuilt = Mesh::from_polygons(
                    m.positions().to_vec(),
                    &sizes,
                    &idx,
                    BuildOptions { allow_multi_edges: true, close_boundaries: false },
                );
                if let Ok(r) = rebuilt {
                    assert_eq!((r.n_vertices(), r.n_edges(), r.n_faces()), (m.n_vertices(), m.n_edges(), m.n_faces()));
                }
            }
        }
    }
}

#[test]
fn insert_then_delete_is_identity_on_counts() {
    let mut m = primitives::cube();
    let before = topo(&m);
    let c1 = m.corner(FaceId(0), 0).unwrap();
    let c2 = m.corner(FaceId(0), 2).unwrap();
    let e = m.insert_edge(c1, c2).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_size_histogram(), [(3, 2), (4, 5)].into_iter().collect());
    m.delete_edge(e).unwrap();
    m.validate().unwrap();
    assert_eq!(topo(&m), before);
    // a handle between two opposite faces, then cut it again
    let c1 = m.corner(FaceId(0), 0).unwrap();
    let c2 = m.corner(FaceId(1), 0).unwrap();
    let e = m.insert_edge(c1, c2).unwrap();
    assert_eq!(m.genus(), 1);
    m.delete_edge(e).unwrap();
    assert_eq!(topo(&m), before);
}

#[test]
fn point_spheres_self_loops_and_two_gons() {
    let mut m = Mesh::new();
    let (v, f) = m.create_vertex(DVec3::ZERO).unwrap();
    m.validate().unwrap();
    assert_eq!(topo(&m), Topo { v: 1, e: 0, f: 1, chi: 2, comps: 1, genus: 0 });
    assert_eq!(m.to_polygons().sizes, vec![1]);
    // a self-loop on a point-sphere: two one-gons
    let e = m.insert_edge(Corner::Point(v), Corner::Point(v)).unwrap();
    m.validate().unwrap();
    assert_eq!((m.n_faces(), m.n_self_loops(), m.genus()), (2, 1, 0));
    assert_eq!(m.face_size_histogram(), [(1, 2)].into_iter().collect());
    m.delete_edge(e).unwrap();
    m.validate().unwrap();
    assert_eq!(m.point_sphere_face(v), Some(f));
    // two point-spheres joined: a sphere with one edge and one two-sided face
    let (w, _) = m.create_vertex(DVec3::X).unwrap();
    assert_eq!(m.n_components(), 2);
    let e = m.insert_edge(Corner::Point(v), Corner::Point(w)).unwrap();
    m.validate().unwrap();
    assert_eq!(topo(&m), Topo { v: 2, e: 1, f: 1, chi: 2, comps: 1, genus: 0 });
    // a second edge between the same vertices: two two-gons (a multi-edge)
    let h = m.vertex_halfedge(v).unwrap();
    let h2 = m.vertex_halfedge(w).unwrap();
    m.insert_edge(Corner::Halfedge(h), Corner::Halfedge(h2)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.face_size_histogram(), [(2, 2)].into_iter().collect());
    // deleting the first edge merges the two two-gons back
    m.delete_edge(e).unwrap();
    m.validate().unwrap();
    assert_eq!((m.n_edges(), m.n_faces()), (1, 1));
    // deleting the last leaves two point-spheres
    m.delete_edge(EdgeId(0)).unwrap();
    m.validate().unwrap();
    assert_eq!((m.n_vertices(), m.n_faces(), m.n_components()), (2, 2, 2));
    m.delete_vertex(v).unwrap();
    m.delete_vertex(VertexId(0)).unwrap();
    assert_eq!(m, Mesh::new());
}

#[test]
fn delete_vertex_refuses_vertices_with_edges() {
    let mut m = primitives::cube();
    let before = m.clone();
    assert!(matches!(m.delete_vertex(VertexId(0)), Err(MeshError::Precondition(_))));
    assert_eq!(m, before);
}

#[test]
fn self_loop_round_trips_through_polygons() {
    let mut m = primitives::cube();
    let c = m.corner(FaceId(2), 1).unwrap();
    m.insert_edge(c, c).unwrap();
    m.validate().unwrap();
    let (sizes, idx) = m.to_polygons().to_i64();
    let r = Mesh::from_polygons(m.positions().to_vec(), &sizes, &idx, BuildOptions::default()).unwrap();
    assert_eq!(topo(&r), topo(&m));
    assert_eq!(r.n_self_loops(), 1);
    // triangulation drops the loop and its one-gon and stays closed
    let (t, _) = r.triangles();
    assert_eq!(t.len(), 12);
}

#[test]
fn construction_errors_name_the_element() {
    let p = |n: usize| (0..n).map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0)).collect::<Vec<_>>();
    let o = BuildOptions::default();
    // tetrahedron with one face flipped
    let e = Mesh::from_polygons(p(4), &[3; 4], &[0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 2, 3], o).unwrap_err();
    assert!(matches!(e, MeshError::InconsistentOrientation { .. }), "{e}");
    // three faces on one edge (a fin)
    let e = Mesh::from_polygons(p(5), &[3; 3], &[0, 1, 2, 1, 0, 3, 0, 1, 4], o).unwrap_err();
    assert!(matches!(e, MeshError::NonManifoldEdge { a: 0, b: 1, .. }), "{e}");
    // two tetrahedra sharing a vertex: a pinch
    let t = [0i64, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3];
    let mut idx = t.to_vec();
    idx.extend(t.iter().map(|&i| if i == 0 { 0 } else { i + 3 }));
    let e = Mesh::from_polygons(p(7), &[3; 8], &idx, o).unwrap_err();
    assert_eq!(e, MeshError::NonManifoldVertex { vertex: 0 });
    // empty face, out of range, NaN, open
    assert_eq!(Mesh::from_polygons(p(3), &[3, 0], &[0, 1, 2], o).unwrap_err(), MeshError::EmptyFace { face: 1 });
    assert!(matches!(
        Mesh::from_polygons(p(3), &[3], &[0, 1, 3], o).unwrap_err(),
        MeshError::IndexOutOfRange { face: 0, position: 2, index: 3, .. }
    ));
    let mut q = p(4);
    q[2].y = f64::NAN;
    assert_eq!(Mesh::from_polygons(q, &[3; 4], &t[..12], o).unwrap_err(), MeshError::NonFinite { vertex: 2 });
    assert!(matches!(Mesh::from_polygons(p(3), &[3], &[0, 1, 2], o).unwrap_err(), MeshError::Boundary { .. }));
    let closed = Mesh::from_polygons(p(3), &[3], &[0, 1, 2], BuildOptions { close_boundaries: true, ..o }).unwrap();
    closed.validate().unwrap();
    assert_eq!((closed.n_faces(), closed.n_holes(), closed.genus()), (2, 1, 0));
    assert_eq!(closed.to_polygons().sizes, vec![3]);
}

#[test]
fn open_grid_is_capped_per_boundary_loop() {
    // an annulus (square with a square hole): two boundary loops, genus 0 after capping
    let mut pos = Vec::new();
    for j in 0..4 {
        for i in 0..4 {
            pos.push(DVec3::new(i as f64, j as f64, 0.0));
        }
    }
    let id = |i: i64, j: i64| j * 4 + i;
    let mut idx = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            if (i, j) != (1, 1) {
                idx.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    let m = Mesh::from_polygons(pos, &[4; 8], &idx, BuildOptions { close_boundaries: true, ..Default::default() }).unwrap();
    m.validate().unwrap();
    assert_eq!((m.n_holes(), m.genus(), m.n_components()), (2, 0, 1));
}

#[test]
fn ear_clipping_handles_a_star() {
    // a planar 5-pointed star (10 corners): a fan from corner 0 would leave the polygon
    let mut pos = Vec::new();
    for k in 0..10 {
        let r = if k % 2 == 0 { 1.0 } else { 0.4 };
        let a = std::f64::consts::TAU * k as f64 / 10.0;
        pos.push(DVec3::new(r * a.cos(), r * a.sin(), 0.0));
    }
    let top: Vec<i64> = (0..10).collect();
    let bottom: Vec<i64> = (0..10).rev().collect();
    let mut idx = top.clone();
    idx.extend(bottom);
    // the star's two sides: a flat sphere; valid topologically
    let m = Mesh::from_polygons(pos.clone(), &[10, 10], &idx, BuildOptions::default()).unwrap();
    let (tris, _) = m.triangles();
    // both sides need every tip's chord, so the second side is fanned
    // around an added point (src/geometry/triangulate/)
    assert_eq!(tris.len(), 8 + 10);
    // every triangle of the top face has positive area and lies inside the star
    let area: f64 = tris[..8]
        .iter()
        .map(|t| {
            let (a, b, c) = (pos[t[0] as usize], pos[t[1] as usize], pos[t[2] as usize]);
            let z = (b - a).cross(c - a).z;
            assert!(z > 0.0, "clipped triangle is inverted");
            z / 2.0
        })
        .sum();
    let exact: f64 = (0..10).map(|k| pos[k].truncate().perp_dot(pos[(k + 1) % 10].truncate()) / 2.0).sum();
    assert!((area - exact).abs() < 1e-12, "{area} vs {exact}");
}

#[test]
fn int32_polygons_build_what_int64_polygons_build() {
    // every corpus mesh and the open cube through both index types, with and
    // without multi-edges allowed, then the same refusals
    let open = ("open", crate::schemes::hosts::test_meshes::cube_with_hole());
    let mut built = 0;
    for (name, m) in crate::schemes::hosts::test_meshes::corpus().into_iter().chain([open]) {
        let (sizes, idx) = m.to_polygons().to_i64();
        let idx32: Vec<i32> = idx.iter().map(|&i| i as i32).collect();
        for allow_multi_edges in [false, true] {
            let opts = BuildOptions { close_boundaries: true, allow_multi_edges };
            let wide = Mesh::from_polygons(m.positions().to_vec(), &sizes, &idx, opts);
            let narrow = Mesh::from_polygons_i32(m.positions().to_vec(), &sizes, &idx32, opts);
            match (wide, narrow) {
                (Ok(a), Ok(b)) => {
                    assert_eq!(a, b, "{name}");
                    built += 1;
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{name}"),
                (a, b) => panic!("{name}: {:?} against {:?}", a.map(|_| ()), b.map(|_| ())),
            }
        }
    }
    assert!(built >= 10, "only {built} meshes built");
    let cube = primitives::cube();
    let (sizes, idx) = cube.to_polygons().to_i64();
    for bad in [8i64, -1] {
        let mut wide = idx.clone();
        wide[5] = bad;
        let narrow: Vec<i32> = wide.iter().map(|&i| i as i32).collect();
        let a = Mesh::from_polygons(cube.positions().to_vec(), &sizes, &wide, BuildOptions::default()).unwrap_err().to_string();
        let b = Mesh::from_polygons_i32(cube.positions().to_vec(), &sizes, &narrow, BuildOptions::default()).unwrap_err().to_string();
        assert_eq!(a, b);
        assert!(a.contains(&format!("index {bad}")), "{a}");
    }
}

#[test]
fn multi_edges_found_per_vertex_as_by_sorting_every_edge() {
    // the reference: every edge's vertex pair (self-loops aside), sorted
    let reference = |m: &Mesh| {
        let mut pairs: Vec<(u32, u32)> = m
            .edges()
            .filter_map(|e| {
                let h = e.halfedge();
                let (a, b) = (m.vertex(h).0, m.head(h).0);
                (a != b).then_some((a.min(b), a.max(b)))
            })
            .collect();
        pairs.sort_unstable();
        pairs.windows(2).any(|w| w[0] == w[1])
    };
    let mut seen = [0usize; 2];
    let mut check = |name: &str, m: &Mesh| {
        let found = m.has_multi_edges();
        assert_eq!(found, reference(m), "{name}");
        seen[found as usize] += 1;
    };
    let open = ("open".to_string(), crate::schemes::hosts::test_meshes::cube_with_hole());
    for (name, m) in crate::schemes::hosts::test_meshes::corpus().into_iter().map(|(n, m)| (n.to_string(), m)).chain([open]) {
        check(&name, &m);
    }
    // valence above 16: a pyramid over a 20-gon (apex and base of valence 20, no
    // multi-edge) and a beach ball of 20 two-gons (its two poles joined 20 times)
    let n = 20;
    let mut pos: Vec<DVec3> = (0..n).map(|i| DVec3::new((i as f64).cos(), (i as f64).sin(), 0.0)).collect();
    pos.push(DVec3::Z);
    let mut sizes = vec![n as i64];
    let mut idx: Vec<i64> = (0..n as i64).rev().collect();
    for i in 0..n as i64 {
        sizes.push(3);
        idx.extend([i, (i + 1) % n as i64, n as i64]);
    }
    check("pyramid", &Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap());
    // two-gon i is corners 2i (north to south) and 2i + 1 (south to north); its
    // north-to-south side is glued to the next two-gon's south-to-north side
    let mut twins = vec![0i64; 2 * n];
    for i in 0..n {
        let j = 2 * ((i + 1) % n) + 1;
        (twins[2 * i], twins[j]) = (j as i64, 2 * i as i64);
    }
    let ball = Mesh::from_corner_twins_i64(vec![DVec3::Z, -DVec3::Z], &vec![2; n], &[0, 1].repeat(n), &twins).unwrap();
    assert_eq!((ball.n_edges(), ball.genus()), (n, 0));
    check("beach ball", &ball);
    assert!(seen[0] >= 3 && seen[1] >= 2, "{seen:?}");
}

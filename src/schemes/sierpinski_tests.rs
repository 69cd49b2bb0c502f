use super::*;
use crate::mesh::{BuildOptions, FaceId};
use crate::primitives;

fn measured(m: &Mesh) -> (u64, u64, u64, u64, i64) {
    (m.n_vertices() as u64, m.n_edges() as u64, m.n_faces() as u64, m.n_self_loops() as u64, m.genus())
}
fn predicted(c: &SierpinskiCounts) -> (u64, u64, u64, u64, i64) {
    (c.vertices, c.edges, c.faces, c.self_loops, c.genus())
}

/// Iterates `n` times, checking validity and the recurrence at each step,
/// and the closed forms when D = 0.
fn check_iterations(m0: &Mesh, n: usize) -> Mesh {
    let c0 = SierpinskiCounts::of(m0).unwrap();
    let mut m = m0.clone();
    for i in 1..=n {
        m = sierpinski(&m).unwrap();
        m.validate().unwrap();
        let c = c0.after(i);
        assert_eq!(measured(&m), predicted(&c), "iteration {i}");
        assert_eq!(SierpinskiCounts::of(&m).unwrap(), c, "iteration {i}: K, D, F0");
        assert_eq!(m.n_components() as u64, c0.components);
        if c0.lone_cones == 0 {
            let n0 = (c0.edges - c0.self_loops) as i64;
            let s = (4i64.pow(i as u32) - 1) / 3;
            let (v, e) = (c0.vertices as i64, c0.edges as i64);
            let (k, f0) = (c0.cones as i64, c0.loop_faces as i64);
            assert_eq!(m.n_vertices() as i64, v + n0 * s);
            assert_eq!(m.n_edges() as i64, e + 4 * n0 * s);
            assert_eq!(m.n_faces() as i64, k + f0 + 2 * n0 * s);
            assert_eq!(m.n_self_loops() as i64, c0.self_loops as i64 + n0 * s);
            assert_eq!(m.euler_characteristic(), v - e + k + f0 - n0 * s);
        }
    }
    m
}

#[test]
fn tetrahedron_genus_anchor() {
    let mut m = primitives::tetrahedron();
    let mut genera = Vec::new();
    for _ in 0..3 {
        m = sierpinski(&m).unwrap();
        genera.push(m.genus());
    }
    assert_eq!(genera, vec![3, 15, 63]);
    // 4^3 tetrahedra: every face a triangle-looking face (3 + self-loops)
    assert_eq!(m.n_faces(), 256);
}

#[test]
fn platonic_torus_genus3_six_iterations() {
    for m in [
        primitives::tetrahedron(),
        primitives::cube(),
        primitives::octahedron(),
        primitives::dodecahedron(),
        primitives::icosahedron(),
        primitives::torus(5, 3, 2.0, 0.5).unwrap(),
        primitives::genus_surface(3).unwrap(),
    ] {
        let c = SierpinskiCounts::of(&m).unwrap();
        assert_eq!((c.cones, c.loop_faces, c.lone_cones), (m.n_vertices() as u64, 0, 0));
        check_iterations(&m, 6);
    }
}

/// Two vertices, `n` edges, `n` two-gons (a hosohedron).
fn hosohedron(n: u32) -> Mesh {
    let pos = vec![DVec3::new(0., 0., 1.), DVec3::new(0., 0., -1.)];
    let cv: Vec<u32> = (0..n).flat_map(|_| [0, 1]).collect();
    // side 0 -> 1 of face k is twin to side 1 -> 0 of face k + 1
    let tw: Vec<u32> = (0..n).flat_map(|k| [2 * ((k + 1) % n) + 1, 2 * ((k + n - 1) % n)]).collect();
    Mesh::from_corner_twins(pos, &vec![2; n as usize], &cv, &tw).unwrap()
}

#[test]
fn two_gons_and_multi_edges() {
    for n in [2, 3, 5] {
        let m = hosohedron(n);
        m.validate().unwrap();
        assert_eq!((m.n_vertices(), m.n_edges(), m.n_faces(), m.genus()), (2, n as usize, n as usize, 0));
        check_iterations(&m, 6);
    }
}

/// The cube with a self-loop bounding a one-gon in one face and a
/// self-loop handle between two faces at another vertex.
fn cube_with_loops() -> Mesh {
    let mut m = primitives::cube();
    let h = m.face_halfedge(FaceId(0)).unwrap();
    m.insert_edge(Corner::Halfedge(h), Corner::Halfedge(h)).unwrap();
    // a handle: self-loop between two corners of one vertex in different faces
    let v = m.head(h);
    let outs: Vec<_> = m.vertex_halfedges(v).collect();
    let (a, b) = (outs[0], outs[1]);
    assert!(!m.is_self_loop(a.edge()) && !m.is_self_loop(b.edge()));
    assert_ne!(m.face(a), m.face(b));
    m.insert_edge(Corner::Halfedge(a), Corner::Halfedge(b)).unwrap();
    m.validate().unwrap();
    m
}

#[test]
fn self_loop_inputs() {
    let m = cube_with_loops();
    assert_eq!((m.n_self_loops(), m.genus()), (2, 1));
    let c = SierpinskiCounts::of(&m).unwrap();
    assert_eq!(c.loop_faces, 1);
    check_iterations(&m, 6);
    // the output of an earlier iteration as input: self-loops everywhere
    let s = sierpinski(&primitives::octahedron()).unwrap();
    check_iterations(&s, 5);
}

#[test]
fn degenerate_inputs() {
    // a point-sphere and a one-gon sphere: no non-loop edge, unchanged
    let mut p = Mesh::new();
    p.create_vertex(DVec3::ZERO).unwrap();
    let s = sierpinski(&p).unwrap();
    s.validate().unwrap();
    assert_eq!(measured(&s), measured(&p));
    let mut l = p.clone();
    l.insert_edge(Corner::Point(crate::VertexId(0)), Corner::Point(crate::VertexId(0))).unwrap();
    let s = sierpinski(&l).unwrap();
    s.validate().unwrap();
    assert_eq!(measured(&s), measured(&l));
    // a dangling edge: one face a -> b -> a; its far end is a lone cone (D = 1 at each end)
    let seg = Mesh::from_polygons(vec![DVec3::ZERO, DVec3::X], &[2], &[0, 1], BuildOptions::default()).unwrap();
    let c = SierpinskiCounts::of(&seg).unwrap();
    assert_eq!((c.cones, c.lone_cones), (2, 2));
    check_iterations(&seg, 6);
    // a cube plus a dangling vertex inside one face (made with InsertEdge)
    let mut m = primitives::cube();
    let (v, _) = m.create_vertex(DVec3::new(0.0, 0.0, 1.0)).unwrap();
    let h = m.face_halfedge(FaceId(0)).unwrap();
    m.insert_edge(Corner::Halfedge(h), Corner::Point(v)).unwrap();
    assert_eq!(SierpinskiCounts::of(&m).unwrap().lone_cones, 1);
    check_iterations(&m, 5);
}

/// Faces as cyclic vertex sequences, each rotated to its smallest
/// rotation, sorted: equal for meshes that differ only in edge/face ids.
fn face_signature(m: &Mesh) -> Vec<Vec<u32>> {
    let mut out: Vec<Vec<u32>> = m
        .faces()
        .map(|f| {
            let c: Vec<u32> = m.face_vertices(f).map(|v| v.0).collect();
            (0..c.len()).map(|r| [&c[r..], &c[..r]].concat()).min().unwrap()
        })
        .collect();
    out.sort();
    out
}

#[test]
fn one_pass_equals_operators() {
    let inputs = [
        primitives::tetrahedron(),
        primitives::cube(),
        primitives::icosahedron(),
        primitives::torus(4, 3, 2.0, 0.5).unwrap(),
        primitives::genus_surface(2).unwrap(),
        hosohedron(3),
        cube_with_loops(),
        sierpinski(&primitives::cube()).unwrap(),
    ];
    for m in inputs {
        let a = sierpinski(&m).unwrap();
        let b = sierpinski_by_operators(&m).unwrap();
        b.validate().unwrap();
        assert_eq!(measured(&a), measured(&b));
        assert_eq!(a.face_size_histogram(), b.face_size_histogram());
        assert_eq!(a.valence_histogram(), b.valence_histogram());
        assert_eq!(a.positions(), b.positions());
        assert_eq!(face_signature(&a), face_signature(&b));
    }
}

#[test]
fn level_stencils_and_origins() {
    use crate::schemes::hosts::test_meshes::*;
    use crate::schemes::level::{EDGE, FACE, VERTEX};
    level_matches_plain_on_corpus(sierpinski, sierpinski_level, |name, m, lv| {
        let o = lv.origins.as_ref().unwrap();
        let c = SierpinskiCounts::of(m).unwrap();
        let n = (c.edges - c.self_loops) as usize;
        let ev = origin_counts(&o.vertex_kind, &o.vertex, EDGE, m.n_edges());
        let ee = origin_counts(&o.edge_kind, &o.edge, EDGE, m.n_edges());
        for e in 0..m.n_edges() {
            // a non-loop edge: its midpoint, two halves and the self-loop at the midpoint; a loop is kept
            let want = if m.is_self_loop(crate::EdgeId(e as u32)) { (0, 1) } else { (1, 3) };
            assert_eq!((ev[e], ee[e]), want, "{name} edge {e}");
        }
        assert!(origin_counts(&o.vertex_kind, &o.vertex, VERTEX, m.n_vertices()).iter().all(|&x| x == 1), "{name}");
        let kinds = |k: &[u8], kind: u8| k.iter().filter(|&&x| x == kind).count();
        // 2N corner triangles and F₀ kept faces from faces, K back faces from vertices, 2N cuts from faces
        assert_eq!(kinds(&o.face_kind, FACE), 2 * n + c.loop_faces as usize, "{name}");
        assert_eq!(kinds(&o.face_kind, VERTEX), c.cones as usize, "{name}");
        assert_eq!(kinds(&o.edge_kind, FACE), 2 * n, "{name}");
    });
    let lv = sierpinski_level(&sierpinski_tetrahedron(), &crate::schemes::level::Request { stencils: true, ..Default::default() }).unwrap();
    assert_eq!(lv.stencils.unwrap().n_rows(), lv.mesh.n_vertices());
    match sierpinski_level(&cube_with_hole(), &Default::default()) {
        Err(crate::error::MeshError::Precondition(msg)) => assert!(msg.starts_with("sierpinski") && msg.contains("no boundary version"), "{msg}"),
        other => panic!("{other:?}"),
    }
}

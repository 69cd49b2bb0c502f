//! The corpus every scheme's unit tests run over.

/// The plain closed-mesh scheme functions (and Sierpinski and Menger, which
/// have no boundary rule) refuse a capped hole instead of refining the cap
/// into a real face (the hole would close silently).
#[test]
fn schemes_without_boundary_rules_refuse_holes() {
    use crate::error::MeshError;
    use crate::schemes::*;
    let open = cube_with_hole();
    let o = menger::MengerOptions::default();
    let runs: [(&str, crate::error::Result<Mesh>); 7] = [
        ("doo_sabin", doo_sabin::doo_sabin(&open)),
        ("dual", dual::dual(&open)),
        ("midpoint", midpoint::midpoint(&open)),
        ("simplest", simplest::simplest(&open)),
        ("sqrt3", sqrt3::sqrt3(&open)),
        ("sierpinski", sierpinski::sierpinski(&open)),
        ("menger", menger::menger(&open, &o)),
    ];
    for (name, r) in runs {
        match r {
            Err(MeshError::Precondition(msg)) => assert!(msg.starts_with(name) && msg.contains("1 boundary loop"), "{msg}"),
            other => panic!("{name} on an open cube: {other:?}"),
        }
    }
    // the closed cube still goes through; Catmull-Clark and Loop have boundary rules
    assert!(doo_sabin::doo_sabin(&primitives::cube()).is_ok());
    assert!(catmull_clark::catmull_clark(&open).is_ok() && loop_subdivision::loop_subdivision(&open).is_ok());
}

#[test]
fn sierpinski_counts() {
    let s = sierpinski_tetrahedron();
    s.validate().unwrap();
    assert_eq!((s.n_vertices(), s.n_edges(), s.n_faces(), s.genus(), s.n_self_loops()), (10, 30, 16, 3, 6));
}
use crate::mesh::{BuildOptions, Corner, Mesh};
use crate::primitives;
use crate::FaceId;
use glam::DVec3;

/// A cube with a self-loop splitting one face into a one-gon and a
/// 5-corner face (the loop's vertex repeated in it).
pub fn cube_with_self_loop() -> Mesh {
    let mut m = primitives::cube();
    let c = m.corner(FaceId(0), 0).unwrap();
    m.insert_edge(c, c).unwrap();
    m
}
/// A cube with a second edge beside an existing one (a multi-edge),
/// splitting a two-gon off a face.
pub fn cube_with_two_gon() -> Mesh {
    let mut m = primitives::cube();
    // corners 0 and 1 of face 0 are joined by an edge already; a second
    // edge between them splits off a two-gon.
    let c0 = m.corner(FaceId(0), 0).unwrap();
    let c1 = m.corner(FaceId(0), 1).unwrap();
    m.insert_edge(c0, c1).unwrap();
    m
}
/// Self-loop joining two different faces at one vertex (Sierpinski's
/// kind): merges them, genus +1.
pub fn cube_with_handle_loop() -> Mesh {
    let mut m = primitives::cube();
    let v = m.corner_vertex(m.corner(FaceId(0), 0).unwrap());
    // another face around the same vertex
    let mut other = None;
    for f in m.faces() {
        if f == FaceId(0) {
            continue;
        }
        for (k, x) in m.face_vertices(f).enumerate() {
            if x == v && other.is_none() {
                other = Some((f, k));
            }
        }
    }
    let (f, k) = other.unwrap();
    let c0 = m.corner(FaceId(0), 0).unwrap();
    let c1 = m.corner(f, k).unwrap();
    m.insert_edge(c0, c1).unwrap();
    m
}
pub fn with_point_sphere() -> Mesh {
    let mut m = primitives::tetrahedron();
    m.create_vertex(DVec3::new(5.0, 0.0, 0.0)).unwrap();
    m
}
/// Level 1 of the Sierpinski paper's scheme on a tetrahedron: four corner
/// tetrahedra whose back faces are hexagons `[x, x, y, y, z, z]` with a
/// zero-length self-loop at every edge midpoint; each loop joins the back
/// faces of two corner pyramids. V = 10, E = 30, F = 16, genus 3.
pub fn sierpinski_tetrahedron() -> Mesh {
    let t = primitives::tetrahedron();
    let tp = t.positions().to_vec();
    let mut pos = tp.clone();
    let mut mid = std::collections::HashMap::new();
    let mut m = |a: u32, b: u32, pos: &mut Vec<DVec3>| -> i64 {
        *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
            pos.push((tp[a as usize] + tp[b as usize]) * 0.5);
            pos.len() as i64 - 1
        })
    };
    let (mut sizes, mut idx) = (Vec::new(), Vec::new());
    for f in t.faces() {
        let v: Vec<u32> = t.face_vertices(f).map(|x| x.0).collect();
        let (a, b, c) = (v[0], v[1], v[2]);
        let (ab, bc, ca) = (m(a, b, &mut pos), m(b, c, &mut pos), m(c, a, &mut pos));
        idx.extend([a as i64, ab, ca, b as i64, bc, ab, c as i64, ca, bc]);
        sizes.extend([3, 3, 3]);
    }
    for a in 0..4u32 {
        let o: Vec<i64> = (0..4u32).filter(|&o| o != a).map(|o| m(a, o, &mut pos)).collect();
        let (x, mut y, mut z) = (o[0], o[1], o[2]);
        let n = (pos[y as usize] - pos[x as usize]).cross(pos[z as usize] - pos[x as usize]);
        if n.dot(pos[x as usize] - tp[a as usize]) < 0.0 {
            std::mem::swap(&mut y, &mut z);
        }
        idx.extend([x, x, y, y, z, z]);
        sizes.push(6);
    }
    Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap()
}

pub fn corpus() -> Vec<(&'static str, Mesh)> {
    vec![
        ("tetrahedron", primitives::tetrahedron()),
        ("cube", primitives::cube()),
        ("octahedron", primitives::octahedron()),
        ("dodecahedron", primitives::dodecahedron()),
        ("icosahedron", primitives::icosahedron()),
        ("torus", primitives::torus(8, 5, 1.0, 0.4).unwrap()),
        ("genus3", primitives::genus_surface(3).unwrap()),
        ("self_loop", cube_with_self_loop()),
        ("two_gon", cube_with_two_gon()),
        ("handle_loop", cube_with_handle_loop()),
        ("point_sphere", with_point_sphere()),
        ("sierpinski", sierpinski_tetrahedron()),
    ]
}

/// A scheme's direct vertex-data masks (`level_with`, no stencils asked
/// for) equal its stencils applied to the same `k`-column rows, on every
/// corpus mesh, within `tol`.
pub fn check_direct_data_on_corpus(
    k: usize,
    tol: f64,
    level: impl Fn(&Mesh, &crate::schemes::level::Request) -> crate::Result<crate::schemes::level::Level>,
    level_with: impl Fn(&Mesh, &crate::schemes::level::Request, &[(Vec<f64>, usize)]) -> crate::Result<(crate::schemes::level::Level, Vec<Vec<f64>>)>,
) {
    use crate::schemes::level::Request;
    let mut n = 0;
    for (name, m) in corpus() {
        let a: Vec<f64> = (0..m.n_vertices() * k).map(|i| ((i * 7919) % 613) as f64 * 0.1 - 3.0).collect();
        let st = level(&m, &Request { stencils: true, ..Default::default() }).unwrap().stencils.unwrap();
        let want = st.apply(&a, k).unwrap();
        let (lv, got) = level_with(&m, &Request::default(), &[(a.clone(), k)]).unwrap();
        assert!(lv.stencils.is_none(), "{name}: no stencils asked for");
        assert_eq!(got[0].len(), want.len(), "{name}");
        for (i, (x, y)) in got[0].iter().zip(&want).enumerate() {
            assert!((x - y).abs() < tol, "{name}: value {i}: {x} vs {y}");
        }
        n += 1;
    }
    assert!(n >= 10);
}

/// The degree of every face, in face order.
pub fn face_sizes(m: &Mesh) -> Vec<usize> {
    m.faces().map(|f| m.face_degree(f)).collect()
}
pub fn n_point_spheres(m: &Mesh) -> usize {
    m.vertices().filter(|&v| m.point_sphere_face(v).is_some()).count()
}

/// Whether every face of `m` other than a one-gon has `n` corners.
pub fn all_faces_but_one_gons_have(m: &Mesh, n: usize) -> bool {
    face_sizes(m).iter().filter(|&&s| s != 1).all(|&s| s == n)
}

/// The checks every scheme's output `r` of input `m` must pass: it
/// validates, keeps the point-spheres, the genus and the number of
/// components, and has `(V', E', F')` = `want` with the point-spheres left
/// out of V' and F'.
pub fn check_output(name: &str, m: &Mesh, r: &Mesh, want: (usize, usize, usize)) {
    let ps = n_point_spheres(m);
    r.validate().unwrap_or_else(|err| panic!("{name}: {err}"));
    assert_eq!(n_point_spheres(r), ps, "{name} point-spheres");
    assert_eq!(r.n_vertices() - ps, want.0, "{name} V'");
    assert_eq!(r.n_edges(), want.1, "{name} E'");
    assert_eq!(r.n_faces() - ps, want.2, "{name} F'");
    assert_eq!(r.genus(), m.genus(), "{name} genus");
    assert_eq!(r.n_components(), m.n_components(), "{name} components");
}

/// Runs `scheme` on every mesh of the [`corpus`] and makes the checks of
/// [`check_output`], with the counts `counts(m, (V, E, F))` from the
/// input's `V`, `E`, `F` (point-spheres left out), then the scheme's own
/// checks `more(name, m, r)`.
pub fn check_on_corpus(
    scheme: impl Fn(&Mesh) -> crate::error::Result<Mesh>,
    counts: impl Fn(&Mesh, (usize, usize, usize)) -> (usize, usize, usize),
    more: impl Fn(&str, &Mesh, &Mesh),
) {
    for (name, m) in corpus() {
        let ps = n_point_spheres(&m);
        let want = counts(&m, (m.n_vertices() - ps, m.n_edges(), m.n_faces() - ps));
        let r = scheme(&m).unwrap_or_else(|err| panic!("{name}: {err}"));
        check_output(name, &m, &r, want);
        more(name, &m, &r);
    }
}

/// A cube without its first face, closed by a hole face.
pub fn cube_with_hole() -> Mesh {
    let c = primitives::cube().to_polygons();
    let sizes: Vec<i64> = c.sizes[1..].iter().map(|&s| s as i64).collect();
    let idx: Vec<i64> = c.indices[4..].iter().map(|&s| s as i64).collect();
    let opts = BuildOptions { close_boundaries: true, ..Default::default() };
    Mesh::from_polygons(primitives::cube().positions().to_vec(), &sizes, &idx, opts).unwrap()
}

/// An icosahedron without two of its faces (apart, so two triangle holes).
pub fn icosahedron_with_two_holes() -> Mesh {
    let c = primitives::icosahedron().to_polygons();
    let tri: Vec<&[u32]> = c.indices.chunks(3).collect();
    // a face not sharing a vertex with face 0
    let far = (1..tri.len()).find(|&f| tri[f].iter().all(|v| !tri[0].contains(v))).unwrap();
    let idx: Vec<i64> = (0..tri.len()).filter(|&f| f != 0 && f != far).flat_map(|f| tri[f].iter().map(|&v| v as i64)).collect();
    let sizes = vec![3i64; idx.len() / 3];
    let opts = BuildOptions { close_boundaries: true, ..Default::default() };
    let m = Mesh::from_polygons(primitives::icosahedron().positions().to_vec(), &sizes, &idx, opts).unwrap();
    assert_eq!(m.n_holes(), 2);
    m
}

/// The open test meshes: a disk, an annulus (tube), a box with one hole and
/// a triangle mesh with two.
pub fn open_meshes() -> Vec<(&'static str, Mesh)> {
    vec![("grid", open_grid(4)), ("tube", open_tube(8, 3)), ("cube_with_hole", cube_with_hole()), ("icosahedron_two_holes", icosahedron_with_two_holes())]
}

/// A cube whose faces 0 and 1 are merged by InsertEdge (genus 1): the
/// merged face runs along both sides of the new edge.
pub fn handle_cube() -> Mesh {
    let mut m = crate::primitives::cube();
    let a = m.face_halfedge(FaceId(0)).unwrap();
    let b = m.face_halfedge(FaceId(1)).unwrap();
    m.insert_edge(Corner::Halfedge(a), Corner::Halfedge(b)).unwrap();
    assert_eq!(m.genus(), 1);
    m
}

/// A prism over a counter-clockwise simple polygon (may be non-convex):
/// planar faces, every vertex 3-valent.
pub fn prism(profile: &[[f64; 2]], height: f64) -> Mesh {
    let n = profile.len() as i64;
    let mut pos: Vec<DVec3> = profile.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect();
    pos.extend(profile.iter().map(|p| DVec3::new(p[0], p[1], height)));
    let mut sizes = vec![n, n];
    let mut idx: Vec<i64> = (0..n).rev().collect();
    idx.extend(n..2 * n);
    for i in 0..n {
        let j = (i + 1) % n;
        sizes.push(4);
        idx.extend([i, j, n + j, n + i]);
    }
    Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap()
}

/// A five-pointed star prism (non-convex planar faces).
pub fn star_prism() -> Mesh {
    let pts: Vec<[f64; 2]> = (0..10)
        .map(|k| {
            let r = if k % 2 == 0 { 1.0 } else { 0.4 };
            let a = std::f64::consts::PI * k as f64 / 5.0;
            [r * a.cos(), r * a.sin()]
        })
        .collect();
    prism(&pts, 0.5)
}

pub fn counts(m: &Mesh) -> (usize, usize, usize) {
    (m.n_vertices(), m.n_edges(), m.n_faces())
}

/// A cube with a self-loop (a one-gon inside a quad, made by InsertEdge
/// on one corner twice) and a two-gon (an edge doubling a cube edge).
pub fn one_gon_two_gon_cube() -> Mesh {
    let mut m = crate::primitives::cube();
    let h = m.face_halfedge(FaceId(0)).unwrap();
    m.insert_edge(Corner::Halfedge(h), Corner::Halfedge(h)).unwrap();
    let g = m.face_halfedge(FaceId(3)).unwrap();
    let g2 = m.next(g);
    m.insert_edge(Corner::Halfedge(g), Corner::Halfedge(g2)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.n_self_loops(), 1);
    let hist = m.face_size_histogram();
    assert_eq!(hist.get(&1), Some(&1));
    assert_eq!(hist.get(&2), Some(&1));
    m
}

/// An open n × n grid of quads on a bumpy height field (one boundary loop).
pub fn open_grid(n: usize) -> Mesh {
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64, j as f64);
            pos.push(DVec3::new(x, y, 0.3 * (x * 0.9).sin() * (y * 1.3).cos()));
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
    let sizes = vec![4i64; n * n];
    Mesh::from_polygons(pos, &sizes, &idx, BuildOptions { close_boundaries: true, ..Default::default() }).unwrap()
}

/// An open tube of `n` × `m` quads (two boundary loops).
pub fn open_tube(n: usize, m: usize) -> Mesh {
    let mut pos = Vec::new();
    for j in 0..=m {
        for i in 0..n {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            pos.push(DVec3::new(t.cos(), t.sin(), j as f64 * 0.7));
        }
    }
    let mut idx = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let (a, b) = ((j * n + i) as i64, (j * n + (i + 1) % n) as i64);
            idx.extend_from_slice(&[a, b, b + n as i64, a + n as i64]);
        }
    }
    Mesh::from_polygons(pos, &vec![4i64; n * m], &idx, BuildOptions { close_boundaries: true, ..Default::default() }).unwrap()
}

/// An open tube of `k` quads around and two rings high, its bottom a real
/// k-gon, its top a hole: an open mesh with one large real face.
pub fn cup(k: usize) -> Mesh {
    let tube = open_tube(k, 2);
    let mut faces: Vec<Vec<u32>> = tube.faces().filter(|&f| !tube.is_hole(f)).map(|f| tube.face_vertices(f).map(|v| v.0).collect()).collect();
    faces.push((0..k as u32).rev().collect());
    let sizes: Vec<i64> = faces.iter().map(|f| f.len() as i64).collect();
    let idx: Vec<i64> = faces.iter().flatten().map(|&v| v as i64).collect();
    let cup = Mesh::from_polygons(tube.positions().to_vec(), &sizes, &idx, BuildOptions { close_boundaries: true, ..Default::default() }).unwrap();
    assert_eq!((cup.n_holes(), *cup.face_size_histogram().keys().max().unwrap()), (1, k));
    cup
}

/// Every output of a level with stencils and origins: the mesh is valid,
/// `S · P` is the output positions, and the origins are in range.
pub fn check_level(name: &str, m: &Mesh, lv: &crate::schemes::level::Level) {
    lv.mesh.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
    if let Some(s) = &lv.stencils {
        assert_eq!((s.n_rows(), s.n_cols), (lv.mesh.n_vertices(), m.n_vertices()), "{name}: stencil shape");
        let p = s.apply_points(m.positions()).unwrap();
        for (i, (a, b)) in p.iter().zip(lv.mesh.positions()).enumerate() {
            assert!((*a - *b).length() <= 1e-12 * (1.0 + b.length()), "{name}: S·P row {i}: {a} vs {b}");
        }
    }
    if let Some(o) = &lv.origins {
        o.check(m, &lv.mesh).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

/// χ of the open surface: V − E + real faces.
pub fn open_euler(m: &Mesh) -> i64 {
    m.n_vertices() as i64 - m.n_edges() as i64 + (m.n_faces() - m.n_holes()) as i64
}

/// How many output elements name each input element of `kind` (`n` of
/// them) as their origin.
pub fn origin_counts(kinds: &[u8], idx: &[u32], kind: u8, n: usize) -> Vec<usize> {
    let mut c = vec![0usize; n];
    for (&k, &i) in kinds.iter().zip(idx) {
        if k == kind {
            c[i as usize] += 1;
        }
    }
    c
}

/// Whether input face `f` is a point-sphere's.
pub fn is_point_face(m: &Mesh, f: usize) -> bool {
    m.f_start[f] & crate::mesh::POINT != 0
}

/// A level of a scheme against its plain call on the corpus: `check_level`,
/// the same polygons and positions, a plain request gives only the mesh;
/// then `more(name, m, level)`.
pub fn level_matches_plain_on_corpus(
    plain: impl Fn(&Mesh) -> crate::error::Result<Mesh>,
    level: impl Fn(&Mesh, &crate::schemes::level::Request) -> crate::error::Result<crate::schemes::level::Level>,
    more: impl Fn(&str, &Mesh, &crate::schemes::level::Level),
) {
    use crate::schemes::level::Request;
    let full = full_request();
    for (name, m) in corpus() {
        let lv = level(&m, &full).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_level(name, &m, &lv);
        assert!(lv.creases.is_none(), "{name}");
        let p = plain(&m).unwrap();
        assert_eq!(lv.mesh.to_polygons(), p.to_polygons(), "{name}");
        for (a, b) in lv.mesh.positions().iter().zip(p.positions()) {
            assert!((*a - *b).length() <= 1e-12 * (1.0 + b.length()), "{name}");
        }
        let bare = level(&m, &Request::plain()).unwrap();
        assert!(bare.stencils.is_none() && bare.origins.is_none() && bare.creases.is_none(), "{name}");
        assert_eq!(bare.mesh.to_polygons(), p.to_polygons(), "{name}");
        assert_eq!(bare.mesh.positions(), p.positions(), "{name}");
        more(name, &m, &lv);
    }
}

/// An edge with hole faces on both sides has no boundary rule: the levels
/// with boundary rules that need a real side name the edge.
#[test]
fn edges_between_two_holes_are_refused() {
    use crate::schemes::level::Request;
    let mut m = primitives::cube();
    let e = 0;
    m.f_hole[m.he_face[2 * e] as usize] = true;
    m.f_hole[m.he_face[2 * e + 1] as usize] = true;
    for (name, r) in [
        ("dual", crate::schemes::dual::dual_level(&m, &Request::plain()).map(|l| l.mesh)),
        ("doo_sabin", crate::schemes::doo_sabin::doo_sabin_level(&m, &Request::plain()).map(|l| l.mesh)),
    ] {
        match r {
            Err(crate::error::MeshError::Precondition(msg)) => assert!(msg.starts_with(name) && msg.contains("edge 0 has hole faces on both sides"), "{msg}"),
            other => panic!("{name}: {other:?}"),
        }
    }
    // midpoint splits it like any edge and keeps both holes
    let lv = crate::schemes::midpoint::midpoint_level(&m, &Request::plain()).unwrap();
    lv.mesh.validate().unwrap();
    assert_eq!(lv.mesh.n_holes(), 2);
}

/// Point-spheres ride along with the open-mesh levels.
#[test]
fn open_levels_keep_point_spheres() {
    use crate::schemes::level::Level;
    let mut m = cube_with_hole();
    m.create_vertex(DVec3::new(5.0, 0.0, 0.0)).unwrap();
    let full = full_request();
    let runs: [(&str, crate::error::Result<Level>); 5] = [
        ("midpoint", crate::schemes::midpoint::midpoint_level(&m, &full)),
        ("dual", crate::schemes::dual::dual_level(&m, &full)),
        ("doo_sabin", crate::schemes::doo_sabin::doo_sabin_level(&m, &full)),
        ("honeycomb", crate::schemes::honeycomb::honeycomb_level(&m, 0.5, None, &full)),
        ("vertex_truncation", crate::schemes::vertex_truncation::vertex_truncation_level(&m, crate::schemes::vertex_truncation::Truncation::Chaikin, &full)),
    ];
    for (name, lv) in runs {
        let lv = lv.unwrap_or_else(|e| panic!("{name}: {e}"));
        check_level(name, &m, &lv);
        assert_eq!((lv.mesh.n_holes(), n_point_spheres(&lv.mesh), lv.mesh.n_components()), (1, 1, 2), "{name}");
        assert_eq!(open_euler(&lv.mesh), open_euler(&m), "{name}");
    }
}

/// A request for everything but creases: stencils and origins.
pub fn full_request() -> crate::schemes::level::Request<'static> {
    crate::schemes::level::Request { stencils: true, origins: true, ..Default::default() }
}

/// Every column of the two meshes equal, and the positions bit for bit (so
/// -0.0 is not 0.0 and one ulp counts): what the fused builds' tests
/// compare with their compositions.
pub fn same_bits(a: &Mesh, b: &Mesh) -> bool {
    let bits = |m: &Mesh| m.pos.iter().flat_map(|p| p.to_array()).map(f64::to_bits).collect::<Vec<_>>();
    bits(a) == bits(b)
        && a.v_out == b.v_out
        && a.he_next == b.he_next
        && a.he_prev == b.he_prev
        && a.he_vert == b.he_vert
        && a.he_face == b.he_face
        && a.f_start == b.f_start
        && a.f_hole == b.f_hole
}

/// A 9×7 torus with every vertex moved off its grid (non-planar quads).
pub fn jittered_torus() -> Mesh {
    let mut t = crate::primitives::torus(9, 7, 2.0, 0.7).unwrap();
    for (i, p) in t.pos.iter_mut().enumerate() {
        *p += glam::DVec3::new((i as f64 * 1.7).sin(), (i as f64 * 2.3).cos(), (i as f64 * 0.9).sin()) * 0.05;
    }
    t
}

/// A fused build against the composition it replaces, on `m`: the same
/// mesh ([`same_bits`], and one ulp of difference is seen) or the same
/// error, untraced and traced (face parents too). Returns whether the
/// fused build's own pass gave the mesh (closed, no point-spheres).
pub fn check_fused(name: &str, m: &Mesh, fused: &dyn Fn(&Mesh) -> crate::error::Result<Mesh>, composed: &dyn Fn(&Mesh) -> crate::error::Result<Mesh>) -> bool {
    use crate::schemes::face_parents::traced;
    let mut one_pass = false;
    match (fused(m), composed(m)) {
        (Ok(a), Ok(b)) => {
            a.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(same_bits(&a, &b), "{name}: the fused build differs from the composition");
            let mut c = a.clone();
            let i = c.pos.len() / 2;
            c.pos[i].y = f64::from_bits(c.pos[i].y.to_bits() ^ 1);
            assert!(!same_bits(&c, &b), "{name}: one ulp unseen");
            one_pass = m.n_holes() == 0 && !m.has_point_spheres();
        }
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{name}"),
        (a, b) => panic!("{name}: fused {:?}, composition {:?}", a.err(), b.err()),
    }
    match (traced(m, || fused(m)), traced(m, || composed(m))) {
        (Ok((a, pa)), Ok((b, pb))) => {
            assert!(same_bits(&a, &b), "{name}: traced, the builds differ");
            assert_eq!(pa, pb, "{name}: face parents");
        }
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{name}"),
        (a, b) => panic!("{name}: traced, fused {:?}, composition {:?}", a.err(), b.err()),
    }
    one_pass
}

/// The inputs every "a level given up equals the borrowed level" test runs
/// on: the corpus (point-spheres, self-loops, two-gons), the open meshes and
/// a torus, named.
pub fn owned_level_cases() -> Vec<(String, Mesh)> {
    let mut cases: Vec<(String, Mesh)> = corpus().into_iter().map(|(n, m)| (n.to_string(), m)).collect();
    cases.extend(open_meshes().into_iter().map(|(n, m)| (n.to_string(), m)));
    cases.push(("torus".into(), crate::primitives::torus(12, 8, 3.0, 1.0).unwrap()));
    cases
}

/// A mesh's positions as bits, for comparisons that must be exact.
pub fn position_bits(m: &Mesh) -> Vec<[u64; 3]> {
    m.positions().iter().map(|p| p.to_array().map(f64::to_bits)).collect()
}

/// Corner data through `m`'s level with placeholder rows for its large
/// faces (`Request::skip_large_face_rows`) and then `fill` (output, input
/// rows, output rows, k) equal the generic transfer over the full rows
/// within 1e-12, and the placeholders alone do not: corner values with
/// seams (each corner its own), 1 and 3 columns.
pub fn assert_large_corners(m: &Mesh, level: impl Fn(&crate::schemes::level::Request) -> crate::schemes::level::Level, fill: impl Fn(&Mesh, &[f64], &mut [f64], usize)) {
    use crate::schemes::corner_transfer::transfer;
    let full = full_request();
    let (a, b) = (level(&full), level(&crate::schemes::level::Request { skip_large_face_rows: true, ..full }));
    assert!(same_bits(&a.mesh, &b.mesh), "the mesh is unaffected");
    let corners: usize = m.faces().filter(|&f| !m.is_hole(f)).map(|f| m.face_degree(f)).sum();
    for k in [1, 3] {
        let rows: Vec<f64> = (0..corners * k).map(|i| ((i * 7919) % 1013) as f64 * 0.01 - 3.0).collect();
        let mut want = vec![(rows.clone(), k)];
        transfer(m, &a.mesh, a.stencils.as_ref().unwrap(), a.origins.as_ref().unwrap(), &mut want).unwrap();
        let mut got = vec![(rows.clone(), k)];
        transfer(m, &b.mesh, b.stencils.as_ref().unwrap(), b.origins.as_ref().unwrap(), &mut got).unwrap();
        assert!(want[0].0.iter().zip(&got[0].0).any(|(x, y)| (x - y).abs() > 1e-3), "the placeholders alone differ");
        fill(&b.mesh, &rows, &mut got[0].0, k);
        assert_eq!(want[0].0.len(), got[0].0.len());
        for (i, (x, y)) in want[0].0.iter().zip(&got[0].0).enumerate() {
            assert!((x - y).abs() <= 1e-12 * (1.0 + x.abs()), "row {}, column {}: {x} vs {y}", i / k, i % k);
        }
    }
}

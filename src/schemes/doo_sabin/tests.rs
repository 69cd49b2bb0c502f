use super::*;
use crate::schemes::hosts::test_meshes::*;

#[test]
fn weights_sum_to_one() {
    for n in 2..12 {
        let s: f64 = (0..n).map(|i| doo_sabin_weight(n, i)).sum();
        assert!((s - 1.0).abs() < 1e-14, "n = {n}");
    }
}

#[test]
fn counts_and_validity_on_corpus() {
    check_on_corpus(doo_sabin, |_, (v, e, f)| (2 * e, 4 * e, f + e + v), |name, m, r| {
        let ps = n_point_spheres(m);
        let mut want = face_sizes(m);
        want.truncate(m.n_faces() - ps);
        want.extend(std::iter::repeat(4).take(m.n_edges()));
        want.extend(m.vertices().filter(|&x| m.point_sphere_face(x).is_none()).map(|x| m.valence(x)));
        want.sort();
        let mut got = face_sizes(r);
        got.truncate(r.n_faces() - ps);
        got.sort();
        assert_eq!(got, want, "{name} face sizes");
    });
}

#[test]
fn level_equals_plain_on_corpus() {
    level_matches_plain_on_corpus(doo_sabin, doo_sabin_level, |name, m, lv| {
        let o = lv.origins.as_ref().unwrap();
        let fl = FaceLayout::new(m).unwrap();
        let (fv, ff, fe) = (
            origin_counts(&o.vertex_kind, &o.vertex, FACE, m.n_faces()),
            origin_counts(&o.face_kind, &o.face, FACE, m.n_faces()),
            origin_counts(&o.edge_kind, &o.edge, FACE, m.n_faces()),
        );
        for f in 0..m.n_faces() {
            let point = is_point_face(m, f);
            // n corner points and n F-face sides per n-gon; a point-sphere keeps its vertex
            assert_eq!((fv[f], ff[f], fe[f]), (fl.degree(f), 1, fl.degree(f)), "{name} face {f} {point}");
        }
        assert!(origin_counts(&o.face_kind, &o.face, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
        assert!(origin_counts(&o.edge_kind, &o.edge, EDGE, m.n_edges()).iter().all(|&c| c == 2), "{name}");
        let vf = origin_counts(&o.face_kind, &o.face, VERTEX, m.n_vertices());
        assert!(vf.iter().enumerate().all(|(v, &c)| c == usize::from(m.v_out[v] & crate::mesh::POINT == 0)), "{name}");
        let kinds = |k: &[u8], kind: u8| k.iter().filter(|&&x| x == kind).count();
        let ps = n_point_spheres(m);
        assert_eq!(kinds(&o.vertex_kind, FACE), m.n_halfedges(), "{name}");
        assert_eq!(kinds(&o.vertex_kind, VERTEX), ps, "{name}");
        assert_eq!((kinds(&o.face_kind, FACE), kinds(&o.face_kind, EDGE), kinds(&o.face_kind, VERTEX)), (m.n_faces(), m.n_edges(), m.n_vertices() - ps), "{name}");
    });
}

#[test]
fn open_meshes_keep_their_holes_with_a_chaikin_boundary() {
    let full = crate::schemes::hosts::test_meshes::full_request();
    for (name, m) in open_meshes() {
        let lv = doo_sabin_level(&m, &full).unwrap();
        check_level(name, &m, &lv);
        let r = &lv.mesh;
        let b = (0..m.n_halfedges()).filter(|&h| m.f_hole[m.he_face[h] as usize]).count();
        let (v, e, f, h) = (m.n_vertices(), m.n_edges(), m.n_faces() - m.n_holes(), m.n_halfedges());
        assert_eq!((r.n_vertices(), r.n_edges(), r.n_faces() - r.n_holes(), r.n_holes()), (h + b, 4 * e + b, f + e + v, m.n_holes()), "{name}");
        assert_eq!(open_euler(r), open_euler(&m), "{name}");
        assert_eq!(r.n_components(), m.n_components(), "{name}");
        // the boundary polygon is refined by Chaikin's rule: output hole f runs through
        // 3/4 a + 1/4 b and 1/4 a + 3/4 b of every edge a -> b of input hole f
        let p = m.positions();
        for hf in (0..m.n_faces()).filter(|&x| m.f_hole[x]) {
            assert!(r.f_hole[hf], "{name}");
            let want: Vec<DVec3> = m
                .face_halfedges(crate::FaceId(hf as u32))
                .flat_map(|g| {
                    let (a, bb) = (p[m.vertex(g).idx()], p[m.head(g).idx()]);
                    [a * 0.75 + bb * 0.25, a * 0.25 + bb * 0.75]
                })
                .collect();
            let got: Vec<DVec3> = r.face_vertices(crate::FaceId(hf as u32)).map(|x| r.position(x)).collect();
            assert_eq!(got.len(), want.len(), "{name}");
            for (a, bb) in got.iter().zip(&want) {
                assert!((*a - *bb).length() < 1e-12, "{name}: {a} vs {bb}");
            }
        }
        // interior corner points keep Doo & Sabin's mask
        let fl = FaceLayout::new(&m).unwrap();
        for ff in (0..m.n_faces()).filter(|&x| !m.f_hole[x]) {
            let hs = fl.corners(ff);
            let n = hs.len();
            for k in 0..n {
                let want: DVec3 = (0..n).map(|i| p[m.he_vert[hs[i] as usize] as usize] * doo_sabin_weight(n, (i + n - k) % n)).sum();
                assert!((r.positions()[fl.off[ff] as usize + k] - want).length() < 1e-12, "{name}");
            }
        }
        // origins: n corner points per real n-gon, 2 Chaikin points and 1 E-face per boundary edge
        let o = lv.origins.as_ref().unwrap();
        let fv = origin_counts(&o.vertex_kind, &o.vertex, FACE, m.n_faces());
        let ev = origin_counts(&o.vertex_kind, &o.vertex, EDGE, m.n_edges());
        for x in 0..m.n_faces() {
            assert_eq!(fv[x], if m.f_hole[x] { 0 } else { fl.degree(x) }, "{name}");
        }
        for x in 0..m.n_edges() {
            let bnd = m.f_hole[m.he_face[2 * x] as usize] || m.f_hole[m.he_face[2 * x + 1] as usize];
            assert_eq!(ev[x], if bnd { 2 } else { 0 }, "{name}");
        }
        assert!(origin_counts(&o.face_kind, &o.face, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
        // two steps: still open, still Chaikin
        let lv2 = doo_sabin_level(r, &full).unwrap();
        check_level(name, r, &lv2);
        assert_eq!((lv2.mesh.n_holes(), open_euler(&lv2.mesh)), (m.n_holes(), open_euler(&m)), "{name}");
    }
    // the plain call still refuses holes
    match doo_sabin(&cube_with_hole()) {
        Err(crate::error::MeshError::Precondition(msg)) => assert!(msg.starts_with("doo_sabin"), "{msg}"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn direct_data_equals_the_stencils_on_corpus() {
    check_direct_data_on_corpus(3, 1e-12, doo_sabin_level, doo_sabin_level_with);
}

#[test]
fn matches_direct_weights() {
    let m = crate::primitives::dodecahedron();
    let r = doo_sabin(&m).unwrap();
    let fl = FaceLayout::new(&m).unwrap();
    for f in 0..m.n_faces() {
        let hs = fl.corners(f);
        let n = hs.len();
        for k in 0..n {
            let want: DVec3 = (0..n).map(|i| m.positions()[m.vertex(crate::HalfedgeId(hs[i])).idx()] * doo_sabin_weight(n, (i + n - k) % n)).sum();
            assert!((r.positions()[fl.off[f] as usize + k] - want).length() < 1e-13);
        }
    }
}

#[test]
fn handle_self_loop_opens() {
    let m = cube_with_handle_loop();
    let r = doo_sabin(&m).unwrap();
    // no two corner points coincide
    let p = r.positions();
    for i in 0..p.len() {
        for j in 0..i {
            assert!((p[i] - p[j]).length() > 1e-6, "{i} {j}");
        }
    }
}

/// The open level's columns, written in closed form, are what the general
/// builder makes of the same corner lists (twins paired and checked, edges
/// numbered by first corner, each vertex's first corner as its v_out).
#[test]
fn open_columns_equal_the_general_builder() {
    let plain = crate::schemes::level::Request::plain();
    for (name, m) in open_meshes() {
        let mut cur = m;
        for level in 0..2 {
            let lv = doo_sabin_level(&cur, &plain).unwrap();
            let (sizes, cv, tw, holes) = super::open::corner_lists(&cur);
            let want = Mesh::from_corner_twins_with_holes(lv.mesh.positions().to_vec(), &sizes, &cv, &tw, holes).unwrap();
            assert_eq!(lv.mesh, want, "{name} level {level}");
            cur = lv.mesh;
        }
    }
}

/// A real face above `open::DENSE_MAX` corners on an open mesh (a cup: a
/// 200-gon bottom, a tube, the top a hole): its corner points come from the
/// face's sums in O(n), the same bits with and without stencils, within
/// rounding of the dense rows (`check_level`), and the closed step's bits
/// for the same face.
#[test]
fn large_faces_of_open_meshes_take_the_sums() {
    let k = 200;
    let cup = cup(k);
    let full = full_request();
    let lv = doo_sabin_level(&cup, &full).unwrap();
    check_level("cup", &cup, &lv);
    let plain = doo_sabin_level(&cup, &Request::plain()).unwrap();
    assert!(same_bits(&plain.mesh, &lv.mesh));
    // the closed step on the same mesh with its hole made a real face
    // writes the bottom's corners with the same function and order
    let mut closed = cup.clone();
    closed.f_hole.iter_mut().for_each(|h| *h = false);
    let c = doo_sabin(&closed).unwrap();
    let bottom = (0..cup.n_faces()).find(|&f| cup.face_degree(crate::FaceId::new(f)) == k && !cup.f_hole[f]).unwrap();
    let fl = crate::schemes::hosts::FaceLayout::new(&cup).unwrap();
    for i in fl.off[bottom] as usize..fl.off[bottom + 1] as usize {
        assert_eq!(lv.mesh.positions()[i].to_array().map(f64::to_bits), c.positions()[i].to_array().map(f64::to_bits), "corner {i}");
    }
}

/// Corner data through an open level whose large faces' rows are
/// placeholders (`Request::skip_large_face_rows`) and then written by
/// `open_large_corners` equal the generic transfer over the full rows,
/// within rounding: a cup with a 200-gon bottom, corner values with seams
/// (each corner its own), 1 and 3 columns; and the placeholders alone do
/// not (the test can fail).
#[test]
fn large_face_corners_equal_the_full_transfer() {
    let cup = cup(200);
    assert!(open_large_corners_apply(&cup));
    assert_large_corners(&cup, |r| doo_sabin_level(&cup, r).unwrap(), |out, rows, got, k| open_large_corners(&cup, out, rows, got, k).unwrap());
}

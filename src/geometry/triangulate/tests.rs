use super::redo::{exact, retry};
use super::*;
use crate::mesh::{Corner, EdgeId, HalfedgeId};
use crate::{primitives, schemes, BuildOptions};

/// No self-loop, face with a repeated vertex or face under three corners
/// (multi-edges are fine: their copies are split).
fn is_simple(m: &Mesh) -> bool {
    let mut cyc = Vec::new();
    for f in m.faces() {
        face_cycle(m, f, &[], &mut cyc);
        let mut s = cyc.clone();
        s.sort_unstable();
        s.dedup();
        if cyc.len() < 3 || s.len() != cyc.len() || cyc.len() != m.face_degree(f) {
            return false;
        }
    }
    true
}

/// Every directed triangle edge once and its reverse once (a closed
/// 2-manifold triangle mesh), every triangle of three distinct ids in range.
fn assert_closed(m: &Mesh, t: &Triangulation) {
    let nv = (m.n_vertices() + t.points.len()) as u32;
    let mut e: Vec<(u32, u32)> = Vec::with_capacity(3 * t.tris.len());
    for tri in &t.tris {
        assert!(tri.iter().all(|&v| v < nv) && tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2], "{tri:?}");
        e.extend((0..3).map(|k| (tri[k], tri[(k + 1) % 3])));
    }
    e.sort_unstable();
    for w in e.windows(2) {
        assert_ne!(w[0], w[1], "directed edge {:?} in two triangles", w[0]);
    }
    for &(a, b) in &e {
        assert!(e.binary_search(&(b, a)).is_ok(), "edge {a}-{b} has one triangle");
    }
    assert_eq!(t.tris.len(), t.tri_face.len());
    assert!(t.tri_face.windows(2).all(|w| w[0] <= w[1]), "triangles grouped by face");
}

fn corner_sum(m: &Mesh) -> usize {
    m.faces().map(|f| m.face_degree(f)).sum()
}

#[test]
fn deleted_edges_of_tetrahedron_and_cube() {
    for base in [primitives::tetrahedron(), primitives::cube()] {
        for e in 0..base.n_edges() {
            let mut m = base.clone();
            m.delete_edge(EdgeId(e as u32)).unwrap();
            let t = m.triangulate();
            assert_closed(&m, &t);
            // the merged faces are folded (bent): each is fanned around one point
            assert_eq!(t.tris.len(), corner_sum(&m) - 2 * m.n_faces() + 2 * t.points.len());
        }
    }
}

#[test]
fn smoothed_sierpinski_of_the_platonic_solids() {
    let solids = [primitives::tetrahedron(), primitives::cube(), primitives::octahedron(), primitives::icosahedron(), primitives::dodecahedron()];
    for (k, s) in solids.iter().enumerate() {
        for n in 1..=2 {
            let f = schemes::sierpinski::sierpinski_iterated(s, n).unwrap();
            for m in [schemes::doo_sabin::doo_sabin(&f).unwrap(), schemes::catmull_clark::catmull_clark(&f).unwrap()] {
                m.validate().unwrap();
                assert!(is_simple(&m), "solid {k} iteration {n}");
                assert_closed(&m, &m.triangulate());
            }
        }
    }
}

#[test]
fn triangle_meshes_come_out_as_they_are() {
    let m = primitives::icosahedron();
    let t = m.triangulate();
    let faces: Vec<[u32; 3]> = m.faces().map(|f| {
        let v: Vec<u32> = m.face_vertices(f).map(|v| v.0).collect();
        [v[0], v[1], v[2]]
    }).collect();
    assert_eq!(t.tris, faces);
    assert_eq!(t.tri_face, (0..20).collect::<Vec<u32>>());
}

/// A flat sphere of two copies of one polygon: each side's triangulation
/// must avoid the other's diagonals.
fn two_sided(pos: Vec<DVec3>) -> Mesh {
    let n = pos.len() as i64;
    let mut idx: Vec<i64> = (0..n).collect();
    idx.extend((0..n).rev());
    Mesh::from_polygons(pos, &[n, n], &idx, BuildOptions::default()).unwrap()
}

fn star(n: usize, r_in: f64) -> Vec<DVec3> {
    (0..n)
        .map(|k| {
            let r = if k % 2 == 0 { 1.0 } else { r_in };
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            DVec3::new(r * a.cos(), r * a.sin(), 0.0)
        })
        .collect()
}

/// Area of face 0's triangles (all positive) against the polygon's.
fn assert_tiles_top(m: &Mesh, t: &Triangulation) {
    let pos = m.positions();
    let p = |v: u32| if (v as usize) < pos.len() { pos[v as usize] } else { t.points[v as usize - pos.len()] };
    let mut area = 0.0;
    for (tri, &f) in t.tris.iter().zip(&t.tri_face) {
        if f == 0 {
            let z = (p(tri[1]) - p(tri[0])).cross(p(tri[2]) - p(tri[0])).z;
            assert!(z > 0.0, "inverted triangle {tri:?}");
            area += z / 2.0;
        }
    }
    let n = pos.len();
    let exact: f64 = (0..n).map(|k| pos[k].truncate().perp_dot(pos[(k + 1) % n].truncate()) / 2.0).sum();
    assert!((area - exact).abs() < 1e-9 * exact, "{area} vs {exact}");
}

#[test]
fn non_convex_stars() {
    for n in [10, 64, 2000, 100_000] {
        let m = two_sided(star(n, 0.4));
        let t = m.triangulate();
        assert_closed(&m, &t);
        assert_tiles_top(&m, &t);
        // both sides need every tip's chord: the second one gets a point
        assert_eq!(t.points.len(), 1, "{n}-gon");
    }
    // star-shaped, but not from the corners' mean: earcut
    let mut p = star(40, 0.4);
    p.iter_mut().for_each(|q| if q.x > 0.0 { *q *= DVec3::new(6.0, 1.0, 1.0) });
    let m = two_sided(p);
    let t = m.triangulate();
    assert_closed(&m, &t);
    assert_tiles_top(&m, &t);
}

/// A spiral strip's outline (turns of width 0.5), `n` corners in the plane z = 0.
pub(super) fn spiral(n: usize, turns: f64) -> Vec<DVec3> {
    let h = n / 2;
    let arm = |r0: f64| -> Vec<DVec3> {
        (0..h)
            .map(|i| {
                let t = i as f64 / (h - 1) as f64;
                let a = t * turns * std::f64::consts::TAU;
                DVec3::new(a.cos(), a.sin(), 0.0) * (r0 + t * turns)
            })
            .collect()
    };
    let mut p = arm(1.0);
    p.extend(arm(0.5).into_iter().rev());
    p
}

/// Faces past `MONOTONE_MIN` corners that earcut was quadratic on (a
/// spiral, a comb of thin spikes not star-shaped from the corners' mean)
/// take the monotone partition: no added point on one side of a prism, and
/// both sides of a spiral sheet (the same diagonals along y) settled by the
/// sweep along x, not by splitting every diagonal.
#[test]
fn large_non_convex_faces_take_the_monotone_partition() {
    let n = 2 * MONOTONE_MIN;
    let spikes: Vec<DVec3> = (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            // spikes off-centre: star-shaped from the origin, not from the corners' mean
            DVec3::new(a.cos(), a.sin(), 0.0) * if k % 2 == 0 { 1.0 } else { 1.5 } + if k < n / 4 { DVec3::X * 0.01 } else { DVec3::ZERO }
        })
        .collect();
    for (name, outline) in [("spiral", spiral(n, 12.0)), ("spikes", spikes)] {
        // a prism: the caps and n side quads
        let mut pos = outline.clone();
        pos.extend(outline.iter().map(|p| *p + DVec3::Z));
        let nn = n as i64;
        let mut sizes = vec![nn, nn];
        let mut idx: Vec<i64> = (0..nn).rev().collect();
        idx.extend(nn..2 * nn);
        for i in 0..nn {
            sizes.push(4);
            idx.extend([i, (i + 1) % nn, nn + (i + 1) % nn, nn + i]);
        }
        let prism = Mesh::from_polygons(pos, &sizes, &idx, BuildOptions::default()).unwrap();
        let t = prism.triangulate();
        assert_closed(&prism, &t);
        assert!(t.points.is_empty(), "{name}: {} points added to the prism", t.points.len());
        let sheet = two_sided(outline);
        let t = sheet.triangulate();
        assert_closed(&sheet, &t);
        // (every spike's base chord is forced on both sides: those need points)
        if name == "spiral" {
            assert!(t.points.len() < n / 20, "{name}: {} points added to the sheet", t.points.len());
        }
    }
}

#[test]
fn star_clip_is_linear_and_right() {
    let p: Vec<DVec2> = star(1000, 0.3).iter().map(|q| q.truncate()).collect();
    let mut out = Vec::new();
    assert!(star_from_mean(&p) && star_clip(&p, &mut out));
    assert!(is_disk_triangulation(1000, &out));
    assert!(out.iter().all(|t| cross2(p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]) > 0.0));
}

#[test]
fn bent_hexagon() {
    // a hexagon folded along its 0–3 axis: non-planar
    let pos: Vec<DVec3> = (0..6)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 6.0;
            let (x, y) = (a.cos(), a.sin());
            DVec3::new(x, y, 0.6 * y.abs())
        })
        .collect();
    let m = two_sided(pos.clone());
    let t = m.triangulate();
    assert_closed(&m, &t);
    // bent past BENT: both sides fanned around their centroids
    assert_eq!((t.points.len(), t.tris.len()), (2, 12));
    // gently bent: diagonals only
    let flat: Vec<DVec3> = pos.iter().map(|p| DVec3::new(p.x, p.y, p.z * 0.1)).collect();
    let m = two_sided(flat);
    let t = m.triangulate();
    assert_closed(&m, &t);
    assert_eq!((t.points.len(), t.tris.len()), (0, 8));
}

#[test]
fn exact_search_finds_the_one_allowed_triangulation() {
    let hex: Vec<DVec2> = (0..6).map(|k| DVec2::from_angle(std::f64::consts::TAU * k as f64 / 6.0)).collect();
    // only the fan from corner 3 is allowed (diagonals 3–5, 3–0, 3–1)
    let allowed = |i: usize, j: usize| i.min(j) == 3 || i.max(j) == 3;
    let mut out = Vec::new();
    assert!(exact(&hex, Shape::Convex, &|i, j| !allowed(i, j), &mut out));
    assert!(is_disk_triangulation(6, &out));
    for t in &out {
        assert!(t.contains(&3), "{t:?}");
    }
    // a quad with one diagonal forbidden takes the other
    let quad = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];
    assert!(exact(&quad, Shape::Convex, &|i, j| (i, j) == (0, 2), &mut out));
    assert!(out.iter().all(|t| t.contains(&1) && t.contains(&3)));
    // every diagonal forbidden: none
    assert!(!exact(&quad, Shape::Convex, &|_, _| true, &mut out));
}

#[test]
fn quad_with_both_diagonals_taken_gets_a_point() {
    // cube face 0 (a, b, c, d): add edges a–c and b–d through other faces
    let mut m = primitives::cube();
    let quad: Vec<u32> = m.face_vertices(FaceId(0)).map(|v| v.0).collect();
    let outside = |m: &Mesh, v: u32, avoid: &[u32]| {
        m.halfedges().find(|&h| m.vertex(h).0 == v && !m.face_vertices(m.face(h)).any(|w| avoid.contains(&w.0))).unwrap()
    };
    for (a, b) in [(quad[0], quad[2]), (quad[1], quad[3])] {
        // corners of a and b in faces without the other quad corners
        let others: Vec<u32> = quad.iter().copied().filter(|&v| v != a && v != b).collect();
        let (ha, hb): (HalfedgeId, HalfedgeId) = (outside(&m, a, &[b]), outside(&m, b, &[a]));
        let _ = others;
        m.insert_edge(Corner::Halfedge(ha), Corner::Halfedge(hb)).unwrap();
    }
    m.validate().unwrap();
    let f = m.faces().find(|&f| { let mut v: Vec<u32> = m.face_vertices(f).map(|v| v.0).collect(); v.sort(); let mut q = quad.clone(); q.sort(); v == q }).unwrap();
    assert!(is_edge(&m, quad[0], quad[2]) && is_edge(&m, quad[1], quad[3]));
    let t = m.triangulate();
    let mine: Vec<[u32; 3]> = t.tris.iter().zip(&t.tri_face).filter(|(_, &g)| g == f.0).map(|(t, _)| *t).collect();
    assert_eq!(mine.len(), 4);
    let nv = m.n_vertices() as u32;
    assert!(mine.iter().all(|t| t.contains(&nv.max(t[0]).max(t[1]).max(t[2])) && t.iter().any(|&v| v >= nv)));
    assert!(!t.points.is_empty());
    let p = t.points[(mine[0].iter().copied().max().unwrap() - nv) as usize];
    let c = quad.iter().map(|&v| m.position(VertexId(v))).sum::<DVec3>() / 4.0;
    assert!(p.distance(c) < 1e-12, "the point is the face's centroid");
}

#[test]
fn retry_splits_forbidden_diagonals_of_non_star_faces() {
    // a comb of twelve teeth (more than EXACT_LIMIT corners): no point sees
    // the whole face, every diagonal forbidden
    let mut p = vec![DVec2::new(0.0, 0.0), DVec2::new(23.0, 0.0)];
    for k in (0..12).rev() {
        let x = 2.0 * k as f64;
        p.extend([DVec2::new(x + 1.0, 3.0), DVec2::new(x, 3.0)]);
        if k > 0 {
            p.extend([DVec2::new(x, 1.0), DVec2::new(x - 1.0, 1.0)]);
        }
    }
    let n = p.len();
    assert!(n > EXACT_LIMIT);
    let cyc: Vec<u32> = (0..n as u32).collect();
    let pos: Vec<DVec3> = p.iter().map(|q| q.extend(0.0)).collect();
    let mut first = Vec::new();
    ear_clip_quadratic(&p, &mut first);
    assert!(is_disk_triangulation(n, &first));
    let (mut out, mut added) = (Vec::new(), Vec::new());
    retry(&cyc, &pos, &p, Shape::NonConvex, &first, &|_, _| true, &mut out, &mut added);
    // one point per diagonal (n − 3), each fanned by four triangles
    assert_eq!(added.len(), n - 3);
    assert_eq!(out.len(), n - 2 + 2 * (n - 3));
    let q = |k: u32| if (k as usize) < n { pos[k as usize] } else { added[k as usize - n] };
    let area: f64 = out
        .iter()
        .map(|t| {
            let z = (q(t[1]) - q(t[0])).cross(q(t[2]) - q(t[0])).z;
            assert!(z > 0.0, "{t:?}");
            z / 2.0
        })
        .sum();
    let exact: f64 = (0..n).map(|k| p[k].perp_dot(p[(k + 1) % n]) / 2.0).sum();
    assert!((area - exact).abs() < 1e-9, "{area} vs {exact}");
    // no diagonal between two corners is left
    for t in &out {
        for k in 0..3 {
            let (i, j) = (t[k] as usize, t[(k + 1) % 3] as usize);
            assert!(i >= n || j >= n || (i + 1) % n == j || (j + 1) % n == i, "diagonal {i}-{j}");
        }
    }
}

#[test]
fn simple_operator_outputs_are_closed() {
    // connect_edges and create_pipe between cube faces
    let mut m = primitives::cube();
    let (h1, h2) = (m.face_halfedge(FaceId(0)).unwrap(), m.face_halfedge(FaceId(1)).unwrap());
    if m.connect_edges(h1, h2).is_ok() {
        m.validate().unwrap();
        if is_simple(&m) {
            assert_closed(&m, &m.triangulate());
        }
    }
    let mut m = primitives::cube();
    let top: Vec<VertexId> = m.face_vertices(FaceId(0)).collect();
    let far = m.faces().find(|&f| m.face_vertices(f).all(|v| !top.contains(&v))).unwrap();
    let (a, b) = (m.face_halfedge(FaceId(0)).unwrap(), m.face_halfedge(far).unwrap());
    m.create_pipe(Corner::Halfedge(a), Corner::Halfedge(b)).unwrap();
    m.validate().unwrap();
    assert!(is_simple(&m));
    assert_closed(&m, &m.triangulate());
}

#[test]
fn deterministic_across_thread_counts() {
    let m = schemes::doo_sabin::doo_sabin(&schemes::sierpinski::sierpinski_iterated(&primitives::cube(), 2).unwrap()).unwrap();
    let a = m.triangulate();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let b = pool.install(|| m.triangulate());
    assert_eq!(a, b);
}


#[test]
fn multi_edges_are_split() {
    // Catmull-Clark of a Sierpinski tetrahedron: each subdivided zero-length
    // self-loop leaves two edges between its vertex and its edge point
    let f = schemes::sierpinski::sierpinski_iterated(&primitives::tetrahedron(), 1).unwrap();
    let m = schemes::catmull_clark::catmull_clark(&f).unwrap();
    let copies = multi_edge_copies(&m);
    assert_eq!(copies.len(), 6);
    let t = m.triangulate();
    assert_closed(&m, &t);
    for (k, &e) in copies.iter().enumerate() {
        let h = EdgeId(e).halfedge();
        let mid = (m.position(m.vertex(h)) + m.position(m.head(h))) / 2.0;
        assert_eq!(t.points[k], mid);
    }
}




/// `triangulate_faces` of every face is `triangulate`; of a patch of faces
/// and every face around its vertices, the patch's triangles are the whole
/// mesh's (as points: added points are numbered by the listed faces), on
/// meshes with multi-edges, colliding diagonals and retried faces.
#[test]
fn listed_faces_triangulate_as_the_whole_mesh() {
    let mut corpus: Vec<Mesh> = crate::schemes::hosts::test_meshes::corpus().into_iter().map(|(_, m)| m).collect();
    let f = schemes::sierpinski::sierpinski_iterated(&primitives::tetrahedron(), 2).unwrap();
    corpus.push(schemes::catmull_clark::catmull_clark(&f).unwrap());
    corpus.push(schemes::doo_sabin::doo_sabin(&f).unwrap());
    let mut c = primitives::cube();
    c.delete_edge(EdgeId(3)).unwrap();
    corpus.push(c);
    corpus.push(two_sided(star(40, 0.5)));
    let (mut checked, mut with_points) = (0, 0);
    for (k, m) in corpus.iter().enumerate() {
        let all: Vec<u32> = (0..m.n_faces() as u32).filter(|&f| !m.is_hole(FaceId(f))).collect();
        let whole = m.triangulate();
        assert_eq!(triangulate_faces(m, &all), whole, "mesh {k}");
        // the patch: every third face; listed: it and every face around its vertices
        let patch: Vec<u32> = all.iter().copied().filter(|f| f % 3 == 0).collect();
        let mut near = vec![false; m.n_faces()];
        mark_faces_around(m, patch.iter().map(|&f| FaceId(f)), &mut near);
        let listed: Vec<u32> = all.iter().copied().filter(|&f| near[f as usize]).collect();
        let part = triangulate_faces(m, &listed);
        let as_points = |t: &Triangulation, f: u32| -> Vec<[[u64; 3]; 3]> {
            let at = |i: u32| if (i as usize) < m.n_vertices() { m.positions()[i as usize] } else { t.points[i as usize - m.n_vertices()] };
            t.tris.iter().zip(&t.tri_face).filter(|(_, &g)| g == f).map(|(tr, _)| tr.map(|i| at(i).to_array().map(f64::to_bits))).collect()
        };
        for &f in &patch {
            assert_eq!(as_points(&part, f), as_points(&whole, f), "mesh {k}, face {f}");
            checked += 1;
        }
        with_points += (!whole.points.is_empty()) as usize;
    }
    assert!(checked > 100 && with_points >= 3, "{checked} faces, {with_points} meshes with added points");
}

#[test]
fn grouped_retry_equals_the_sequential_pass() {
    // meshes with many colliding faces: small ones sharing vertex pairs
    // (smoothed Sierpinski outputs, merged faces) and large ones (both
    // sides of a star, > PAIR_LIMIT corners); the big one spans many tasks
    let mut corpus = vec![two_sided(star(40, 0.5)), two_sided(star(7, 0.5))];
    for base in [primitives::tetrahedron(), primitives::cube()] {
        for e in 0..base.n_edges() {
            let mut m = base.clone();
            m.delete_edge(EdgeId(e as u32)).unwrap();
            corpus.push(m);
        }
    }
    for s in [primitives::tetrahedron(), primitives::cube(), primitives::dodecahedron()] {
        for n in 1..=3 {
            let f = schemes::sierpinski::sierpinski_iterated(&s, n).unwrap();
            corpus.push(schemes::doo_sabin::doo_sabin(&f).unwrap());
            corpus.push(schemes::catmull_clark::catmull_clark(&f).unwrap());
        }
    }
    let big = schemes::catmull_clark::catmull_clark(&schemes::sierpinski::sierpinski_iterated(&primitives::cube(), 5).unwrap()).unwrap();
    corpus.push(big);
    let mut redone_faces = 0;
    for (k, m) in corpus.iter().enumerate() {
        let (a, b) = (triangulate_with(m, true, None), triangulate_with(m, false, None));
        assert_eq!(a, b, "mesh {k}");
        redone_faces += a.points.len();
    }
    // the corpus does exercise the retry (added points only come from it here)
    assert!(redone_faces > 1000, "{redone_faces}");
}

/// The one-walk fast path agrees with the check and the write it replaced:
/// the same answer on the corpus, open meshes and multi-edged triangle
/// meshes, and the same triangles where it says yes.
#[test]
fn write_if_plain_agrees_with_check_then_write() {
    use crate::schemes::hosts::test_meshes as tm;
    let mut meshes = tm::corpus();
    meshes.extend(tm::open_meshes());
    meshes.push(("ico_loop", schemes::loop_subdivision::loop_subdivision(&primitives::icosahedron()).unwrap()));
    meshes.push(("torus_loop", schemes::loop_subdivision::loop_subdivision(&primitives::torus(6, 5, 1.0, 0.3).unwrap()).unwrap()));
    let mut yes = 0;
    for (name, m) in &meshes {
        let mut got = vec![-1i64; 3 * m.n_faces()];
        let plain = m.write_triangle_faces_if_plain(&mut got);
        assert_eq!(plain, m.triangles_are_faces(), "{name}");
        if plain {
            let mut want = vec![0i64; 3 * m.n_faces()];
            m.write_triangle_faces(&mut want);
            assert_eq!(got, want, "{name}");
            yes += 1;
        }
    }
    assert!(yes >= 2);
}

/// Large strictly convex faces are halved, not fanned: a disk
/// triangulation at every size, positive triangles tiling the cap, a closed
/// triangle mesh, and boxes that overlap in O(n log n) pairs (a fan's boxes
/// all hold its first corner: n²/2 pairs).
#[test]
fn large_convex_faces_are_halved() {
    let mut out = Vec::new();
    for n in 3..300 {
        halving(n, &mut out);
        assert!(is_disk_triangulation(n, &out), "{n}");
    }
    for n in [HALVING_MIN + 1, 100, 1000, 4096] {
        let m = crate::schemes::conway::seeds::prism(n).unwrap();
        let t = m.triangulate();
        assert_closed(&m, &t);
        assert!(t.points.is_empty());
        let cap = m.faces().find(|&f| m.face_degree(f) == n).unwrap();
        // face 0 of the tiling check is the cap, seen from +z
        let pos = m.positions();
        let tris: Vec<[u32; 3]> = t.tris.iter().zip(&t.tri_face).filter(|(_, &f)| f == cap.0).map(|(t, _)| *t).collect();
        assert_eq!(tris.len(), n - 2);
        let normal = pos[tris[0][0] as usize].z.signum();
        let mut area = 0.0;
        for tri in &tris {
            let z = (pos[tri[1] as usize] - pos[tri[0] as usize]).cross(pos[tri[2] as usize] - pos[tri[0] as usize]).z * normal;
            assert!(z > 0.0, "{n}: inverted or flat triangle {tri:?}");
            area += z / 2.0;
        }
        let cyc: Vec<DVec3> = m.face_vertices(cap).map(|v| pos[v.idx()]).collect();
        let exact: f64 = (0..n).map(|k| cyc[k].truncate().perp_dot(cyc[(k + 1) % n].truncate()) / 2.0).sum::<f64>().abs();
        assert!((area - exact).abs() < 1e-9 * exact, "{n}: {area} vs {exact}");
        let boxes: Vec<(DVec3, DVec3)> = tris.iter().map(|t| {
            let q = t.map(|v| pos[v as usize]);
            (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]))
        }).collect();
        let mut pairs = 0usize;
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                pairs += !(a.0.cmpgt(b.1).any() || b.0.cmpgt(a.1).any()) as usize;
            }
        }
        let bound = 4 * n * (usize::BITS - n.leading_zeros()) as usize;
        assert!(pairs <= bound, "{n}: {pairs} overlapping boxes, bound {bound}");
    }
}

//! Counts, face sizes, genus and validity of every operator over the
//! scheme corpus; Hart's counts of named polyhedra; chirality; the parser.

use super::*;
use crate::mesh::Histogram;
use crate::primitives;
use crate::schemes::hosts::test_meshes::*;

const ALL: &[Op] = &[
    Op::Dual,
    Op::Ambo,
    Op::Truncate(None),
    Op::Kis(None),
    Op::Join,
    Op::Expand,
    Op::Ortho,
    Op::Gyro,
    Op::Snub,
    Op::Bevel,
    Op::Meta,
    Op::Needle(None),
    Op::Zip(None),
    Op::Chamfer,
    Op::Subdivide,
    Op::Whirl,
    Op::Volute,
    Op::Propellor,
    Op::Quinto,
    Op::Loft(None),
    Op::Reflect,
];

/// Face degrees and valences of the non-point-sphere elements.
fn sizes(m: &Mesh) -> (Vec<usize>, Vec<usize>) {
    let fd = m.faces().filter(|&f| !is_point_face(m, f.idx())).map(|f| m.face_degree(f)).collect();
    let vd = m.vertices().filter(|&v| m.point_sphere_face(v).is_none()).map(|v| m.valence(v)).collect();
    (fd, vd)
}

/// The face-size histogram the module docs' table states for `op` on `m`.
fn expected_faces(op: Op, m: &Mesh) -> Histogram {
    let (fd, vd) = sizes(m);
    let e = m.n_edges();
    let mut h = Histogram::new();
    let mut add = |s: usize, k: usize| *h.entry(s).or_default() += k;
    let (f1, f2, v1, v2) = (|| fd.iter().copied(), || fd.iter().map(|x| 2 * x), || vd.iter().copied(), || vd.iter().map(|x| 2 * x));
    use Op::*;
    match op {
        Dual => v1().for_each(|s| add(s, 1)),
        Ambo => f1().chain(v1()).for_each(|s| add(s, 1)),
        Truncate(_) => f2().chain(v1()).for_each(|s| add(s, 1)),
        Kis(_) | Needle(_) => add(3, 2 * e),
        Join => add(4, e),
        Expand => {
            f1().chain(v1()).for_each(|s| add(s, 1));
            add(4, e)
        }
        Ortho => add(4, 2 * e),
        Gyro => add(5, 2 * e),
        Snub => {
            f1().chain(v1()).for_each(|s| add(s, 1));
            add(3, 2 * e)
        }
        Bevel => {
            f2().chain(v2()).for_each(|s| add(s, 1));
            add(4, e)
        }
        Meta => add(3, 4 * e),
        Zip(_) => f1().chain(v2()).for_each(|s| add(s, 1)),
        Chamfer => {
            f1().for_each(|s| add(s, 1));
            add(6, e)
        }
        Subdivide => {
            f1().for_each(|s| add(s, 1));
            add(3, 2 * e)
        }
        Whirl => {
            f1().for_each(|s| add(s, 1));
            add(6, 2 * e)
        }
        Volute => {
            f1().for_each(|s| add(s, 1));
            add(3, 4 * e)
        }
        Propellor | Loft(_) => {
            f1().for_each(|s| add(s, 1));
            add(4, 2 * e)
        }
        Quinto => {
            f1().for_each(|s| add(s, 1));
            add(5, 2 * e)
        }
        Reflect => f1().for_each(|s| add(s, 1)),
    }
    h.retain(|_, k| *k > 0);
    h
}

fn no_points_histogram(m: &Mesh) -> Histogram {
    let mut h = Histogram::new();
    for s in sizes(m).0 {
        *h.entry(s).or_default() += 1;
    }
    h
}

#[test]
fn every_operator_on_the_corpus() {
    for &op in ALL {
        check_on_corpus(
            |m| op.apply(m),
            |_, (v, e, f)| {
                let p = op.predict((v as u64, e as u64, f as u64));
                (p.0 as usize, p.1 as usize, p.2 as usize)
            },
            |name, m, r| {
                assert_eq!(no_points_histogram(r), expected_faces(op, m), "{op:?} on {name}");
                assert_eq!(r.euler_characteristic(), m.euler_characteristic(), "{op:?} on {name}");
            },
        );
    }
}

#[test]
fn operators_on_genus_3_and_several_components() {
    let g3 = primitives::genus_surface(3).unwrap();
    let two = {
        let (ca, cb) = (primitives::cube(), primitives::torus(6, 4, 1.0, 0.3).unwrap());
        let (a, b) = (ca.to_polygons(), cb.to_polygons());
        let n = ca.n_vertices() as i64;
        let pos: Vec<glam::DVec3> = ca.positions().iter().chain(cb.positions()).copied().collect();
        let sizes: Vec<i64> = a.sizes.iter().chain(&b.sizes).map(|&s| s as i64).collect();
        let idx: Vec<i64> = a.indices.iter().map(|&i| i as i64).chain(b.indices.iter().map(|&i| i as i64 + n)).collect();
        Mesh::from_polygons(pos, &sizes, &idx, crate::mesh::BuildOptions::default()).unwrap()
    };
    for m in [g3, two] {
        for &op in ALL {
            let r = op.apply(&m).unwrap();
            r.validate().unwrap();
            let p = op.predict((m.n_vertices() as u64, m.n_edges() as u64, m.n_faces() as u64));
            assert_eq!((r.n_vertices() as u64, r.n_edges() as u64, r.n_faces() as u64), p, "{op:?}");
            assert_eq!((r.genus(), r.n_components()), (m.genus(), m.n_components()), "{op:?}");
        }
    }
}

/// `kN`, `lN` act on the N-sided faces, `tN`, `nN` on the N-valent vertices.
#[test]
fn numbered_operators_choose() {
    for (name, m) in corpus() {
        let (fd, vd) = sizes(&m);
        let ps = n_point_spheres(&m);
        let (v, e, f) = (m.n_vertices() - ps, m.n_edges(), m.n_faces() - ps);
        for n in [1, 2, 3, 4, 5] {
            let (s, sig) = (fd.iter().filter(|&&d| d == n).count(), fd.iter().filter(|&&d| d == n).sum::<usize>());
            let (sv, sigv) = (vd.iter().filter(|&&d| d == n).count(), vd.iter().filter(|&&d| d == n).sum::<usize>());
            let runs = [
                (Op::Kis(Some(n)), (v + s, e + sig, f - s + sig)),
                (Op::Loft(Some(n)), (v + sig, e + 2 * sig, f + sig)),
                (Op::Zip(Some(n)), (f - s + sig, e + sig, v + s)),
                (Op::Needle(Some(n)), (f + sv, e + sigv, v - sv + sigv)),
                (Op::Truncate(Some(n)), (v - sv + sigv, e + sigv, f + sv)),
            ];
            for (op, want) in runs {
                let r = op.apply(&m).unwrap();
                check_output(&format!("{op:?} on {name}"), &m, &r, want);
            }
        }
    }
    // t5 on the icosahedron truncates all its (5-valent) vertices, t3 none
    let i = primitives::icosahedron();
    assert_eq!(counts(&Op::Truncate(Some(5)).apply(&i).unwrap()), (60, 90, 32));
    assert_eq!(Op::Truncate(Some(3)).apply(&i).unwrap().to_polygons(), dual(&dual(&i).unwrap()).unwrap().to_polygons());
}

fn run(s: &str) -> (usize, usize, usize) {
    let m = conway(s, None).unwrap_or_else(|e| panic!("{s}: {e}"));
    m.validate().unwrap();
    assert!(m.signed_volume() > 0.0, "{s} is outward");
    counts(&m)
}

/// V, E, F of named polyhedra (Hart's and Wikipedia's tables).
#[test]
fn named_polyhedra() {
    let table: &[(&str, (usize, usize, usize))] = &[
        ("T", (4, 6, 4)),
        ("C", (8, 12, 6)),
        ("O", (6, 12, 8)),
        ("D", (20, 30, 12)),
        ("I", (12, 30, 20)),
        ("aT", (6, 12, 8)),
        ("aC", (12, 24, 14)),
        ("aD", (30, 60, 32)),
        ("tT", (12, 18, 8)),
        ("tC", (24, 36, 14)),
        ("tO", (24, 36, 14)),
        ("tD", (60, 90, 32)),
        ("tI", (60, 90, 32)),
        ("kT", (8, 18, 12)),
        ("kC", (14, 36, 24)),
        ("kO", (14, 36, 24)),
        ("kD", (32, 90, 60)),
        ("kI", (32, 90, 60)),
        ("jC", (14, 24, 12)),
        ("jD", (32, 60, 30)),
        ("eC", (24, 48, 26)),
        ("eD", (60, 120, 62)),
        ("eI", (60, 120, 62)),
        ("oC", (26, 48, 24)),
        ("oD", (62, 120, 60)),
        ("bC", (48, 72, 26)),
        ("bO", (48, 72, 26)),
        ("bD", (120, 180, 62)),
        ("mC", (26, 72, 48)),
        ("mD", (62, 180, 120)),
        ("sC", (24, 60, 38)),
        ("sD", (60, 150, 92)),
        ("sT", (12, 30, 20)),
        ("gT", (20, 30, 12)),
        ("gC", (38, 60, 24)),
        ("gD", (92, 150, 60)),
        ("nC", (14, 36, 24)),
        ("zD", (60, 90, 32)),
        ("cC", (32, 48, 18)),
        ("cT", (16, 24, 10)),
        ("cD", (80, 120, 42)),
        ("uT", (10, 24, 16)),
        ("pC", (32, 60, 30)),
        ("wT", (28, 42, 16)),
        ("qC", (44, 72, 30)),
        ("lC", (32, 60, 30)),
        ("P5", (10, 15, 7)),
        ("A5", (10, 20, 12)),
        ("Y5", (6, 10, 6)),
        ("dA5", (12, 20, 10)),
        ("dtkC", (38, 108, 72)),
        ("t5dD", (60, 90, 32)),
        ("k5aD", (42, 120, 80)),
    ];
    for &(s, want) in table {
        assert_eq!(run(s), want, "{s}");
    }
    // sT is the icosahedron, gT the dodecahedron, aT the octahedron
    assert_eq!(conway("sT", None).unwrap().face_size_histogram(), primitives::icosahedron().face_size_histogram());
    assert_eq!(conway("gT", None).unwrap().face_size_histogram(), primitives::dodecahedron().face_size_histogram());
    let ti = conway("tI", None).unwrap().face_size_histogram();
    assert_eq!((ti.get(&5), ti.get(&6)), (Some(&12), Some(&20)));
}

/// u is the dual of chamfer: `u = dcd` in topology.
#[test]
fn subdivide_is_dcd() {
    for (name, m) in corpus() {
        let u = subdivide(&m).unwrap();
        let dcd = dual(&chamfer(&dual(&m).unwrap()).unwrap()).unwrap();
        assert_eq!((counts(&u), u.face_size_histogram(), u.valence_histogram()), (counts(&dcd), dcd.face_size_histogram(), dcd.valence_histogram()), "{name}");
    }
}

/// Every face as its cycle of quantized positions, starting at its least
/// corner (rotation only, so orientation counts), sorted.
fn oriented_faces(m: &Mesh) -> Vec<Vec<[i64; 3]>> {
    let q = |p: glam::DVec3| [(p.x * 1e9).round() as i64, (p.y * 1e9).round() as i64, (p.z * 1e9).round() as i64];
    let mut out: Vec<Vec<[i64; 3]>> = m
        .faces()
        .map(|f| {
            let c: Vec<[i64; 3]> = m.face_vertices(f).map(|v| q(m.position(v))).collect();
            let k = (0..c.len()).min_by_key(|&i| c[i]).unwrap();
            c[k..].iter().chain(&c[..k]).copied().collect()
        })
        .collect();
    out.sort();
    out
}

/// The same surface with other vertex ids and face starts: faces listed
/// backwards, each from its second corner, vertices in reverse order.
fn renumbered(m: &Mesh) -> Mesh {
    let p = m.to_polygons();
    let nv = m.n_vertices();
    let pos: Vec<glam::DVec3> = m.positions().iter().rev().copied().collect();
    let (mut sizes, mut idx, mut at) = (Vec::new(), Vec::new(), 0usize);
    let mut faces = Vec::new();
    for &s in &p.sizes {
        faces.push(&p.indices[at..at + s as usize]);
        at += s as usize;
    }
    for f in faces.iter().rev() {
        sizes.push(f.len() as i64);
        idx.extend(f[1..].iter().chain(&f[..1]).map(|&v| (nv - 1 - v as usize) as i64));
    }
    Mesh::from_polygons(pos, &sizes, &idx, crate::mesh::BuildOptions::default()).unwrap()
}

/// The side of the diagonal centre → input vertex each gyro pentagon lies
/// on, seen from outside: `n · ((v − c) × (m − c))` with m the pentagon's
/// centroid. Gyro's output keeps the input vertices first and the face
/// centres next, so both are found by index.
fn gyro_twists(input: &Mesh, g: &Mesh) -> Vec<f64> {
    let (nv, nf) = (input.n_vertices() as u32, input.n_faces() as u32);
    g.faces()
        .map(|f| {
            let vs: Vec<u32> = g.face_vertices(f).map(|v| v.0).collect();
            let ps: Vec<glam::DVec3> = vs.iter().map(|&v| g.positions()[v as usize]).collect();
            let mid = ps.iter().sum::<glam::DVec3>() / ps.len() as f64;
            let c = ps[vs.iter().position(|&v| (nv..nv + nf).contains(&v)).unwrap()];
            let v = ps[vs.iter().position(|&v| v < nv).unwrap()];
            g.face_newell(f).dot((v - c).cross(mid - c))
        })
        .collect()
}

/// Chirality: gyro turns the same way seen from outside on every face of
/// every genus, its mirror image (r g) turns the other way, gyro of a
/// mirror image (g r) turns like gyro again (orientation kept, never
/// flipped), and nothing depends on vertex ids or face starts.
#[test]
fn chirality_follows_orientation() {
    for m in [primitives::cube(), primitives::genus_surface(2).unwrap()] {
        let g = gyro(&m).unwrap();
        g.validate().unwrap();
        let tw = gyro_twists(&m, &g);
        let sign = tw[0].signum();
        assert!(tw.iter().all(|t| t.signum() == sign && t.abs() > 1e-9), "one handedness all over");
        let mirror = reflect(&m).unwrap();
        assert!(gyro_twists(&mirror, &gyro(&mirror).unwrap()).iter().all(|t| t.signum() == sign), "g r keeps the handedness");
        let rg = reflect(&g).unwrap();
        // r keeps vertex and face ids, so the layout of g holds for r g
        assert!(gyro_twists(&m, &rg).iter().all(|t| t.signum() == -sign), "r g is the other hand");
        assert_ne!(oriented_faces(&g), oriented_faces(&rg));
        for op in [Op::Gyro, Op::Snub, Op::Whirl, Op::Propellor, Op::Volute] {
            assert_eq!(oriented_faces(&op.apply(&renumbered(&m)).unwrap()), oriented_faces(&op.apply(&m).unwrap()), "{op:?}");
        }
    }
    // the cube is its own mirror image (negation maps it onto itself, faces
    // reversed): g of it is g of the cube, with other ids
    let c = primitives::cube();
    assert_eq!(oriented_faces(&gyro(&reflect(&c).unwrap()).unwrap()), oriented_faces(&gyro(&c).unwrap()));
    // meshes polygon lists cannot carry: r r renumbers half-edges and face starts
    for m in [cube_with_self_loop(), cube_with_two_gon(), sierpinski_tetrahedron()] {
        let rr = reflect(&reflect(&m).unwrap()).unwrap();
        for op in [Op::Gyro, Op::Snub, Op::Whirl, Op::Propellor, Op::Volute] {
            let (a, b) = (op.apply(&rr).unwrap(), op.apply(&m).unwrap());
            a.validate().unwrap();
            assert_eq!(oriented_faces(&a), oriented_faces(&b), "{op:?}");
        }
    }
    assert!(gyro(&c).unwrap().signed_volume() > 0.0 && reflect(&gyro(&c).unwrap()).unwrap().signed_volume() > 0.0);
}

#[test]
fn reflect_twice_is_identity() {
    for (name, m) in corpus() {
        let r = reflect(&reflect(&m).unwrap()).unwrap();
        assert_eq!(oriented_faces(&r), oriented_faces(&m), "{name}");
    }
}

#[test]
fn parser() {
    let n = parse("dt5kC").unwrap();
    assert_eq!(n.ops, vec![Op::Kis(None), Op::Truncate(Some(5)), Op::Dual]);
    assert_eq!(n.seed, Some(Seed::Cube));
    assert_eq!(parse("tk").unwrap(), Notation { ops: vec![Op::Kis(None), Op::Truncate(None)], seed: None });
    assert_eq!(parse("P12").unwrap().seed, Some(Seed::Prism(12)));
    let bad = [
        ("dxC", "position 1 of \"dxC\": unknown letter 'x'"),
        ("d C", "position 1 of \"d C\": unexpected character ' '"),
        ("5C", "position 0 of \"5C\": number '5' without a letter before it"),
        ("Ct", "position 0 of \"Ct\": seed 'C' must be the rightmost letter"),
        ("a3C", "operator 'a' takes no number"),
        ("P", "seed 'P' needs its number of sides"),
        ("A2", "at least 3 sides"),
        ("C4", "seed 'C' takes no number"),
        ("t0C", "number 0 after 't' is outside"),
        ("k99999999999999999999999C", "is outside"),
    ];
    for (s, want) in bad {
        let e = parse(s).unwrap_err().to_string();
        assert!(e.contains(want), "{s}: {e}");
    }
    assert!(conway("tk", None).unwrap_err().to_string().contains("no seed"));
    assert!(conway("tkC", Some(&primitives::cube())).unwrap_err().to_string().contains("seed mesh was given too"));
    assert_eq!(counts(&conway("tk", Some(&primitives::cube())).unwrap()), counts(&conway("tkC", None).unwrap()));
    assert_eq!(conway("", Some(&primitives::cube())).unwrap().to_polygons(), primitives::cube().to_polygons());
}

#[test]
fn open_meshes_are_refused() {
    for &op in ALL {
        let e = op.apply(&cube_with_hole()).unwrap_err().to_string();
        assert!(e.contains("boundary loop"), "{op:?}: {e}");
    }
}

#[test]
fn budget_refuses_a_huge_chain() {
    let e = conway("kkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkC", None).unwrap_err().to_string();
    assert!(e.contains("31-bit"), "{e}");
}

#[test]
fn seeds_are_outward() {
    for n in [3, 4, 5, 8] {
        for s in [Seed::Prism(n), Seed::Antiprism(n), Seed::Pyramid(n)] {
            let m = s.build().unwrap();
            m.validate().unwrap();
            assert!(m.signed_volume() > 0.0, "{s:?}");
            assert_eq!(counts(&m), s.counts(), "{s:?}");
        }
    }
    assert!(seeds::prism(2).is_err());
}

#[test]
fn canonical_form() {
    for s in ["C", "tI", "dtkC", "gC", "P5"] {
        let m = conway(s, None).unwrap();
        let (c, r) = canonical::canonicalize(&m, 5000, 1e-14).unwrap();
        c.validate().unwrap();
        assert!(r < 1e-6, "{s}: residual {r}");
        assert_eq!(c.to_polygons().indices, m.to_polygons().indices);
        // every edge tangent to the unit sphere
        for e in 0..c.n_edges() {
            let (a, b) = (c.positions()[c.he_vert[2 * e] as usize], c.positions()[c.he_vert[2 * e + 1] as usize]);
            let d = b - a;
            let t = a - d * (d.dot(a) / d.length_squared());
            assert!((t.length() - 1.0).abs() < 1e-5, "{s}");
        }
    }
    // the cube [-1, 1]³ is canonical once scaled; the raw tI and kC are not
    assert!(canonical::canonicalize(&primitives::cube(), 0, 0.0).unwrap().1 < 1e-12);
    for s in ["tI", "kC"] {
        let r = canonical::canonicalize(&conway(s, None).unwrap(), 0, 0.0).unwrap().1;
        assert!(r > 1e-3, "{s}: {r}");
    }
    assert!(canonical::canonicalize(&primitives::cube(), 10, f64::NAN).is_err());
    assert!(canonical::canonicalize(&cube_with_hole(), 10, 0.0).is_err());
}

/// The fused builds (`dual_ambo::join`, `ortho`, `bevel`, `dual_kis`, `truncate`, `dual_chiral`, `ambo::expand`, `kis_of`, and
/// the operators made of them) give what the compositions they replace give: the same mesh,
/// face parents and errors, on the scheme corpus (non-convex faces,
/// self-loops, two-gons, genus 3, point-spheres) and on open meshes (which
/// take the composition and are refused).
#[test]
fn fused_builds_are_their_compositions() {
    use crate::schemes::face_parents::traced;
    type F = Box<dyn Fn(&Mesh) -> Result<Mesh>>;
    let mut ms = crate::schemes::topmod::tests::meshes();
    ms.push(("one_gon_two_gon", one_gon_two_gon_cube()));
    ms.extend(open_meshes());
    let pairs: Vec<(&str, F, F)> = vec![
        ("join", Box::new(dual_ambo::join), Box::new(|m| dual(&ambo(m)?))),
        ("ortho", Box::new(|m| Op::Ortho.apply(m)), Box::new(|m| dual(&ambo(&ambo(m)?)?))),
        ("bevel", Box::new(|m| Op::Bevel.apply(m)), Box::new(|m| dual(&kis(&dual(&ambo(m)?)?, None)?))),
        ("meta", Box::new(|m| Op::Meta.apply(m)), Box::new(|m| kis(&dual(&ambo(m)?)?, None))),
        ("zip", Box::new(|m| Op::Zip(None).apply(m)), Box::new(|m| dual(&kis(m, None)?))),
        ("truncate", Box::new(|m| Op::Truncate(None).apply(m)), Box::new(|m| dual(&kis(&dual(m)?, None)?))),
        ("snub", Box::new(|m| Op::Snub.apply(m)), Box::new(|m| dual(&chiral::gyro(m)?))),
        ("expand", Box::new(|m| Op::Expand.apply(m)), Box::new(|m| ambo(&ambo(m)?))),
        ("needle", Box::new(|m| Op::Needle(None).apply(m)), Box::new(|m| kis(&dual(m)?, None))),
        ("volute", Box::new(|m| Op::Volute.apply(m)), Box::new(|m| dual(&chiral::whirl(&dual(m)?)?))),
        ("dual whirl", Box::new(dual_chiral::dual_whirl), Box::new(|m| dual(&chiral::whirl(m)?))),
    ];
    for (op, fused, composed) in &pairs {
        for (name, m) in &ms {
            // untraced (ortho's one pass runs only then), then traced
            match (fused(m), composed(m)) {
                (Ok(a), Ok(b)) => assert!(a == b, "{op} on {name}: the fused build differs from the composition"),
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{op} on {name}"),
                (a, b) => panic!("{op} on {name}: fused {:?}, composition {:?}", a.err(), b.err()),
            }
            match (traced(m, || fused(m)), traced(m, || composed(m))) {
                (Ok((a, pa)), Ok((b, pb))) => {
                    assert!(a == b, "{op} on {name}: the fused build differs from the composition");
                    assert_eq!(pa, pb, "{op} on {name}: face parents");
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{op} on {name}"),
                (a, b) => panic!("{op} on {name}: fused {:?}, composition {:?}", a.err(), b.err()),
            }
        }
    }
}

//! Measurements behind the figures of `docs/schemes/menger.md` (issue 17),
//! as ignored tests: `cargo test --release --lib menger::diagnose --
//! --ignored --nocapture`, cases from `CASES` (`octahedron:3,cube:2`).
//!
//! * [`compare_offsets`]: crossing pairs (with contacts; proper crossings in
//!   brackets), faces, genus, sign of the volume, faces whose depth was
//!   reduced and the time, per iteration, for both [`Offset`] constructions
//!   (each iterating on its own outputs; `LAST=1`: only the last iteration,
//!   on the default construction's previous output; `ONLY=merged|per_face`;
//!   the peak is the process's so far, so run one case and one construction
//!   per process to compare memory).
//! * [`classify_crossings`]: the last iteration's crossing pairs by the roles
//!   of their two faces (outer remeshing, pipe wall, strip, miter quad,
//!   vertex face) and by how their input faces meet (the same face, across
//!   an edge of a given kind and interior angle, at a vertex, apart).
//! * [`rejection_exact`]: the side-plane rejection of
//!   `geometry::crossing::triangles_meet` changes no answer
//!   ([`rejection_check`] on every iteration), and the scan's time.

use super::check::build_valid;
use super::offset::plan;
use super::*;
use crate::geometry::crossing::crossing_pairs;
use crate::geometry::triangles_with_points;
use crate::mesh::{FaceId, HalfedgeId, VertexId};
use crate::primitives;
use std::collections::BTreeMap;

fn input(name: &str) -> Mesh {
    match name {
        "cube" => primitives::cube(),
        "tetrahedron" => primitives::tetrahedron(),
        "octahedron" => primitives::octahedron(),
        "icosahedron" => primitives::icosahedron(),
        "dodecahedron" => primitives::dodecahedron(),
        "torus" => primitives::torus(24, 12, 1.0, 0.4).unwrap(),
        "genus2" => primitives::genus_surface(2).unwrap(),
        _ => panic!("unknown input {name}"),
    }
}

/// Peak resident set size of this process so far (kB), from /proc.
fn peak_kb() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| l.split_whitespace().nth(1)?.parse().ok()))
        .unwrap_or(0)
}

fn cases(default: &str) -> Vec<(String, usize)> {
    let s = std::env::var("CASES").unwrap_or_else(|_| default.into());
    s.split(',').map(|c| {
        let (n, k) = c.split_once(':').expect("CASE is name:iterations");
        (n.to_string(), k.parse().expect("iterations"))
    }).collect()
}

#[test]
#[ignore]
fn compare_offsets() {
    let last = std::env::var("LAST").is_ok();
    let only = std::env::var("ONLY").ok();
    for (name, n) in cases("cube:3,tetrahedron:3,octahedron:3,icosahedron:2,dodecahedron:2,torus:1,genus2:2") {
        let m0 = input(&name);
        let base = if last { menger_iterated(&m0, n - 1, &MengerOptions::default()).unwrap() } else { m0 };
        for (label, offset) in [("merged", Offset::Merged), ("per_face", Offset::PerFace)] {
            if only.as_deref().is_some_and(|x| x != label) {
                continue;
            }
            let o = MengerOptions { offset, ..Default::default() };
            let mut m = base.clone();
            let mut line = format!("{name:12} {label:8}");
            for k in (if last { n } else { 1 })..=n {
                let t = std::time::Instant::now();
                let (x, r) = match menger_reported(&m, &o) {
                    Ok(x) => x,
                    Err(e) => {
                        line += &format!(" | {k}: error {e}");
                        break;
                    }
                };
                let secs = t.elapsed().as_secs_f64();
                x.validate().unwrap();
                let (tris, p) = triangles_with_points(&x);
                let meet = crossing_pairs(&p, &tris, None, true).len();
                let proper = crossing_pairs(&p, &tris, None, false).len();
                let (nred, fmin) = r.reduced();
                let vol = if x.signed_volume() > 0.0 { "+" } else { "NOT POSITIVE" };
                line += &format!(" | {k}: F {} g {} vol {vol} {meet} ({proper}) reduced {nred} min {fmin:.3} {secs:.2} s peak {} kB", x.n_faces(), x.genus(), peak_kb());
                m = x;
            }
            eprintln!("{line}");
        }
    }
}

#[test]
#[ignore]
fn classify_crossings() {
    use crate::schemes::level::{EDGE, FACE};
    let o = MengerOptions { offset: if std::env::var("PER_FACE").is_ok() { Offset::PerFace } else { Offset::Merged }, ..Default::default() };
    for (name, n) in cases("octahedron:3,dodecahedron:3") {
        let pre = if std::env::var("PRE_PF").is_ok() { o } else { MengerOptions::default() };
        let m = menger_iterated(&input(&name), n - 1, &pre).unwrap();
        // the per-face depth as a factor of the requested one (module docs,
        // "Per-face corners", invariant 6)
        let scale: f64 = std::env::var("SCALE").ok().and_then(|x| x.parse().ok()).unwrap_or(1.0);
        let red = (o.offset == Offset::PerFace).then(|| Reduction { depth: vec![scale; m.n_faces()] });
        let ((b, mesh), left, _) = build_valid(&m, &o, red.as_ref()).unwrap();
        let pl = plan(&m, &o, &vec![false; m.n_vertices()], None).unwrap();
        let pos = m.positions();
        let t = mesh.triangulate();
        let (tris, p) = triangles_with_points(&mesh);
        let pairs = crossing_pairs(&p, &tris, None, true);
        eprintln!("{name} {n} ({:?}): {} faces, {} crossing pairs, {left} input vertices still crossing", o.offset, mesh.n_faces(), pairs.len());
        let class = |v: u32| -> String {
            m.vertex_halfedges(VertexId(v)).map(|h| match pl.kind[h.edge().idx()] {
                EdgeKind::Collapse => 'C',
                EdgeKind::Strip => 'S',
                EdgeKind::Miter => 'M',
            }).collect()
        };
        let role = |f: u32| -> String {
            let (k, id) = b.face_origin[f as usize];
            match k {
                FACE if mesh.face_vertices(FaceId(f)).any(|v| v.0 >= b.first_inner) => "pipe".into(),
                FACE => "outer".into(),
                EDGE => format!("{:?}", pl.kind[id as usize]).to_lowercase(),
                _ => "vertex face".into(),
            }
        };
        let angle = |h: HalfedgeId| super::offset::interior_angle(&m, &pl.face_n, h).to_degrees();
        let relation = |a: u32, c: u32| -> String {
            if a == c {
                return "same face".into();
            }
            if let Some(h) = m.face_halfedges(FaceId(a)).find(|h| m.face(h.twin()) == FaceId(c)) {
                return format!("across a {:?} edge of {:.0}°", pl.kind[h.edge().idx()], angle(h)).to_lowercase();
            }
            let va: Vec<VertexId> = m.face_vertices(FaceId(a)).collect();
            match m.face_vertices(FaceId(c)).find(|v| va.contains(v)) {
                Some(v) => format!("at a vertex {}", class(v.0)),
                None => "apart".into(),
            }
        };
        let input_face = |f: u32| (b.face_origin[f as usize].0 == FACE).then_some(b.face_origin[f as usize].1);
        let (mut roles, mut rel): (BTreeMap<String, usize>, BTreeMap<String, usize>) = Default::default();
        for &(i, j) in &pairs {
            let (fa, fb) = (t.tri_face[i as usize], t.tri_face[j as usize]);
            let (mut ra, mut rb) = (role(fa), role(fb));
            if ra > rb {
                std::mem::swap(&mut ra, &mut rb);
            }
            *roles.entry(format!("{ra} × {rb}")).or_default() += 1;
            if let (Some(a), Some(c)) = (input_face(fa), input_face(fb)) {
                *rel.entry(format!("{ra} × {rb}, {}", relation(a, c))).or_default() += 1;
                if a == c && std::env::var("HEIGHTS").is_ok() {
                    let (n, p0) = (pl.face_n[a as usize], pos[m.face_vertices(FaceId(a)).next().unwrap().idx()]);
                    let hgt = |k: u32| tris[k as usize].map(|v| (n.dot(p[v as usize] - p0) / pl.face_d[a as usize] * 1000.0).round() / 1000.0);
                    eprintln!("    same face {a}: heights/D {:?} (face {ra}) {:?} (face {rb}) pairs {i} {j}", hgt(i), hgt(j));
                }
            }
        }
        if std::env::var("VERTS").is_ok() {
            let mut vs: BTreeMap<u32, usize> = BTreeMap::new();
            for &(i, j) in &pairs {
                for f in [t.tri_face[i as usize], t.tri_face[j as usize]] {
                    let (k, id) = b.face_origin[f as usize];
                    if k != FACE && k != EDGE {
                        *vs.entry(id).or_default() += 1;
                    }
                }
            }
            let mut kinds: BTreeMap<String, (usize, usize)> = BTreeMap::new();
            for (&v, &c) in &vs {
                let normals: Vec<glam::DVec3> = m.vertex_halfedges(VertexId(v)).map(|h| pl.face_n[m.face(h).idx()]).collect();
                let kern = super::offset::below_every_face(pos[v as usize], &normals, 1.0).is_some();
                let angles: Vec<String> = m.vertex_halfedges(VertexId(v)).map(|h| format!("{:.0}", angle(h))).collect();
                let e = kinds.entry(format!("{} kernel {kern} angles {}", class(v), angles.join(","))).or_default();
                e.0 += 1;
                e.1 += c;
            }
            kinds.iter().for_each(|(k, (n, c))| eprintln!("  vertices {n:5} pairs {c:6}: {k}"));
            if let (Ok(_), Some((&v, _))) = (std::env::var("DETAIL"), vs.iter().next()) {
                let pv = pos[v as usize];
                let dmin = m.vertex_halfedges(VertexId(v)).map(|h| pl.face_d[m.face(h).idx()]).fold(f64::INFINITY, f64::min);
                let loc = |x: glam::DVec3| ((x - pv) / dmin * 1000.0).round() / 1000.0;
                eprintln!("  vertex {v}, D min {dmin:.4e} (coordinates below: relative to it, in D)");
                for h in m.vertex_halfedges(VertexId(v)) {
                    let f = m.face(h).idx();
                    eprintln!("    face {f}: n {:?} D {:.3} depth {:.3} | edge to {} angle {:.1} {:?} dir {:?}", (pl.face_n[f] * 1000.0).round() / 1000.0,
                        pl.face_d[f] / dmin, pl.face_depth[f] / dmin, m.head(h).0, angle(h), pl.kind[h.edge().idx()], loc(pos[m.head(h).idx()]).normalize_or_zero());
                }
                for (i, &o) in b.owner.iter().enumerate() {
                    if o == v && i as u32 >= b.first_inner {
                        eprintln!("    inner point {i}: {:?}", loc(b.pos[i]));
                    }
                }
                for &(i, j) in &pairs {
                    let (fa, fb) = (t.tri_face[i as usize], t.tri_face[j as usize]);
                    let own = |f: u32| { let (k, id) = b.face_origin[f as usize]; k != FACE && k != EDGE && id == v };
                    if own(fa) || own(fb) {
                        eprintln!("    pair {} {:?} × {} {:?}", role(fa), tris[i as usize].map(|x| loc(p[x as usize])), role(fb), tris[j as usize].map(|x| loc(p[x as usize])));
                    }
                }
            }
        }
        roles.iter().for_each(|(k, v)| eprintln!("  {v:6} {k}"));
        rel.iter().for_each(|(k, v)| eprintln!("  {v:6} {k}"));
        let mut sizes: BTreeMap<String, usize> = BTreeMap::new();
        for f in mesh.faces() {
            *sizes.entry(format!("{} {}-gon", role(f.0), mesh.face_degree(f))).or_default() += 1;
        }
        eprintln!("  output faces: {sizes:?}");
    }
}

/// Every pair of triangles of `m` with overlapping boxes, tested with and
/// without the side-plane rejection of `triangles_meet` in both modes;
/// panics on the first different answer. Returns the pairs, those the
/// rejection settles, and the answers that were a crossing or contact.
pub(super) fn rejection_check(m: &Mesh) -> (usize, usize, usize) {
    use crate::geometry::crossing::{meet_without_rejection, separated_for_test, triangles_meet};
    let (tris, p) = triangles_with_points(m);
    let mut boxes: Vec<(glam::DVec3, glam::DVec3, usize)> = tris
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let q = t.map(|v| p[v as usize]);
            (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]), i)
        })
        .collect();
    boxes.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
    let (mut pairs, mut rejected, mut met) = (0usize, 0usize, 0usize);
    for a in 0..boxes.len() {
        let (la, ha, i) = boxes[a];
        for &(lb, hb, j) in &boxes[a + 1..] {
            if lb.x > ha.x {
                break;
            }
            if la.cmpgt(hb).any() || lb.cmpgt(ha).any() {
                continue;
            }
            let (ti, tj) = (tris[i], tris[j]);
            let (pi, pj) = (ti.map(|v| p[v as usize]), tj.map(|v| p[v as usize]));
            pairs += 1;
            rejected += separated_for_test(ti, pi, tj, pj) as usize;
            for cop in [false, true] {
                let full = meet_without_rejection(ti, pi, tj, pj, cop);
                met += full as usize;
                assert_eq!(triangles_meet(ti, pi, tj, pj, cop), full, "triangles {i} {ti:?} {pi:?} and {j} {tj:?} {pj:?}, coplanar {cop}");
            }
        }
    }
    (pairs, rejected, met)
}

#[test]
#[ignore]
fn rejection_exact() {
    for (name, n) in cases("octahedron:3,tetrahedron:3,torus:2,dodecahedron:3,icosahedron:3,cube:4") {
        for (label, offset) in [("merged", Offset::Merged), ("per_face", Offset::PerFace)] {
            let o = MengerOptions { offset, reduce_thickness: false, ..Default::default() };
            let mut m = input(&name);
            for k in 1..=n {
                m = match menger(&m, &o) {
                    Ok(x) => x,
                    Err(e) => {
                        eprintln!("{name} {k} {label}: {e}");
                        break;
                    }
                };
                let t = std::time::Instant::now();
                let (tris, p) = triangles_with_points(&m);
                let found = crossing_pairs(&p, &tris, None, true).len();
                let secs = t.elapsed().as_secs_f64();
                let (pairs, rejected, met) = rejection_check(&m);
                eprintln!("{name} {k} {label}: {pairs} box pairs, {rejected} rejected, {met} answers true; scan {found} pairs in {secs:.3} s");
            }
        }
    }
}

/// The contacts the exact tests report on a case's last iteration, each
/// with which test finds it and its shape (issue 17: contacts CGAL does not
/// find).
#[test]
#[ignore]
fn contact_details() {
    use crate::geometry::crossing::contact_parts;
    for (name, n) in cases("torus:2") {
        let m = menger_iterated(&input(&name), n, &MengerOptions::default()).unwrap();
        let (tris, p) = triangles_with_points(&m);
        let pairs = crossing_pairs(&p, &tris, None, true);
        let proper = crossing_pairs(&p, &tris, None, false);
        eprintln!("{name} {n}: {} pairs, {} proper", pairs.len(), proper.len());
        for &(i, j) in pairs.iter().filter(|x| proper.binary_search(x).is_err()).take(6) {
            let (ti, tj) = (tris[i as usize], tris[j as usize]);
            let (pi, pj) = (ti.map(|v| p[v as usize]), tj.map(|v| p[v as usize]));
            eprintln!("  {ti:?} {tj:?}: {}", contact_parts(ti, pi, tj, pj));
            eprintln!("    {pi:?}\n    {pj:?}");
        }
    }
}

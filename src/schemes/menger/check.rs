//! The crossing check of step 3 (module docs of [`super`], "Crossing
//! check"): build, test each input vertex's triangles with the exact
//! predicate of [`crate::geometry::crossing`], rebuild crossing vertices
//! fully collapsed, for a few rounds.

use super::remesh::{build_polygons, Built};
use super::{MengerOptions, MengerReport, Reduction};
use crate::error::Result;
use crate::geometry::crossing::local_crossings;
use crate::geometry::triangulate::Triangulation;
use crate::mesh::{BuildOptions, Mesh};
use glam::DVec3;

/// Rounds of the crossing check (module docs): a vertex found crossing is
/// rebuilt fully collapsed; a second round catches vertices whose
/// neighbourhood changed.
const CROSSING_ROUNDS: usize = 3;

/// The polygons and the mesh of one iteration (module docs): built with the
/// rules of VII.3–VII.5, then every input vertex whose local result crosses
/// itself is rebuilt fully collapsed, for up to [`CROSSING_ROUNDS`] rounds.
/// Also returns how many input vertices still cross at the end, and the
/// output's crossing pairs when [`release_full`] scanned it.
pub(super) fn build_valid(m: &Mesh, o: &MengerOptions, red: Option<&Reduction>) -> Result<Checked> {
    let mut full = vec![false; m.n_vertices()];
    // after the first round only vertices next to a change are checked again
    let mut recheck = vec![false; m.n_vertices()];
    // whether each vertex crossed when it was last checked
    let mut crossing = vec![false; m.n_vertices()];
    // vertices whose vertex face was coned in some round
    let mut coned = vec![false; m.n_vertices()];
    let mut round = 0;
    loop {
        // (the previous round's build and triangulation are dropped before
        // this one is made)
        let cur = build_once(m, o, &full, red)?;
        // kept for the whole-output scan should this build be the last
        let tri = Tris::of(&cur.1);
        let only = (round > 0).then_some(&recheck[..]);
        let mut lc = local_crossings(&tri.p, &tri.t.tris, &cur.0.owner, cur.0.first_inner, only);
        crate::cancel::check()?;
        for (v, c) in crossing.iter_mut().enumerate() {
            if only.map_or(true, |r| r[v]) {
                *c = false;
            }
        }
        for &v in &lc {
            crossing[v as usize] = true;
        }
        // per-face corners (module docs) have no full collapse to fall back on
        if round == CROSSING_ROUNDS || o.offset == super::Offset::PerFace {
            return release_full(m, o, red, (cur, tri), &full, &crossing, &coned);
        }
        // a vertex face with no planar split would be coned from a new
        // vertex, a saddle-like point the next iteration cannot offset:
        // such vertices are fully collapsed too (no vertex face)
        lc.extend(cur.0.coned.iter().copied());
        for &v in &cur.0.coned {
            coned[v as usize] = true;
        }
        let mut changed = false;
        recheck.iter_mut().for_each(|x| *x = false);
        for v in lc {
            if !full[v as usize] {
                full[v as usize] = true;
                changed = true;
                // its neighbours' structures share its pipes and strips
                recheck[v as usize] = true;
                for h in m.vertex_halfedges(crate::mesh::VertexId(v)) {
                    recheck[m.head(h).idx()] = true;
                }
            }
        }
        if !changed {
            return release_full(m, o, red, (cur, tri), &full, &crossing, &coned);
        }
        round += 1;
    }
}

/// A build of [`build_valid`]: the polygons and mesh, the input vertices
/// still crossing, and the crossing pairs if they were scanned, else the
/// triangulation the per-vertex check made of this mesh (for the scan).
pub(super) type Checked = ((Built, Mesh), usize, Scan);

/// The whole-output scan's pairs ([`output_crossings`]), or what it starts
/// from.
pub(super) enum Scan {
    Pairs(Vec<(u32, u32)>),
    Tris(Tris),
}

/// An output's triangulation and its points (the mesh's, then those the
/// triangulation added), made once per build: the per-vertex check and
/// the whole-output scan read the same triangles (a triangulation of the
/// torus row's 1.6 M faces takes about as long as a tenth of the scan).
pub(super) struct Tris {
    t: Triangulation,
    p: Vec<DVec3>,
}

impl Tris {
    fn of(mesh: &Mesh) -> Tris {
        let t = mesh.triangulate();
        let mut p = mesh.positions().to_vec();
        p.extend_from_slice(&t.points);
        Tris { t, p }
    }
}

/// The end of the crossing check (module docs, "Crossing check"): a vertex
/// that still crosses once fully collapsed may cross less as first built.
/// With the thickness reduction on (it scans the whole output anyway), such
/// vertices (not coned, which must stay collapsed) are released together
/// in the first build (not in the reduction's rebuilds),
/// then each keeps the state whose build has fewer crossing pairs with a
/// corner it placed, and the build with the fewest pairs of the three is
/// returned. A crossing-free output has no such vertex and is unchanged.
fn release_full(m: &Mesh, o: &MengerOptions, red: Option<&Reduction>, (cur, tri): ((Built, Mesh), Tris), full: &[bool], crossing: &[bool], coned: &[bool]) -> Result<Checked> {
    let n = crossing.iter().filter(|&&c| c).count();
    let cand: Vec<usize> = (0..full.len()).filter(|&v| full[v] && crossing[v] && !coned[v]).collect();
    // (only before the reduction's rebuilds: each costs two builds and three scans)
    if !o.reduce_thickness || red.is_some() || cand.is_empty() {
        return Ok((cur, n, Scan::Tris(tri)));
    }
    let mut released = full.to_vec();
    cand.iter().for_each(|&v| released[v] = false);
    let pc = output_crossings(&tri, cur.0.first_inner);
    drop(tri);
    let alt = build_once(m, o, &released, red)?;
    let pa = output_crossings(&Tris::of(&alt.1), alt.0.first_inner);
    let (cc, ca) = (pairs_per_owner(&cur, &pc, full.len()), pairs_per_owner(&alt, &pa, full.len()));
    let mut mixed = full.to_vec();
    cand.iter().filter(|&&v| ca[v] < cc[v]).for_each(|&v| mixed[v] = false);
    let mut best = if pa.len() < pc.len() { (alt, pa) } else { (cur, pc) };
    if mixed != full && mixed != released {
        let mix = build_once(m, o, &mixed, red)?;
        let pm = output_crossings(&Tris::of(&mix.1), mix.0.first_inner);
        if pm.len() < best.1.len() {
            best = (mix, pm);
        }
    }
    crate::cancel::check()?;
    Ok((best.0, n, Scan::Pairs(best.1)))
}

/// Crossing pairs per input vertex: those with a corner its rules placed.
fn pairs_per_owner(b: &(Built, Mesh), pairs: &[(u32, u32)], nv: usize) -> Vec<usize> {
    let mut count = vec![0usize; nv];
    let mut vs: Vec<u32> = Vec::new();
    for &(x, y) in pairs {
        vs.clear();
        for f in [x, y] {
            vs.extend(b.1.face_vertices(crate::mesh::FaceId(f)).filter_map(|w| b.0.owner.get(w.idx()).copied()).filter(|&o| o != u32::MAX));
        }
        vs.sort_unstable();
        vs.dedup();
        vs.iter().for_each(|&v| count[v as usize] += 1);
    }
    count
}

/// One build with the given fully collapsed vertices: with the `4D` miter
/// bound and the near weld, or, when that does not give a manifold, with a
/// `2D` miter bound and coincident points welded only.
pub(super) fn build_once(m: &Mesh, o: &MengerOptions, full: &[bool], red: Option<&Reduction>) -> Result<(Built, Mesh)> {
    let b = build_polygons(m, o, true, full, red)?;
    match Mesh::from_polygons(b.pos.clone(), &b.sizes, &b.idx, BuildOptions::default()) {
        Ok(mesh) => Ok((b, mesh)),
        Err(_) => {
            let b = build_polygons(m, o, false, full, red)?;
            let mesh = Mesh::from_polygons(b.pos.clone(), &b.sizes, &b.idx, BuildOptions::default())?;
            Ok((b, mesh))
        }
    }
}

/// Rebuilds of the thickness reduction (module docs, "Thickness
/// reduction"): each halves the offset depth of the faces involved in a
/// crossing.
pub const REDUCTION_ROUNDS: usize = 6;
/// The smallest thickness factor a face is reduced to.
pub const REDUCTION_FLOOR: f64 = 1.0 / 32.0;

/// Crossing triangle pairs of the output, with coplanar contacts
/// ([`crate::geometry::crossing::triangles_meet`], what
/// `Mesh.self_intersections` counts), each given by the two output faces
/// it came from.
///
/// Two triangles of the outer remeshing (every corner below `first_inner`)
/// lie in the input's faces and cannot cross (as in the per-vertex check),
/// so only pairs with another triangle are tested.
pub(super) fn output_crossings(tri: &Tris, first_inner: u32) -> Vec<(u32, u32)> {
    let (t, p) = (&tri.t, &tri.p);
    let focus: Vec<bool> = t.tris.iter().map(|tv| tv.iter().any(|&v| v >= first_inner)).collect();
    let pairs = crate::geometry::crossing::crossing_pairs(p, &t.tris, Some(&focus), true);
    pairs.iter().map(|&(i, j)| (t.tri_face[i as usize], t.tri_face[j as usize])).collect()
}

/// The input faces whose thickness placed an output face: its origin face,
/// the two faces of its origin edge or the faces around its origin vertex
/// (`Origins` kinds), and the faces around every input vertex whose rule
/// placed one of its corners (merged corners and meeting points follow the
/// depths of all the faces around their vertex).
fn implicated(m: &Mesh, b: &Built, mesh: &Mesh, face: u32, out: &mut Vec<u32>) {
    use crate::schemes::level::{EDGE, FACE};
    let around = |v: u32, out: &mut Vec<u32>| {
        for h in m.vertex_halfedges(crate::mesh::VertexId(v)) {
            out.push(m.face(h).0);
        }
    };
    match b.face_origin[face as usize] {
        (FACE, f) => out.push(f),
        (EDGE, e) => {
            let h = crate::mesh::EdgeId(e).halfedge();
            out.push(m.face(h).0);
            out.push(m.face(h.twin()).0);
        }
        (_, v) => around(v, out),
    }
    for v in mesh.face_vertices(crate::mesh::FaceId(face)) {
        if let Some(&o) = b.owner.get(v.idx()) {
            if o != u32::MAX {
                around(o, out);
            }
        }
    }
}

/// The input faces behind crossing `pairs` of a build ([`implicated`] for
/// both faces of each pair), sorted and without repeats, into `hit`.
fn behind(m: &Mesh, b: &Built, mesh: &Mesh, pairs: &[(u32, u32)], hit: &mut Vec<u32>) {
    hit.clear();
    for &(x, y) in pairs {
        implicated(m, b, mesh, x, hit);
        implicated(m, b, mesh, y, hit);
    }
    hit.sort_unstable();
    hit.dedup();
}

/// One per-face build (module docs, "Per-face corners") at the depths of
/// `red`. Per-face corners have no full collapse to fall back on, so the
/// per-vertex check only reports (`crossing_vertices`): it runs here when
/// no whole-output scan follows (`!reduce`), else [`build_reduced`] runs it
/// where the scan found pairs (a crossing-free output has no crossing
/// vertex either: the check tests a subset of the scan's pairs with the
/// same predicate).
fn build_apart(m: &Mesh, o: &MengerOptions, red: &Reduction, reduce: bool) -> Result<((Built, Mesh), usize, Tris)> {
    let cur = build_once(m, o, &vec![false; m.n_vertices()], Some(red))?;
    let tri = Tris::of(&cur.1);
    let vertices = if reduce { 0 } else { crossing_vertex_count(&cur.0, &tri) };
    crate::cancel::check()?;
    Ok((cur, vertices, tri))
}

/// Input vertices whose own triangles cross (the per-vertex check).
fn crossing_vertex_count(b: &Built, tri: &Tris) -> usize {
    local_crossings(&tri.p, &tri.t.tris, &b.owner, b.first_inner, None).len()
}

/// One iteration with the thickness reduction (module docs, "Thickness
/// reduction"), for both constructions: a build ([`build_valid`], or
/// [`build_apart`] at the per-face depth), then, while the output has
/// crossing triangle pairs (exact predicate, the whole output), the input
/// faces involved ([`implicated`]) get half their depth and the level is
/// rebuilt; faces already at [`REDUCTION_FLOOR`] stay there. The build with
/// the fewest pairs is kept; a per-face one that is crossing-free then
/// gives depth back ([`raise_back`]). Without `reduce`, one build and no
/// whole-output scan.
pub(super) fn build_reduced(m: &Mesh, o: &MengerOptions, reduce: bool) -> Result<((Built, Mesh), MengerReport)> {
    let per_face = o.offset == super::Offset::PerFace;
    let nf = m.n_faces();
    // both constructions start at the requested depth (module docs,
    // "Per-face corners", invariant 6): the factor faces are reduced from
    let nominal = 1.0;
    let mut red = Reduction { depth: vec![nominal; nf] };
    let mut rounds = 0;
    let mut hit: Vec<u32> = Vec::new();
    // the build with the fewest crossing pairs so far
    let mut best: Option<((Built, Mesh), MengerReport)> = None;
    loop {
        let ((b, mesh), mut vertices, scanned) = if per_face {
            let (built, vertices, tri) = build_apart(m, o, &red, reduce)?;
            (built, vertices, Scan::Tris(tri))
        } else {
            build_valid(m, o, (rounds > 0).then_some(&red))?
        };
        // per face: the factor of the face's depth, with the sharp-edge
        // bound of the per-face construction (invariant 3)
        let face_factor = if per_face { b.depth_factor.clone() } else { red.depth.clone() };
        let report = |crossing_pairs, crossing_vertices| MengerReport { face_factor, rounds, crossing_pairs, crossing_vertices, nominal };
        if !reduce {
            return Ok(((b, mesh), report(None, vertices)));
        }
        let pairs = match scanned {
            Scan::Pairs(p) => p,
            Scan::Tris(t) => {
                let p = output_crossings(&t, b.first_inner);
                if per_face && !p.is_empty() {
                    vertices = crossing_vertex_count(&b, &t);
                }
                p
            }
        };
        crate::cancel::check()?;
        if best.as_ref().is_some_and(|(_, r)| r.crossing_pairs.is_some_and(|n| n <= pairs.len())) {
            // this round did not lower the count: the best so far stands
            return Ok(best.expect("set"));
        }
        behind(m, &b, &mesh, &pairs, &mut hit);
        let report = report(Some(pairs.len()), vertices);
        let clean = pairs.is_empty();
        drop(pairs);
        if clean && per_face && rounds > 0 {
            return raise_back(m, o, &mut red, ((b, mesh), report));
        }
        best = Some(((b, mesh), report));
        if clean || rounds == REDUCTION_ROUNDS {
            return Ok(best.expect("set"));
        }
        let mut changed = false;
        for &f in &hit {
            let f = f as usize;
            if red.depth[f] > nominal * REDUCTION_FLOOR * (1.0 + 1e-9) {
                red.depth[f] *= 0.5;
                changed = true;
            }
        }
        if !changed {
            return Ok(best.expect("set"));
        }
        rounds += 1;
    }
}

/// Steps of [`raise_back`]: each multiplies the reduced depths by the
/// square root of the previous factor (√2, then 2^¼).
const RAISE_STEPS: usize = 2;

/// After the reduction has left a crossing-free build (per-face
/// construction, module docs "Per-face corners", invariant 6): halving
/// overshoots by up to 2×, so the reduced faces get part of their depth
/// back, ×√2 then ×2^¼ (never above the requested one), each step kept if
/// the output stays crossing-free; where it does not, the faces behind the
/// new crossing pairs keep their depth and the others are raised, if that
/// build is crossing-free. Measured: the mean depth factor of the
/// torus's second iteration 0.50 → 0.84 (two more builds), the
/// tetrahedron's third 0.46 → 0.70 (three).
fn raise_back(m: &Mesh, o: &MengerOptions, red: &mut Reduction, mut best: ((Built, Mesh), MengerReport)) -> Result<((Built, Mesh), MengerReport)> {
    let rounds = best.1.rounds;
    let mut step = std::f64::consts::SQRT_2;
    let mut hit: Vec<u32> = Vec::new();
    // a crossing-free build at the given depths, as the best so far
    let try_build = |depth: &Reduction| -> Result<Attempt> {
        let (built, _, t) = build_apart(m, o, depth, true)?;
        let pairs = output_crossings(&t, built.0.first_inner);
        crate::cancel::check()?;
        if !pairs.is_empty() {
            return Ok(Attempt::Crossing(built, pairs));
        }
        let report = MengerReport { face_factor: built.0.depth_factor.clone(), rounds, crossing_pairs: Some(0), crossing_vertices: 0, nominal: 1.0 };
        Ok(Attempt::Clean((built, report)))
    };
    for _ in 0..RAISE_STEPS {
        let mut up = red.clone();
        let mut any = false;
        for d in up.depth.iter_mut().filter(|d| **d < 1.0) {
            *d = (*d * step).min(1.0);
            any = true;
        }
        if !any {
            break;
        }
        match try_build(&up)? {
            Attempt::Clean(b) => {
                best = b;
                *red = up;
            }
            Attempt::Crossing(b, pairs) => {
                // the faces behind the new crossings keep their depth
                behind(m, &b.0, &b.1, &pairs, &mut hit);
                drop(b);
                for &f in &hit {
                    up.depth[f as usize] = red.depth[f as usize];
                }
                if up != *red {
                    if let Attempt::Clean(b) = try_build(&up)? {
                        best = b;
                        *red = up;
                    }
                }
            }
        }
        step = step.sqrt();
    }
    Ok(best)
}

/// A build of [`raise_back`]: crossing-free (with its report), or with the
/// crossing pairs it has.
enum Attempt {
    Clean(((Built, Mesh), MengerReport)),
    Crossing((Built, Mesh), Vec<(u32, u32)>),
}

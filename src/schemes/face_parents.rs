//! Face parents of the keyed remeshing catalog (issue 15): which input face
//! every output face of a Conway operator or TopMod scheme descends from, so
//! per-face data (material ids, groups) is inherited instead of dropped.
//!
//! The builders record it as they go: [`crate::schemes::keyed::Out`] keeps
//! per output face the input element it was built from (set by the scheme
//! before each face), and [`crate::schemes::dual::dual`] knows its own (face
//! v from vertex v, vertex f from face f). Each finished build appends a
//! [`Step`] to a per-thread trace while [`traced`] runs; the steps of a chain
//! (compositions such as `t = dkd`, TopMod's "dual + X + dual", repeated
//! iterations) compose by lookup.
//!
//! The rule, the smoothing schemes' (`python/levels.rs`,
//! `exported_face_origins`) applied to these operators:
//!
//! * a face built inside input face f (a kis triangle, a shrunk copy, a
//!   corner pentagon, a half-edge's hexagon) has parent f;
//! * a face born around an input edge e (chamfer's hexagons) has the face of
//!   e's first side, `face(2e)`;
//! * a face born around an input vertex v (dual, ambo) has the parent of v:
//!   the lowest-index face around it for a vertex of the input (the
//!   smoothing schemes take the first face of its ring from `v_out`; the
//!   lowest one does not depend on half-edge numbering, so a chain gives
//!   the same parents in one call as in several), and along a chain the
//!   parent of the element v was born from (a dual's vertex f is face f, an
//!   ambo vertex is its edge), so truncate's `F` faces (`dkd`: born around
//!   the kis mesh's vertices, which are the dual's vertices, which are the
//!   input's faces) keep their own face.
//!
//! A vertex's origin is explicit where the scheme states it (kept input
//! vertices, a dual's face points, ambo's edge points) and otherwise that of
//! the output face of its first corner (a new point lies inside, or on the
//! border of, the faces built from one input element).
//!
//! The schemes not built through `Out` (honeycomb, Loop, Doo-Sabin inside
//! TopMod's root-3, dual Loop and Doo-Sabin BC) record through
//! [`via_origins`]: their level's correspondence read under the same rule.
//! Any other build in the chain that records nothing breaks the chain:
//! [`traced`] then returns no parents and the bindings drop face data with
//! the usual warning, never guess.

use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use std::cell::RefCell;

/// Marks a source naming an input vertex (indices are below 2^31).
pub(crate) const VERT: u32 = 1 << 31;

/// One build: its input's counts and, per output face and vertex, the
/// input element it descends from (a face id, or `VERT | v`).
#[derive(Clone, Debug)]
pub(crate) struct Step {
    pub in_v: usize,
    pub in_f: usize,
    pub face: Vec<u32>,
    pub vertex: Vec<u32>,
}

thread_local! {
    /// The steps recorded on this thread, `None` for a build that recorded
    /// nothing usable; the whole `Option` is `None` when no trace runs.
    static TRACE: RefCell<Option<Vec<Option<Step>>>> = const { RefCell::new(None) };
}

/// Whether a trace is recording on this thread (builders skip the work
/// otherwise).
pub(crate) fn recording() -> bool {
    TRACE.with(|t| t.borrow().is_some())
}

/// Appends a build's step (`None`: it could not say).
pub(crate) fn record(s: Option<Step>) {
    TRACE.with(|t| {
        if let Some(v) = t.borrow_mut().as_mut() {
            v.push(s);
        }
    });
}

/// The number of steps recorded so far (for [`take_since`]).
pub(crate) fn mark() -> usize {
    TRACE.with(|t| t.borrow().as_ref().map_or(0, |v| v.len()))
}

/// Removes and returns the steps recorded after `mark`.
pub(crate) fn take_since(mark: usize) -> Vec<Option<Step>> {
    TRACE.with(|t| t.borrow_mut().as_mut().map_or_else(Vec::new, |v| v.split_off(mark.min(v.len()))))
}

/// `b` after `a` (`b` built from `a`'s output), as one step from `a`'s
/// input; `None` when the counts do not chain.
pub(crate) fn then(a: &Step, b: &Step) -> Option<Step> {
    if b.in_f != a.face.len() || b.in_v != a.vertex.len() {
        return None;
    }
    let look = |s: u32| if s & VERT != 0 { a.vertex[(s & !VERT) as usize] } else { a.face[s as usize] };
    Some(Step { in_v: a.in_v, in_f: a.in_f, face: b.face.iter().map(|&s| look(s)).collect(), vertex: b.vertex.iter().map(|&s| look(s)).collect() })
}

/// The steps composed into one (`None` for none, a broken one, or counts
/// that do not chain).
pub(crate) fn chain(steps: Vec<Option<Step>>) -> Option<Step> {
    let mut it = steps.into_iter();
    let mut acc = it.next()??;
    for s in it {
        acc = then(&acc, &s?)?;
    }
    Some(acc)
}

/// The identity step of `m` (every element its own origin).
pub(crate) fn identity(m: &Mesh) -> Step {
    Step { in_v: m.n_vertices(), in_f: m.n_faces(), face: (0..m.n_faces() as u32).collect(), vertex: (0..m.n_vertices() as u32).map(|v| VERT | v).collect() }
}

/// The input face of every vertex of `m` for sources naming it: the
/// lowest-index face around it (a point-sphere's own face). Lowest, not the
/// face of `v_out`, so the parents do not depend on half-edge numbering and
/// a chain gives the same parents in one call or in several: the keyed
/// builder's vertices and faces keep their input's order, so the lowest
/// output face around a kept vertex descends from the lowest input face.
fn vertex_faces(m: &Mesh) -> Vec<u32> {
    let (_, vert, face) = m.halfedge_columns();
    let mut out: Vec<u32> = m.v_out.iter().map(|&o| if o & POINT != 0 { o & !POINT } else { NONE }).collect();
    for (&v, &f) in vert.iter().zip(face) {
        let x = &mut out[v as usize];
        *x = (*x).min(f);
    }
    out
}

/// The step of a level built with origins ([`crate::schemes::level::Origins`],
/// the smoothing schemes' correspondence), under this module's rule: an
/// element born from face f has parent f, from vertex v the parent of v,
/// from edge e the face of its first side, `face(2e)`.
pub(crate) fn step_of_origins(m: &Mesh, o: &crate::schemes::level::Origins) -> Step {
    use crate::schemes::level::{EDGE, VERTEX};
    let (_, _, he_face) = m.halfedge_columns();
    let src = |(&k, &i): (&u8, &u32)| match k {
        VERTEX => VERT | i,
        EDGE => he_face[2 * i as usize],
        _ => i,
    };
    Step {
        in_v: m.n_vertices(),
        in_f: m.n_faces(),
        face: o.face_kind.iter().zip(&o.face).map(src).collect(),
        vertex: o.vertex_kind.iter().zip(&o.vertex).map(src).collect(),
    }
}

/// A scheme that does not build through the recording builders (Loop,
/// honeycomb, Doo-Sabin) inside a traced chain (TopMod's root-3, dual Loop,
/// Doo-Sabin BC): while a trace runs, the level is built with origins and
/// their step recorded (whatever the build itself recorded is replaced);
/// otherwise `plain` runs as it is.
pub(crate) fn via_origins(
    m: &Mesh,
    level: impl FnOnce(&crate::schemes::level::Request) -> Result<crate::schemes::level::Level>,
    plain: impl FnOnce() -> Result<Mesh>,
) -> Result<Mesh> {
    if !recording() {
        return plain();
    }
    let at = mark();
    let req = crate::schemes::level::Request { origins: true, ..Default::default() };
    let l = level(&req)?;
    take_since(at);
    let step = l.origins.as_ref().map(|o| step_of_origins(m, o)).filter(|s| s.face.len() == l.mesh.n_faces() && s.vertex.len() == l.mesh.n_vertices());
    record(step);
    Ok(l.mesh)
}

/// Runs `build` (which must build its output from `m` through the recording
/// builders) with a trace, and returns its output with the face parents:
/// per output face, the face of `m` it inherits from (internal ids), or
/// `None` when some step of the chain did not record (see the module docs).
/// No build at all gives the identity when the output has `m`'s counts.
pub fn traced(m: &Mesh, build: impl FnOnce() -> Result<Mesh>) -> Result<(Mesh, Option<Vec<u32>>)> {
    /// Puts the caller's trace back even if `build` unwinds: the thread may
    /// be a long-lived worker that runs later, untraced calls.
    struct Restore(Option<Option<Vec<Option<Step>>>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            if let Some(saved) = self.0.take() {
                TRACE.with(|t| t.replace(saved));
            }
        }
    }
    let mut restore = Restore(Some(TRACE.with(|t| t.replace(Some(Vec::new())))));
    let out = build();
    let steps = TRACE.with(|t| t.replace(restore.0.take().flatten())).unwrap_or_default();
    let out = out?;
    let step = if steps.is_empty() { Some(identity(m)) } else { chain(steps) };
    let parents = step.filter(|s| s.in_f == m.n_faces() && s.in_v == m.n_vertices() && s.face.len() == out.n_faces() && s.vertex.len() == out.n_vertices()).map(|s| {
        let vf = if s.face.iter().any(|&x| x & VERT != 0) { vertex_faces(m) } else { Vec::new() };
        let p: Vec<u32> = s.face.iter().map(|&x| if x & VERT != 0 { vf[(x & !VERT) as usize] } else { x }).collect();
        debug_assert!(p.iter().all(|&f| f != NONE && (f as usize) < m.n_faces()));
        p
    });
    Ok((out, parents))
}

/// Composes face parents across calls: `later[g]` is a face of the mesh
/// `earlier` maps back from.
pub fn compose_parents(earlier: &[u32], later: &[u32]) -> Vec<u32> {
    later.iter().map(|&g| earlier[g as usize]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;
    use crate::schemes::conway;

    fn parents(notation: &str, m: &Mesh) -> Vec<u32> {
        let (out, p) = traced(m, || conway::conway(notation, Some(m))).unwrap();
        let p = p.unwrap_or_else(|| panic!("{notation}: no parents"));
        assert_eq!(p.len(), out.n_faces());
        p
    }

    /// Every operator's output faces name input faces; the operators that
    /// keep a copy of every input face (the `F` term of F') or split every
    /// face (kis, gyro) keep every input face's id, and the chain's compositions agree with the
    /// composed single letters.
    #[test]
    fn every_operator_has_parents() {
        let m = primitives::dodecahedron();
        for o in conway::OPERATORS {
            let p = parents(&o.letter.to_string(), &m);
            assert!(p.iter().all(|&f| (f as usize) < m.n_faces()), "{}", o.letter);
            let all: std::collections::BTreeSet<u32> = p.iter().copied().collect();
            // a copy per input face (an `F` term in F'), or a child per half-edge
            if o.counts[2].starts_with('F') || "kg".contains(o.letter) {
                assert_eq!(all.len(), m.n_faces(), "{}: every input face has a child", o.letter);
            }
        }
        // t = dkd: the first F faces of the truncation are the input faces
        let t = parents("t", &m);
        assert_eq!(&t[..m.n_faces()], &(0..m.n_faces() as u32).collect::<Vec<_>>()[..]);
        assert_eq!(parents("t", &m), parents("dkd", &m));
    }

    /// One call or several: `dk` in one chain and kis then dual agree.
    #[test]
    fn chains_agree_across_calls() {
        let m = crate::schemes::hosts::test_meshes::handle_cube();
        let (k, pk) = traced(&m, || conway::kis(&m, None)).unwrap();
        let (_, pd) = traced(&k, || crate::schemes::dual::dual(&k)).unwrap();
        assert_eq!(compose_parents(&pk.unwrap(), &pd.unwrap()), parents("dk", &m));
    }

    /// A non-recording build inside the chain gives no parents.
    #[test]
    fn unrecorded_build_breaks_the_chain() {
        let m = primitives::cube();
        let (_, p) = traced(&m, || crate::schemes::loop_subdivision::loop_subdivision(&conway::kis(&m, None)?)).unwrap();
        assert!(p.is_none());
    }
    /// Every TopMod scheme built through `Out` gives parents on the corpus
    /// (point-spheres, self-loops, two-gons, genus included); the schemes
    /// that keep a face per input face keep every id.
    #[test]
    fn topmod_schemes_have_parents() {
        use crate::schemes::topmod::{self as tm, extrude::{Extrusion, Kind}};
        type Scheme = fn(&Mesh) -> Result<Mesh>;
        let all: [(&str, Scheme, bool); 22] = [
            ("root3", tm::compose::root3, false),
            ("dual_loop", tm::compose::dual_loop, false),
            ("doo_sabin_bc", tm::compose::doo_sabin_bc, true),
            ("stellate", |m| tm::stellate::stellate(m, 0.1), true),
            ("double_stellate", |m| tm::stellate::double_stellate(m, 0.1), true),
            ("stellate_edge_removal", |m| tm::stellate::stellate_edge_removal(m, 0.0), false),
            ("double_stellate_misc", |m| tm::stellate::double_stellate_misc(m, 0.1, 0.1), false),
            ("linear_vertex_insertion", tm::linear::linear_vertex_insertion, true),
            ("corner_cutting", |m| tm::corner_cutting::corner_cutting(m, 0.5), true),
            ("modified_corner_cutting", |m| tm::corner_cutting::modified_corner_cutting(m, 0.25), true),
            ("loop_style", |m| tm::loop_style::loop_style(m, 1.0), true),
            ("root4", |m| tm::loop_style::root4(m, 0.0, 0.0), true),
            ("fractal", |m| tm::loop_style::fractal(m, 1.0), true),
            ("pentagonalize", |m| tm::pentagonal::pentagonalize(m, 0.0), true),
            ("pentagon_preserving", |m| tm::pentagonal::pentagon_preserving(m, 0.75), true),
            ("dual_12_6_4", |m| tm::twelve_six_four::dual_12_6_4(m, 0.7), true),
            ("remesh_12_6_4", |m| tm::compose::remesh_12_6_4(m, 0.7), false),
            ("checkerboard", |m| tm::checkerboard::checkerboard(m, 0.33), true),
            ("dual_checkerboard", |m| tm::compose::dual_checkerboard(m, 0.33), true),
            ("doo_sabin_bc_new", |m| tm::doo_sabin_bc_new::doo_sabin_bc_new(m, 1.0, 1.0), true),
            ("dome", |m| tm::extrude::dome(m, 1.0, 1.0), true),
            ("extrude", |m| tm::extrude::extrude(m, &[0], &Extrusion { kind: Kind::Cubical, length: 1.0, scale: 1.0, twist: 0.0, segments: 2, angle: None, lengths: None }), true),
        ];
        for (mesh, m) in crate::schemes::topmod::tests::meshes() {
            for (name, f, every) in all {
                if name == "extrude" && m.face_halfedge(crate::FaceId(0)).is_none() {
                    continue;
                }
                let (out, p) = traced(&m, || f(&m)).unwrap();
                let p = p.unwrap_or_else(|| panic!("{name} on {mesh}: no parents"));
                assert_eq!(p.len(), out.n_faces(), "{name} on {mesh}");
                assert!(p.iter().all(|&f| (f as usize) < m.n_faces()), "{name} on {mesh}");
                if every {
                    let got: std::collections::BTreeSet<u32> = p.iter().copied().collect();
                    assert_eq!(got.len(), m.n_faces(), "{name} on {mesh}: every input face has a child");
                }
            }
        }
    }

    /// The compositions whose middle scheme records through its origins
    /// ([`via_origins`]) build the same mesh traced as untraced (the level
    /// with origins is the same construction).
    #[test]
    fn origin_parents_leave_the_mesh_alone() {
        use crate::schemes::output_hashes::mesh_hash;
        use crate::schemes::topmod::compose;
        type Scheme = fn(&Mesh) -> Result<Mesh>;
        let all: [(&str, Scheme); 3] = [("root3", compose::root3), ("dual_loop", compose::dual_loop), ("doo_sabin_bc", compose::doo_sabin_bc)];
        for (mesh, m) in crate::schemes::topmod::tests::meshes() {
            for (name, f) in all {
                let plain = f(&m);
                let (out, p) = match traced(&m, || f(&m)) {
                    Ok(x) => x,
                    Err(e) => {
                        assert_eq!(plain.unwrap_err().to_string(), e.to_string(), "{name} on {mesh}");
                        continue;
                    }
                };
                assert_eq!(mesh_hash(&out), mesh_hash(&plain.unwrap()), "{name} on {mesh}");
                assert!(p.is_some(), "{name} on {mesh}: no parents");
            }
        }
    }

    /// The corpus through every Conway operator: point-spheres map to
    /// themselves and chains compose.
    #[test]
    fn conway_on_the_corpus() {
        for (mesh, m) in crate::schemes::topmod::tests::meshes() {
            for o in conway::OPERATORS {
                let (out, p) = traced(&m, || conway::Op::apply(conway::parse(&o.letter.to_string()).unwrap().ops[0], &m)).unwrap();
                let p = p.unwrap_or_else(|| panic!("{} on {mesh}: no parents", o.letter));
                assert_eq!(p.len(), out.n_faces());
                for f in 0..out.n_faces() {
                    // a point-sphere's face inherits from a point-sphere
                    let pt = out.face_halfedge(crate::FaceId(f as u32)).is_none();
                    assert_eq!(pt, m.face_halfedge(crate::FaceId(p[f])).is_none(), "{} on {mesh}: face {f}", o.letter);
                }
            }
        }
    }
}

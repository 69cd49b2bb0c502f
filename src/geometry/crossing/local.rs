//! The crossing check after a local change (handles, pipes, the wireframe
//! tools): only the faces the operator made are tested, against the faces
//! near them, in time proportional to those faces and a pass over the
//! output (issue 16: a two-face handle on a 100k-face torus spent 30 ms
//! here, triangulating and hashing the whole mesh, for a 1–5 ms tool).

use crate::mesh::{FaceId, Mesh, VertexId};
use glam::DVec3;

/// Crossing triangle pairs that involve a face of `after` that is not a face
/// of `before` (same vertex cycle up to rotation, vertex ids kept): the
/// check of a local operator (a handle, a pipe) that added or reshaped
/// those faces, blind to crossings the input already had. Coplanar
/// contacts count (`triangles_meet`).
///
/// Only faces whose corners' box meets the new faces' box can hold a
/// triangle in a tested pair; they are triangulated with every face around
/// their vertices (the faces that could share a diagonal or a multi-edge
/// with them, `triangulate_faces`), the rest of the mesh is not read.
///
/// Cancellable like [`super::crossing_pairs`].
pub fn crossings_of_new_faces(before: &Mesh, after: &Mesh) -> usize {
    crossings_of_new_faces_upto(before, after, usize::MAX).0
}

/// [`crossings_of_new_faces`] counting up to `limit` pairs, and whether it
/// stopped there (`crossing_pairs_upto`).
pub fn crossings_of_new_faces_upto(before: &Mesh, after: &Mesh, limit: usize) -> (usize, bool) {
    let new_face = new_faces(before, after);
    let pos = after.positions();
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for f in after.faces().filter(|f| new_face[f.idx()]) {
        for v in after.face_vertices(f) {
            lo = lo.min(pos[v.idx()]);
            hi = hi.max(pos[v.idx()]);
        }
    }
    if lo.cmpgt(hi).any() || crate::cancel::requested() {
        return (0, false); // no new face with a corner
    }
    // faces whose box meets the new faces' box, then every face around
    // their vertices
    let mut near: Vec<bool> = after
        .faces()
        .map(|f| {
            !after.is_hole(f) && {
                let (mut a, mut b) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
                for v in after.face_vertices(f) {
                    a = a.min(pos[v.idx()]);
                    b = b.max(pos[v.idx()]);
                }
                !(a.cmpgt(hi).any() || b.cmplt(lo).any())
            }
        })
        .collect();
    let real = after.n_faces() - after.n_holes();
    let t = if near.iter().filter(|&&x| x).count() == real {
        // every face (the wireframe tools: all new)
        after.triangulate()
    } else {
        let meets: Vec<FaceId> = after.faces().filter(|f| near[f.idx()]).collect();
        crate::geometry::triangulate::mark_faces_around(after, meets, &mut near);
        let listed: Vec<u32> = (0..after.n_faces() as u32).filter(|&f| near[f as usize] && !after.is_hole(FaceId(f))).collect();
        crate::geometry::triangulate::triangulate_faces(after, &listed)
    };
    let focus: Vec<bool> = t.tri_face.iter().map(|&f| new_face[f as usize]).collect();
    let mut p = pos.to_vec();
    p.extend_from_slice(&t.points);
    let (pairs, stopped) = super::crossing_pairs_upto(&p, &t.tris, Some(&focus), true, &[], limit);
    (pairs.len(), stopped)
}

/// Per face of `after`: a real face whose vertex cycle (up to rotation) is
/// not one of `before`'s real faces. Local operators keep most face ids, so
/// a face equal to `before`'s face of the same id is settled at once; any
/// other is looked for among `before`'s faces around its first vertex (a
/// face through a vertex is one of the faces around it), so no table of
/// the whole mesh is built.
fn new_faces(before: &Mesh, after: &Mesh) -> Vec<bool> {
    let (mut a, mut b) = (Vec::new(), Vec::new());
    // a point-sphere's face has no corners: old when `before` has one
    let mut before_empty: Option<bool> = None;
    after
        .faces()
        .map(|f| {
            if after.is_hole(f) {
                return false;
            }
            cycle(after, f, &mut a);
            let old = |g: FaceId, b: &mut Vec<u32>| !before.is_hole(g) && cycle_of_len(before, g, a.len(), b) && same_cycle(&a, b);
            if f.idx() < before.n_faces() && old(f, &mut b) {
                return false;
            }
            let Some(&v) = a.first() else {
                return !*before_empty.get_or_insert_with(|| before.faces().any(|g| !before.is_hole(g) && before.face_vertices(g).next().is_none()));
            };
            let Some(s) = ((v as usize) < before.n_vertices()).then(|| before.vertex_halfedge(VertexId(v))).flatten() else {
                return true;
            };
            let mut h = s;
            loop {
                if old(before.face(h), &mut b) {
                    return false;
                }
                h = before.rotate(h);
                if h == s {
                    return true;
                }
            }
        })
        .collect()
}

fn cycle(m: &Mesh, f: FaceId, out: &mut Vec<u32>) {
    out.clear();
    out.extend(m.face_vertices(f).map(|v| v.0));
}

/// `cycle` when face `f` has `n` corners, else false after reading at most
/// n + 1 of them: a face beside a 100,000-gon of `before` is compared with
/// it at the cost of its own size (collecting the whole 100,000-gon for
/// every face around it made the check quadratic).
fn cycle_of_len(m: &Mesh, f: FaceId, n: usize, out: &mut Vec<u32>) -> bool {
    out.clear();
    for v in m.face_vertices(f) {
        if out.len() == n {
            return false;
        }
        out.push(v.0);
    }
    out.len() == n
}

/// Whether `b` is `a` read from another corner.
fn same_cycle(a: &[u32], b: &[u32]) -> bool {
    a.len() == b.len() && (a.is_empty() || (0..b.len()).any(|k| b[k] == a[0] && b[k..].iter().chain(&b[..k]).eq(a)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::crossing::crossing_pairs;

    /// New faces found by id and around a vertex equal those by a set of
    /// all cycles (the first implementation) on handles, a wireframe and a
    /// mesh against itself.
    #[test]
    fn new_faces_as_by_a_set() {
        use std::collections::HashSet;
        let by_set = |before: &crate::mesh::Mesh, after: &crate::mesh::Mesh| -> Vec<bool> {
            let cycle = |m: &crate::mesh::Mesh, f: crate::mesh::FaceId| {
                let mut c: Vec<u32> = m.face_vertices(f).map(|v| v.0).collect();
                let k = (0..c.len()).min_by_key(|&i| c[i]).unwrap_or(0);
                c.rotate_left(k);
                c
            };
            let old: HashSet<Vec<u32>> = before.faces().filter(|&f| !before.is_hole(f)).map(|f| cycle(before, f)).collect();
            after.faces().map(|f| !after.is_hole(f) && !old.contains(&cycle(after, f))).collect()
        };
        let g = crate::primitives::genus_surface(2).unwrap();
        let t = crate::primitives::torus(12, 8, 3.0, 1.0).unwrap();
        // the highest and the lowest face (the catalog's selection for handles)
        let ends = |m: &crate::mesh::Mesh| {
            let z: Vec<f64> = m.face_centroids().iter().map(|p| p.z).collect();
            [(0..z.len()).max_by(|&a, &b| z[a].total_cmp(&z[b])).unwrap(), (0..z.len()).min_by(|&a, &b| z[a].total_cmp(&z[b])).unwrap()]
        };
        let cases = [
            (t.clone(), t.multi_face_handle(&ends(&t), 0.5, -0.25).unwrap()),
            (g.clone(), g.multi_face_handle_edges(&ends(&g)).unwrap().0),
            (crate::mesh::Mesh::new(), g.wireframe(0.05, None).unwrap()),
            (g.clone(), g.clone()),
            (crate::schemes::hosts::test_meshes::cube_with_self_loop(), crate::schemes::hosts::test_meshes::cube_with_self_loop()),
        ];
        for (before, after) in &cases {
            let got = new_faces(before, after);
            assert_eq!(got, by_set(before, after));
            assert!(got.iter().any(|&x| x) == (before != after));
        }
    }

    /// The whole-mesh check this module replaced: every face triangulated,
    /// new faces by a set of all cycles.
    fn whole_mesh_count(before: &Mesh, after: &Mesh) -> usize {
        use std::collections::HashSet;
        let key = |m: &Mesh, f: FaceId| {
            let mut c: Vec<u32> = m.face_vertices(f).map(|v| v.0).collect();
            let k = (0..c.len()).min_by_key(|&i| c[i]).unwrap_or(0);
            c.rotate_left(k);
            c
        };
        let old: HashSet<Vec<u32>> = before.faces().filter(|&f| !before.is_hole(f)).map(|f| key(before, f)).collect();
        let t = after.triangulate();
        let focus: Vec<bool> = t.tri_face.iter().map(|&f| !old.contains(&key(after, FaceId(f)))).collect();
        let mut p = after.positions().to_vec();
        p.extend_from_slice(&t.points);
        crossing_pairs(&p, &t.tris, Some(&focus), true).len()
    }

    /// The local check counts what the whole-mesh check counts, with and
    /// without crossings: handles through the torus (64 and 21 pairs) and
    /// beside it, a wireframe (every face new) thin and thick (2,060
    /// pairs), and no change at all.
    #[test]
    fn local_check_equals_the_whole_mesh_check() {
        let t = crate::primitives::torus(12, 8, 3.0, 1.0).unwrap();
        let g = crate::primitives::genus_surface(2).unwrap();
        let cases = [
            (t.clone(), t.multi_face_handle_edges(&[0, 50]).unwrap().0),
            (t.clone(), t.multi_face_handle_edges(&[3, 40]).unwrap().0),
            (t.clone(), t.multi_face_handle_edges(&[0, 1]).unwrap().0),
            (t.clone(), t.multi_face_handle(&[10, 60], 0.5, -0.25).unwrap()),
            (Mesh::new(), g.wireframe(0.05, None).unwrap()),
            (Mesh::new(), t.wireframe(0.6, None).unwrap()),
            (g.clone(), g.clone()),
        ];
        let mut crossing = 0;
        for (k, (before, after)) in cases.iter().enumerate() {
            let n = crossings_of_new_faces(before, after);
            assert_eq!(n, whole_mesh_count(before, after), "case {k}");
            crossing += (n > 0) as usize;
        }
        assert!(crossing >= 3, "the cases must include crossings: {crossing}");
    }

    #[test]
    fn counting_stops_at_the_limit() {
        // a wireframe far thicker than its edges: every tube through its
        // neighbours, thousands of crossing pairs
        let m = crate::schemes::conway::seeds::prism(60).unwrap();
        let out = m.wireframe(0.5, None).unwrap();
        let empty = Mesh::new();
        let all = crossings_of_new_faces(&empty, &out);
        assert!(all > 2000, "{all} pairs: the case must cross a lot");
        assert_eq!(crossings_of_new_faces_upto(&empty, &out, all), (all, true));
        assert_eq!(crossings_of_new_faces_upto(&empty, &out, all + 1), (all, false));
        let (some, stopped) = crossings_of_new_faces_upto(&empty, &out, 500);
        assert!(stopped && (500..all).contains(&some), "{some} of {all}");
    }
}

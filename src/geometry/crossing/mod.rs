//! Exact crossing checks between triangles, shared by every construction
//! that can make a surface pass through itself (generalized Menger sponges,
//! handles, pipes) and by the self-intersection queries.
//!
//! [`triangles_cross`] is the predicate: a proper crossing, an edge of one
//! triangle through the interior of the other, with orientations relative
//! to the lengths involved so that tiny features are tested as strictly as
//! large ones. [`local_crossings`] tests groups of triangles that one rule
//! placed (Menger's per-vertex check); [`crossing_pairs`] scans a whole
//! triangulation, or only the pairs that involve chosen triangles.

use glam::DVec3;

mod bvh;
mod hub;
mod local;
mod predicate;

pub use local::{crossings_of_new_faces, crossings_of_new_faces_upto};

#[cfg(test)]
pub(crate) use predicate::{contact_parts, meet_without_rejection, separated_for_test};
pub(crate) use predicate::{triangles_cross, triangles_meet};

/// Input vertices whose local structure crosses itself: the output
/// triangles with a corner placed by an input vertex's rule ([`Built`]'s
/// `owner`) are tested pairwise per vertex; both triangles' owners of every
/// crossing pair are returned. Linear in the output (a vertex's triangles
/// are bounded by its valence), parallel over vertices.
///
/// Cancellable ([`crate::cancel`]): once cancellation is requested the
/// result is incomplete, and callers check [`crate::cancel::check`].
pub(crate) fn local_crossings(p: &[DVec3], tris: &[[u32; 3]], owner: &[u32], first_inner: u32, only: Option<&[bool]>) -> Vec<u32> {
    use rayon::prelude::*;
    // points added by the triangulation have no owner
    let owner_of = |v: u32| owner.get(v as usize).copied().unwrap_or(u32::MAX);
    // triangles bucketed by owner (counting sort)
    let owners_of = |t: &[u32; 3]| {
        let mut o = t.map(owner_of);
        o.sort_unstable();
        [0, 1, 2].map(|k| if o[k] != u32::MAX && (k == 0 || o[k] != o[k - 1]) { o[k] } else { u32::MAX })
    };
    let nown = owner.iter().filter(|&&o| o != u32::MAX).map(|&o| o as usize + 1).max().unwrap_or(0);
    let mut start = vec![0usize; nown + 1];
    for t in tris {
        for o in owners_of(t) {
            if o != u32::MAX {
                start[o as usize + 1] += 1;
            }
        }
    }
    for k in 0..nown {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut by_owner = vec![0u32; start[nown]];
    for (i, t) in tris.iter().enumerate() {
        for o in owners_of(t) {
            if o != u32::MAX {
                by_owner[fill[o as usize]] = i as u32;
                fill[o as usize] += 1;
            }
        }
    }
    let owners: Vec<usize> = (0..nown).filter(|&k| start[k + 1] > start[k] && only.map_or(true, |f| f[k])).collect();
    let mut bad: Vec<u32> = owners
        .par_iter()
        .flat_map_iter(|&k| {
            let mut out: Vec<u32> = Vec::new();
            // cancelled: nothing, the caller checks
            if crate::cancel::requested() {
                return out;
            }
            // sweep along x over the bucket's boxes; two triangles of the
            // outer remeshing (all corners below `first_inner`) lie in the
            // input's faces and cannot cross
            let mut boxes: Vec<(DVec3, DVec3, u32, bool, [u32; 3])> = by_owner[start[k]..start[k + 1]]
                .iter()
                .map(|&t| {
                    let tv = tris[t as usize];
                    let q = tv.map(|v| p[v as usize]);
                    (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]), t, tv.iter().all(|&v| v < first_inner), owners_of(&tv))
                })
                .collect();
            boxes.sort_unstable_by(|a, b| a.0.x.total_cmp(&b.0.x));
            for a in 0..boxes.len() {
                let (la, ha, ta, oa, wa) = boxes[a];
                for &(lb, hb, tb, ob, wb) in &boxes[a + 1..] {
                    if lb.x > ha.x {
                        break;
                    }
                    if (oa && ob) || la.cmpgt(hb).any() || lb.cmpgt(ha).any() {
                        continue;
                    }
                    // a pair in the buckets of several common owners (a
                    // sixth of the torus row's pairs) is tested in the
                    // first checked one only: what it finds does not
                    // depend on the bucket
                    if wa.iter().any(|&o| o < k as u32 && wb.contains(&o) && only.map_or(true, |f| f[o as usize])) {
                        continue;
                    }
                    let (ta, tb) = (tris[ta as usize], tris[tb as usize]);
                    if triangles_cross(ta, ta.map(|v| p[v as usize]), tb, tb.map(|v| p[v as usize])) {
                        out.extend(ta.iter().chain(&tb).map(|&v| owner_of(v)).filter(|&o| o != u32::MAX));
                    }
                }
            }
            out
        })
        .collect();
    bad.sort_unstable();
    bad.dedup();
    bad
}

/// Crossing triangle pairs `(i, j)`, `i < j`, of a triangulation
/// ([`triangles_meet`] with `coplanar`), among the pairs whose bounding
/// boxes overlap, found by a bounding volume hierarchy ([`bvh`]); pairs
/// sharing a vertex of many triangles, among those whose arcs of
/// directions there overlap ([`hub`]). With
/// `focus`, only pairs with at least one focused triangle are tested, and
/// only triangles overlapping the focused triangles' bounding box enter the
/// hierarchy (a local check after a local change costs what the change
/// touched). Pairs are sorted.
///
/// Cancellable like [`local_crossings`].
pub fn crossing_pairs(p: &[DVec3], tris: &[[u32; 3]], focus: Option<&[bool]>, coplanar: bool) -> Vec<(u32, u32)> {
    crossing_pairs_in_pieces(p, tris, focus, coplanar, &[])
}

/// [`crossing_pairs`] where the caller knows some triangles to lie on one
/// convex piece of surface (the lateral faces of a convex prism: they meet
/// only along their shared sides and corners): triangles with the same
/// `piece[i]` other than `u32::MAX` are not tested against each other. An
/// empty `piece` is [`crossing_pairs`].
pub fn crossing_pairs_in_pieces(p: &[DVec3], tris: &[[u32; 3]], focus: Option<&[bool]>, coplanar: bool, piece: &[u32]) -> Vec<(u32, u32)> {
    crossing_pairs_upto(p, tris, focus, coplanar, piece, usize::MAX).0
}

/// [`crossing_pairs_in_pieces`] until `limit` pairs are found, and whether
/// it stopped there (then the pairs are `limit` or a few more of them, not
/// all): a report of a surface folded through itself everywhere costs what
/// `limit` pairs cost, not the quadratically many it has.
pub fn crossing_pairs_upto(p: &[DVec3], tris: &[[u32; 3]], focus: Option<&[bool]>, coplanar: bool, piece: &[u32], limit: usize) -> (Vec<(u32, u32)>, bool) {
    use rayon::prelude::*;
    debug_assert!(piece.is_empty() || piece.len() == tris.len());
    // the hierarchy's records, made once (boxes, ids and focus together:
    // no box table, centroid table or permutation besides them)
    let mut items: Vec<bvh::Item> = tris
        .par_iter()
        .enumerate()
        .map(|(i, &t)| bvh::Item::of(p, t, i as u32, focus.map_or(true, |f| f[i])))
        .collect();
    if crate::cancel::requested() {
        return (Vec::new(), false);
    }
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    let mut n_focus = 0usize;
    for b in items.iter().filter(|b| b.focus) {
        lo = lo.min(b.lo);
        hi = hi.max(b.hi);
        n_focus += 1;
    }
    if n_focus == 0 {
        return (Vec::new(), false);
    }
    items.retain(|b| !(b.lo.cmpgt(hi).any() || b.hi.cmplt(lo).any()));
    let test = |i: u32, j: u32| {
        if !piece.is_empty() && piece[i as usize] != u32::MAX && piece[i as usize] == piece[j as usize] {
            return false;
        }
        let (ti, tj) = (tris[i as usize], tris[j as usize]);
        // two sides shared (a face's own triangles): never a contact, and
        // a sixth of a wireframe's pairs; decided before reading the points
        if ti.iter().filter(|v| tj.contains(v)).count() >= 2 {
            return false;
        }
        triangles_meet(ti, ti.map(|v| p[v as usize]), tj, tj.map(|v| p[v as usize]), coplanar)
    };
    let budget = bvh::Budget::new(limit);
    let mut found = hub::pairs_upto(p, tris, items, &test, &budget);
    found.par_sort_unstable();
    found.dedup();
    (found, budget.spent())
}

/// The uniform-grid scan [`crossing_pairs`] used before its hierarchy: the
/// reference its results are compared with.
#[cfg(test)]
fn crossing_pairs_grid(p: &[DVec3], tris: &[[u32; 3]], focus: Option<&[bool]>, coplanar: bool) -> Vec<(u32, u32)> {
    use rayon::prelude::*;
    let boxes: Vec<(DVec3, DVec3)> = tris
        .par_iter()
        .map(|t| {
            let q = t.map(|v| p[v as usize]);
            (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]))
        })
        .collect();
    let focused = |i: usize| focus.map_or(true, |f| f[i]);
    let cancelled = crate::cancel::requested;
    if cancelled() {
        return Vec::new();
    }
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    let mut n_focus = 0usize;
    for (i, b) in boxes.iter().enumerate() {
        if focused(i) {
            lo = lo.min(b.0);
            hi = hi.max(b.1);
            n_focus += 1;
        }
    }
    if n_focus == 0 {
        return Vec::new();
    }
    let overlaps = |b: &(DVec3, DVec3)| !(b.0.cmpgt(hi).any() || b.1.cmplt(lo).any());
    let cand: Vec<u32> = (0..tris.len() as u32).filter(|&i| overlaps(&boxes[i as usize])).collect();
    // about four triangles per cell, at most 256 cells along an axis
    let n = ((4.0 * cand.len() as f64).cbrt().ceil() as usize).clamp(1, 256);
    let cell = (hi - lo) / n as f64 + DVec3::splat(1e-12);
    let key = |x: DVec3| {
        let c = ((x - lo) / cell).floor();
        let k = |c: f64| c.clamp(0.0, (n - 1) as f64) as u32;
        [k(c.x), k(c.y), k(c.z)]
    };
    let mut entries: Vec<(u32, u32)> = Vec::with_capacity(cand.len());
    for (k, &i) in cand.iter().enumerate() {
        if k % 65536 == 0 && cancelled() {
            return Vec::new();
        }
        let (a, b) = (key(boxes[i as usize].0), key(boxes[i as usize].1));
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    entries.push(((x * n as u32 + y) * n as u32 + z, i));
                }
            }
        }
    }
    if cancelled() {
        return Vec::new();
    }
    entries.par_sort_unstable();
    if cancelled() {
        return Vec::new();
    }
    let starts: Vec<usize> = (0..entries.len()).filter(|&k| k == 0 || entries[k].0 != entries[k - 1].0).collect();
    let mut found: Vec<(u32, u32)> = starts
        .par_iter()
        .enumerate()
        .flat_map_iter(|(s, &a)| {
            let b = starts.get(s + 1).copied().unwrap_or(entries.len());
            let cellv = &entries[a..b];
            let mut out = Vec::new();
            // cancelled: nothing, the caller checks
            if crate::cancel::requested() {
                return out;
            }
            for (k, &(_, i)) in cellv.iter().enumerate() {
                for &(_, j) in &cellv[k + 1..] {
                    let (iu, ju) = (i as usize, j as usize);
                    if !(focused(iu) || focused(ju)) {
                        continue;
                    }
                    let (bi, bj) = (boxes[iu], boxes[ju]);
                    if bi.0.cmpgt(bj.1).any() || bj.0.cmpgt(bi.1).any() {
                        continue;
                    }
                    // test a pair once, in the cell of its boxes' common
                    // low corner (both triangles are in it: `key` is monotonic)
                    let c = key(bi.0.max(bj.0));
                    if (c[0] * n as u32 + c[1]) * n as u32 + c[2] != cellv[0].0 {
                        continue;
                    }
                    let (ti, tj) = (tris[iu], tris[ju]);
                    if triangles_meet(ti, ti.map(|v| p[v as usize]), tj, tj.map(|v| p[v as usize]), coplanar) {
                        out.push((i.min(j), i.max(j)));
                    }
                }
            }
            out
        })
        .collect();
    found.par_sort_unstable();
    found.dedup();
    found
}

/// Crossing triangle pairs of the whole triangulation of `m`
/// ([`triangles_meet`] with `coplanar`; the Menger figures count proper
/// crossings only, `coplanar = false`). Pairs index `m.triangulate()`'s
/// triangles and are sorted.
pub fn mesh_crossing_pairs(m: &crate::mesh::Mesh, coplanar: bool) -> Vec<(u32, u32)> {
    let (tris, p) = super::triangles_with_points(m);
    crossing_pairs(&p, &tris, None, coplanar)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_skip_only_their_own_pairs() {
        // two crossing triangles and a third crossing the second
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.3, 0.2, 1.0), DVec3::new(0.2, 0.3, 1.0), DVec3::new(0.25, -1.0, 0.25), DVec3::new(0.25, 1.0, 0.25), DVec3::new(0.25, 0.0, 0.3)];
        let tris = [[0, 1, 2], [3, 4, 5], [6, 7, 8]];
        let all = crossing_pairs(&p, &tris, None, true);
        assert!(all.contains(&(0, 1)), "{all:?}");
        assert_eq!(crossing_pairs_in_pieces(&p, &tris, None, true, &[]), all);
        assert_eq!(crossing_pairs_in_pieces(&p, &tris, None, true, &[u32::MAX; 3]), all);
        let some = crossing_pairs_in_pieces(&p, &tris, None, true, &[7, 7, u32::MAX]);
        assert_eq!(some, all.iter().copied().filter(|&x| x != (0, 1)).collect::<Vec<_>>());
    }

    #[test]
    fn triangle_crossing_predicate() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let ids = [0, 1, 2];
        // a triangle piercing t's interior
        let s = [DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.3, 0.2, 1.0), DVec3::new(0.2, 0.3, 1.0)];
        assert!(triangles_cross(ids, t, [3, 4, 5], s));
        // the same one lifted off t's plane
        let up = s.map(|p| p + DVec3::Z * 1.5);
        assert!(!triangles_cross(ids, t, [3, 4, 5], up));
        // sharing an edge: never a crossing
        assert!(!triangles_cross(ids, t, [0, 1, 6], [DVec3::ZERO, DVec3::X, DVec3::new(0.5, -0.5, 0.0)]));
        // sharing a vertex, the opposite edge through t's interior
        let f = [DVec3::ZERO, DVec3::new(0.5, 0.2, -1.0), DVec3::new(0.2, 0.5, 1.0)];
        assert!(triangles_cross(ids, t, [0, 7, 8], f));
        // sharing a vertex and merely touching there
        let g = [DVec3::ZERO, DVec3::new(-1.0, 0.0, 1.0), DVec3::new(0.0, -1.0, 1.0)];
        assert!(!triangles_cross(ids, t, [0, 9, 10], g));
        // an edge in t's plane through its interior: a contact only the
        // coplanar mode counts (a handle's first segment folded onto its neighbour)
        let c = [DVec3::new(0.2, 0.2, 0.0), DVec3::new(2.0, 2.0, 0.0), DVec3::new(0.2, 0.2, 1.0)];
        assert!(!triangles_cross(ids, t, [3, 4, 5], c));
        assert!(triangles_meet(ids, t, [3, 4, 5], c, true));
        // coplanar overlapping triangles, no vertex shared
        let o = [DVec3::new(0.1, 0.1, 0.0), DVec3::new(2.0, 0.1, 0.0), DVec3::new(0.1, 2.0, 0.0)];
        assert!(triangles_meet(ids, t, [3, 4, 5], o, true));
        // coplanar neighbours side by side, sharing a vertex only: no contact
        let n = [DVec3::ZERO, DVec3::new(-1.0, 0.0, 0.0), DVec3::new(0.0, -1.0, 0.0)];
        assert!(!triangles_meet(ids, t, [0, 4, 5], n, true));
        // sharing a vertex, an edge from it lying in t's plane across t
        let d = [DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.0, 0.0, 1.0)];
        assert!(!triangles_cross(ids, t, [0, 4, 5], d));
        assert!(triangles_meet(ids, t, [0, 4, 5], d, true));
        // two triangles crossing in an X, each edge meeting the other only on
        // its boundary (a twisted handle segment): they share a segment
        let a = 1.0 / 3.0;
        let x1 = [DVec3::new(a, a, 0.9), DVec3::new(-a, a, 1.0), DVec3::new(-a, -a, 1.0)];
        let x2 = [DVec3::new(a, a, 1.0), DVec3::new(-a, a, 0.9), DVec3::new(-a, -a, 0.9)];
        assert!(!triangles_cross(ids, x1, [3, 4, 5], x2));
        assert!(triangles_meet(ids, x1, [3, 4, 5], x2, true));
        // a convex fan's neighbours meeting only at their common vertex
        let f1 = [DVec3::ZERO, DVec3::X, DVec3::new(0.0, 1.0, 0.2)];
        let f2 = [DVec3::ZERO, DVec3::new(0.0, 1.0, 0.2), DVec3::new(-1.0, 0.0, 0.1)];
        assert!(!triangles_meet([0, 1, 2], f1, [0, 2, 3], f2, true));
        // sharing a vertex, one folded through the other beyond it
        let f3 = [DVec3::ZERO, DVec3::new(0.5, 0.5, -1.0), DVec3::new(0.5, 0.5, 1.0)];
        assert!(triangles_meet([0, 1, 2], f1, [0, 4, 5], f3, true));
    }

    /// The hierarchy finds exactly the grid's pairs: a random soup of
    /// small triangles (many crossings, touching and coplanar ones), a
    /// wireframe (thin tubes, dense), with and without a focus, both modes.
    #[test]
    fn hierarchy_equals_grid() {
        let mut rng = crate::test_rng::Xorshift::new(0x9e37_79b9_7f4a_7c15);
        let mut rnd = || rng.unit();
        let mut p = Vec::new();
        let mut tris = Vec::new();
        for t in 0..3000u32 {
            let c = DVec3::new(rnd(), rnd(), rnd()) * 4.0;
            for _ in 0..3 {
                // coordinates on a coarse lattice now and then: coplanar and touching cases
                let q = c + DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 0.6;
                p.push(if t % 5 == 0 { (q * 4.0).round() / 4.0 } else { q });
            }
            tris.push([3 * t, 3 * t + 1, 3 * t + 2]);
        }
        // shared corners: every 7th triangle reuses a corner of the one before
        for t in (7..tris.len()).step_by(7) {
            tris[t][0] = tris[t - 1][1];
        }
        let wire = crate::primitives::torus(24, 12, 3.0, 1.0).unwrap().wireframe(0.05, None).unwrap();
        let (wt, wp) = crate::geometry::triangles_with_points(&wire);
        let focus: Vec<bool> = (0..tris.len()).map(|i| i % 3 == 0).collect();
        let wfocus: Vec<bool> = (0..wt.len()).map(|i| i < 50).collect();
        for coplanar in [false, true] {
            let all = crossing_pairs(&p, &tris, None, coplanar);
            assert!(all.len() > 100, "{}", all.len());
            assert_eq!(all, crossing_pairs_grid(&p, &tris, None, coplanar));
            assert_eq!(crossing_pairs(&p, &tris, Some(&focus), coplanar), crossing_pairs_grid(&p, &tris, Some(&focus), coplanar));
            assert_eq!(crossing_pairs(&wp, &wt, None, coplanar), crossing_pairs_grid(&wp, &wt, None, coplanar));
            assert_eq!(crossing_pairs(&wp, &wt, Some(&wfocus), coplanar), crossing_pairs_grid(&wp, &wt, Some(&wfocus), coplanar));
        }
    }

    #[test]
    fn scan_finds_pairs_and_focus_restricts_them() {
        // triangle 0 pierced by 1; 2 far away; 3 pierces 2
        let p = vec![
            DVec3::ZERO, DVec3::X, DVec3::Y,
            DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.3, 0.2, 1.0), DVec3::new(0.2, 0.3, 1.0),
            DVec3::new(10.0, 0.0, 0.0), DVec3::new(11.0, 0.0, 0.0), DVec3::new(10.0, 1.0, 0.0),
            DVec3::new(10.2, 0.2, -1.0), DVec3::new(10.3, 0.2, 1.0), DVec3::new(10.2, 0.3, 1.0),
        ];
        let tris = [[0, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11]];
        assert_eq!(crossing_pairs(&p, &tris, None, false), vec![(0, 1), (2, 3)]);
        assert_eq!(crossing_pairs(&p, &tris, Some(&[false, false, false, true]), false), vec![(2, 3)]);
        assert_eq!(crossing_pairs(&p, &tris, Some(&[false; 4]), false), vec![]);
    }
}


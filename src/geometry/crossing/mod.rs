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
            let mut boxes: Vec<(DVec3, DVec3, u32, bool)> = by_owner[start[k]..start[k + 1]]
                .iter()
                .map(|&t| {
                    let tv = tris[t as usize];
                    let q = tv.map(|v| p[v as usize]);
                    (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]), t, tv.iter().all(|&v| v < first_inner))
                })
                .collect();
            boxes.sort_unstable_by(|a, b| a.0.x.total_cmp(&b.0.x));
            for a in 0..boxes.len() {
                let (la, ha, ta, oa) = boxes[a];
                for &(lb, hb, tb, ob) in &boxes[a + 1..] {
                    if lb.x > ha.x {
                        break;
                    }
                    if (oa && ob) || la.cmpgt(hb).any() || lb.cmpgt(ha).any() {
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

/// Orientation of `d` against the plane through `a, b, c`, relative to the
/// lengths involved, so tiny features are tested as strictly as large ones.
pub(crate) fn orient_rel(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let (u, v, w) = (b - a, c - a, d - a);
    let scale = u.length() * v.length() * w.length();
    if scale == 0.0 { 0.0 } else { u.cross(v).dot(w) / scale }
}

/// Whether two triangles cross properly: an edge of one passes through the
/// interior of the other. Triangles sharing an edge are never counted;
/// triangles sharing a vertex only with their edges that avoid it; touching
/// contacts (within `1e-10`, relative) are not counted.
pub(crate) fn triangles_cross(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3]) -> bool {
    triangles_meet(ti, pi, tj, pj, false)
}

/// [`triangles_cross`], and with `coplanar` also an edge of one triangle
/// lying in the other's plane and passing through its interior (a surface
/// folded onto another along a line, or coplanar overlapping triangles):
/// the contacts a general self-intersection check must count, and which the
/// Menger construction's own check leaves to [`triangles_cross`] (its
/// figures are counted that way).
pub(crate) fn triangles_meet(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3], coplanar: bool) -> bool {
    if side_plane_rejects(pi, pj) && (separated_by_side_plane(ti, pi, tj, pj) || separated_by_side_plane(tj, pj, ti, pi)) {
        return false;
    }
    meet_without_rejection(ti, pi, tj, pj, coplanar)
}

/// [`triangles_meet`]'s exact tests, without the side-plane rejection.
pub(crate) fn meet_without_rejection(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3], coplanar: bool) -> bool {
    match triangles_meet_edges(ti, pi, tj, pj, coplanar) {
        Edges::Meet => true,
        Edges::Apart => false,
        Edges::Miss => coplanar && overlap_on_plane_line(ti, pi, tj, pj),
    }
}

/// What the edge tests found.
enum Edges {
    /// An edge of one meets the other's interior.
    Meet,
    /// No edge does, and [`overlap_on_plane_line`] would say no as well
    /// (two sides shared, or one triangle off the other's plane beyond its
    /// tolerance but for a shared corner): most candidate pairs of a scan,
    /// which then skip it.
    Apart,
    /// No edge does.
    Miss,
}

#[cfg(test)]
pub(crate) fn separated_for_test(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3]) -> bool {
    side_plane_rejects(pi, pj) && (separated_by_side_plane(ti, pi, tj, pj) || separated_by_side_plane(tj, pj, ti, pi))
}

/// Whether [`separated_by_side_plane`] may settle a pair without changing
/// an answer of the exact tests: planes less than 1e-10 rad apart (coplanar
/// to every test, which a separating plane settles) or more than 1e-4 rad
/// (the line where they meet is well conditioned), and neither triangle a
/// needle. In between the tests were found answering by rounding (contacts
/// between nearly coplanar neighbours, on Menger outputs, that CGAL does
/// not find; `overlap_on_plane_line` now treats planes under 1e-6 rad as
/// coplanar), and the rejection leaves those pairs to them, so that it
/// never changes a count (`menger::diagnose::rejection_check`).
fn side_plane_rejects(pi: [DVec3; 3], pj: [DVec3; 3]) -> bool {
    // and neither triangle a needle (smallest angle below about 1e-4 rad):
    // its plane is rounding noise, which the exact tests read as crossing it
    let normal = |p: [DVec3; 3]| {
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let l2 = (p[1] - p[0]).length_squared().max((p[2] - p[1]).length_squared()).max((p[0] - p[2]).length_squared());
        (n, n.length() > 1e-4 * l2)
    };
    let ((ni, oki), (nj, okj)) = (normal(pi), normal(pj));
    let (s, l) = (ni.cross(nj).length(), ni.length() * nj.length());
    oki && okj && (s <= 1e-10 * l || s >= 1e-4 * l)
}

/// Which of the tests of [`triangles_meet`] find a pair, and its shape
/// (diagnostics of Menger's contacts).
#[cfg(test)]
pub(crate) fn contact_parts(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3]) -> String {
    let (ni, nj) = ((pi[1] - pi[0]).cross(pi[2] - pi[0]), (pj[1] - pj[0]).cross(pj[2] - pj[0]));
    let shared = ti.iter().filter(|v| tj.contains(v)).count();
    let needle = |p: [DVec3; 3], n: DVec3| n.length() / (p[1] - p[0]).length_squared().max((p[2] - p[1]).length_squared()).max((p[0] - p[2]).length_squared());
    format!(
        "edges {} coplanar-edges {} plane-line {}; shared {shared}, sin {:.2e}, shape {:.2e} {:.2e}",
        matches!(triangles_meet_edges(ti, pi, tj, pj, false), Edges::Meet),
        matches!(triangles_meet_edges(ti, pi, tj, pj, true), Edges::Meet),
        overlap_on_plane_line(ti, pi, tj, pj),
        ni.cross(nj).length() / (ni.length() * nj.length()),
        needle(pi, ni),
        needle(pj, nj)
    )
}

/// Quick rejection before the exact tests of [`triangles_meet`]: a plane
/// through a side of triangle `a`, perpendicular to `a`, with every corner
/// of `b` that `a` does not share strictly beyond it (margin `1e-6`,
/// relative, far above the tests' `1e-10`). Then `a` lies on one side and
/// `b` on the other, meeting at most in a shared corner on the side: no
/// crossing or contact of either mode. It settles coplanar neighbours (rows
/// of coplanar faces, as in Menger sponges), which the side-of-plane
/// rejection in `triangles_meet_edges` cannot.
fn separated_by_side_plane(ta: [u32; 3], pa: [DVec3; 3], tb: [u32; 3], pb: [DVec3; 3]) -> bool {
    let n = (pa[1] - pa[0]).cross(pa[2] - pa[0]);
    let shared = ta.iter().position(|v| tb.contains(v));
    'side: for k in 0..3 {
        let k1 = (k + 1) % 3;
        // a shared corner must lie on the plane: on a side through it
        if shared.is_some_and(|s| s != k && s != k1) {
            continue;
        }
        // outward normal of the side (n points to the side of a's
        // counterclockwise order)
        let m = (pa[k1] - pa[k]).cross(n);
        let ml = m.length();
        if ml == 0.0 {
            return false;
        }
        for i in 0..3 {
            if ta.contains(&tb[i]) {
                continue;
            }
            let r = pb[i] - pa[k];
            if !(m.dot(r) > 1e-6 * ml * r.length()) {
                continue 'side;
            }
        }
        return true;
    }
    false
}

/// Whether two triangles in different planes share a piece of positive
/// length of the line where their planes meet: an intersection even where
/// every edge meets the other triangle only on its boundary (two triangles
/// crossing in an X, edge on edge), which the edge tests cannot see.
/// Triangles sharing an edge never count; sharing a vertex, only when the
/// common piece leaves that vertex.
fn overlap_on_plane_line(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3]) -> bool {
    const EPS: f64 = 1e-10;
    if ti.iter().filter(|v| tj.contains(v)).count() >= 2 {
        return false;
    }
    let scale = pi.iter().chain(&pj).fold(0.0f64, |m, x| m.max((*x - pi[0]).length()));
    let (ni, nj) = ((pi[1] - pi[0]).cross(pi[2] - pi[0]), (pj[1] - pj[0]).cross(pj[2] - pj[0]));
    let dir = ni.cross(nj);
    // planes less than 1e-6 rad apart are coplanar here: the line where they
    // meet, and the pieces along it, move by rounding over 1e-16 / angle of
    // the size, which the 1e-9 overlap test below cannot tell from a contact
    // (two Menger triangles 1.2e-10 rad apart sharing a corner were found
    // "meeting" so; CGAL finds nothing there)
    if scale == 0.0 || dir.length() <= 1e-6 * ni.length() * nj.length() {
        return false; // coplanar or degenerate: the edge tests decide
    }
    // the piece of triangle `p` on the plane (`n`, through `o`): its ends
    // projected on `dir`, or None when it misses the plane
    let piece = |p: [DVec3; 3], n: DVec3, o: DVec3| -> Option<(f64, f64)> {
        let d = p.map(|x| n.dot(x - o) / (n.length() * scale));
        // a triangle lying in the other's plane (every corner within the
        // tolerance) is coplanar with it by the edge tests' own measure,
        // which decide it; its "piece" would be the whole triangle projected
        // on a line that rounding chose (planes 1e-10 apart, needles), and
        // reported contacts no exact test finds (CGAL: none on the Menger
        // torus's second iteration, where this found 223)
        if d.iter().all(|x| x.abs() <= EPS) {
            return None;
        }
        // the ends as a running (min, max), in the order they are met (no
        // allocation: this runs for most candidate pairs of a scan)
        let (mut lo, mut hi, mut any) = (f64::INFINITY, f64::NEG_INFINITY, false);
        let mut eat = |t: f64| {
            lo = lo.min(t);
            hi = hi.max(t);
            any = true;
        };
        for k in 0..3 {
            let (a, b) = (k, (k + 1) % 3);
            if d[a].abs() <= EPS {
                eat(dir.dot(p[a]));
            }
            if (d[a] > EPS && d[b] < -EPS) || (d[a] < -EPS && d[b] > EPS) {
                let x = p[a] + (p[b] - p[a]) * (d[a] / (d[a] - d[b]));
                eat(dir.dot(x));
            }
        }
        any.then_some((lo, hi))
    };
    let Some(a) = piece(pi, nj, pj[0]) else { return false };
    let Some(b) = piece(pj, ni, pi[0]) else { return false };
    a.1.min(b.1) - a.0.max(b.0) > 1e-9 * dir.length() * scale
}

fn triangles_meet_edges(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3], coplanar: bool) -> Edges {
    const EPS: f64 = 1e-10;
    // a segment in t's plane through t's interior: it crosses an edge of t
    // properly or ends strictly inside t (orientations in the plane of t,
    // relative like `orient_rel`)
    let in_plane_hits = |s0: DVec3, s1: DVec3, t: [DVec3; 3]| -> bool {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let side = |a: DVec3, b: DVec3, c: DVec3| {
            let (u, v) = (b - a, c - a);
            let scale = u.length() * v.length() * n.length();
            if scale == 0.0 { 0.0 } else { u.cross(v).dot(n) / scale }
        };
        let inside = |q: DVec3| {
            let o = [side(t[0], t[1], q), side(t[1], t[2], q), side(t[2], t[0], q)];
            o.iter().all(|&x| x > EPS) || o.iter().all(|&x| x < -EPS)
        };
        if inside(s0) || inside(s1) {
            return true;
        }
        (0..3).any(|k| {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let (o1, o2) = (side(s0, s1, a), side(s0, s1, b));
            let (o3, o4) = (side(a, b, s0), side(a, b, s1));
            ((o1 > EPS && o2 < -EPS) || (o1 < -EPS && o2 > EPS)) && ((o3 > EPS && o4 < -EPS) || (o3 < -EPS && o4 > EPS))
        })
    };
    // the segment s0 s1 (whose ends lie at relative heights d0, d1 over t's
    // plane, `orient_rel(t[0], t[1], t[2], s)`) through t's interior
    let seg_hits = |s0: DVec3, s1: DVec3, d0: f64, d1: f64, t: [DVec3; 3]| -> bool {
        if !((d0 > EPS && d1 < -EPS) || (d0 < -EPS && d1 > EPS)) {
            return false;
        }
        let o = [orient_rel(s0, s1, t[0], t[1]), orient_rel(s0, s1, t[1], t[2]), orient_rel(s0, s1, t[2], t[0])];
        o.iter().all(|&x| x > EPS) || o.iter().all(|&x| x < -EPS)
    };
    let shared = ti.iter().filter(|v| tj.contains(v)).count();
    if shared >= 2 {
        return Edges::Apart;
    }
    // quick rejection: one triangle strictly on one side of the other's
    // plane (margin far above the relative tolerance of the exact test)
    // (a shared vertex lies in both planes and is left out: the other
    // triangle then meets the plane only there, at a corner)
    for (pa, pb, ta, tb) in [(pi, pj, ti, tj), (pj, pi, tj, ti)] {
        let n = (pa[1] - pa[0]).cross(pa[2] - pa[0]);
        let (mut pos, mut neg, mut dmin, mut rmax) = (0, 0, f64::INFINITY, 0.0f64);
        for k in 0..3 {
            if ta.contains(&tb[k]) {
                continue;
            }
            let r = pb[k] - pa[0];
            let d = n.dot(r);
            if d > 0.0 { pos += 1 } else if d < 0.0 { neg += 1 }
            dmin = dmin.min(d.abs());
            rmax = rmax.max(r.length_squared());
        }
        // squared: min |d| > 1e-6 |n| max |r|
        if (pos == 0 || neg == 0) && pos + neg == 3 - shared && dmin * dmin > 1e-12 * n.length_squared() * rmax {
            // off the plane beyond `overlap_on_plane_line`'s own tolerance
            // too (its heights, computed as it does): its piece of that
            // plane is at most the shared corner, a point
            let scale = pi.iter().chain(&pj).fold(0.0f64, |m, x| m.max((*x - pi[0]).length()));
            return if scale == 0.0 || dmin / (n.length() * scale) > EPS { Edges::Apart } else { Edges::Miss };
        }
    }
    for (ta, tb, pa, pb) in [(ti, tj, pi, pj), (tj, ti, pj, pi)] {
        // orient_rel(pb[0], pb[1], pb[2], x) for the three corners of ta,
        // with pb's plane computed once
        let (u, v) = (pb[1] - pb[0], pb[2] - pb[0]);
        let (n, l) = (u.cross(v), u.length() * v.length());
        let h = pa.map(|x| {
            let w = x - pb[0];
            let scale = l * w.length();
            if scale == 0.0 { 0.0 } else { n.dot(w) / scale }
        });
        for e in 0..3 {
            let (a, b) = (ta[e], ta[(e + 1) % 3]);
            // an edge in the other's plane, even one from the shared vertex
            if coplanar && h[e].abs() <= EPS && h[(e + 1) % 3].abs() <= EPS && in_plane_hits(pa[e], pa[(e + 1) % 3], pb) {
                return Edges::Meet;
            }
            if shared == 1 && (tb.contains(&a) || tb.contains(&b)) {
                continue;
            }
            if seg_hits(pa[e], pa[(e + 1) % 3], h[e], h[(e + 1) % 3], pb) {
                return Edges::Meet;
            }
        }
    }
    Edges::Miss
}

/// Crossing triangle pairs `(i, j)`, `i < j`, of a triangulation
/// ([`triangles_meet`] with `coplanar`), among the pairs whose bounding
/// boxes overlap, found by a bounding volume hierarchy ([`bvh`]). With
/// `focus`, only pairs with at least one focused triangle are tested, and
/// only triangles overlapping the focused triangles' bounding box enter the
/// hierarchy (a local check after a local change costs what the change
/// touched). Pairs are sorted.
///
/// Cancellable like [`local_crossings`].
pub fn crossing_pairs(p: &[DVec3], tris: &[[u32; 3]], focus: Option<&[bool]>, coplanar: bool) -> Vec<(u32, u32)> {
    use rayon::prelude::*;
    let boxes: Vec<(DVec3, DVec3)> = tris
        .par_iter()
        .map(|t| {
            let q = t.map(|v| p[v as usize]);
            (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]))
        })
        .collect();
    if crate::cancel::requested() {
        return Vec::new();
    }
    let focused = |i: usize| focus.map_or(true, |f| f[i]);
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
    let tree = bvh::Bvh::new(&boxes, focus, cand);
    let test = |i: u32, j: u32| {
        let (ti, tj) = (tris[i as usize], tris[j as usize]);
        triangles_meet(ti, ti.map(|v| p[v as usize]), tj, tj.map(|v| p[v as usize]), coplanar)
    };
    let mut found = tree.pairs(&test);
    found.par_sort_unstable();
    found.dedup();
    found
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

/// Crossing triangle pairs that involve a face of `after` that is not a face
/// of `before` (same vertex cycle up to rotation, vertex ids kept): the
/// check of a local operator (a handle, a pipe) that added or reshaped
/// those faces, blind to crossings the input already had. Coplanar
/// contacts count ([`triangles_meet`]).
pub fn crossings_of_new_faces(before: &crate::mesh::Mesh, after: &crate::mesh::Mesh) -> usize {
    let new_face = new_faces(before, after);
    let t = after.triangulate();
    let focus: Vec<bool> = t.tri_face.iter().map(|&f| new_face[f as usize]).collect();
    let mut p = after.positions().to_vec();
    p.extend_from_slice(&t.points);
    crossing_pairs(&p, &t.tris, Some(&focus), true).len()
}

/// Per face of `after`: a real face whose vertex cycle (up to rotation)
/// is not one of `before`'s real faces.
fn new_faces(before: &crate::mesh::Mesh, after: &crate::mesh::Mesh) -> Vec<bool> {
    let old = Cycles::of(before);
    // (no old faces, as for the wireframe tools: every face is new)
    if old.off.len() == 1 {
        after.faces().map(|f| !after.is_hole(f)).collect()
    } else {
        let new = Cycles::of(after);
        let mut keys: Vec<(u64, u32)> = (0..old.len()).filter(|&f| !before.is_hole(crate::mesh::FaceId(f as u32))).map(|f| (old.hash(f), f as u32)).collect();
        keys.sort_unstable();
        (0..new.len())
            .map(|f| {
                if after.is_hole(crate::mesh::FaceId(f as u32)) {
                    return false;
                }
                let h = new.hash(f);
                let first = keys.partition_point(|&(k, _)| k < h);
                !keys[first..].iter().take_while(|&&(k, _)| k == h).any(|&(_, g)| new.same(f, &old, g as usize))
            })
            .collect()
    }
}

/// Every face's vertex cycle, read from the rotation that starts at its
/// smallest vertex (its first occurrence), in one flat array: faces of two
/// meshes are compared as cycles up to rotation, vertex ids kept, with one
/// allocation per mesh instead of one per face.
struct Cycles {
    v: Vec<u32>,
    off: Vec<usize>,
}

impl Cycles {
    fn of(m: &crate::mesh::Mesh) -> Cycles {
        let mut c = Cycles { v: Vec::with_capacity(m.n_halfedges() + m.n_faces()), off: vec![0] };
        for f in m.faces() {
            let s = c.v.len();
            c.v.extend(m.face_vertices(f).map(|v| v.0));
            let k = (0..c.v.len() - s).min_by_key(|&i| c.v[s + i]).unwrap_or(0);
            c.v[s..].rotate_left(k);
            c.off.push(c.v.len());
        }
        c
    }
    fn len(&self) -> usize {
        self.off.len() - 1
    }
    fn cycle(&self, f: usize) -> &[u32] {
        &self.v[self.off[f]..self.off[f + 1]]
    }
    fn hash(&self, f: usize) -> u64 {
        self.cycle(f).iter().fold(self.cycle(f).len() as u64, |h, &x| (h ^ x as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15).rotate_left(29))
    }
    fn same(&self, f: usize, other: &Cycles, g: usize) -> bool {
        self.cycle(f) == other.cycle(g)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
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

    /// New faces by the flat cycle table equal those by a set of cycles
    /// (the table's predecessor) on handles, a wireframe and a mesh
    /// against itself.
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


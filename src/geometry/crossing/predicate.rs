//! The exact predicates of the crossing checks: whether two triangles cross
//! ([`triangles_cross`]) or meet ([`triangles_meet`], contacts included),
//! with orientations relative to the lengths involved and a quick
//! side-plane rejection that never changes an answer.

use glam::DVec3;

/// Orientation of `d` against the plane through `a, b, c`, relative to the
/// lengths involved, so tiny features are tested as strictly as large ones.
fn orient_rel(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
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
    // the exact tests' cheap "apart" (a shared side, or one triangle off the
    // other's plane) first: most pairs of a scan end there (a wireframe's:
    // 85 %), and the side-plane rejection, which costs more, could only
    // have answered "no" as well
    let quick = quick_apart(ti, pi, tj, pj);
    if matches!(quick, Some(Edges::Apart)) {
        return false;
    }
    if side_plane_rejects(pi, pj) && (separated_by_side_plane(ti, pi, tj, pj) || separated_by_side_plane(tj, pj, ti, pi)) {
        return false;
    }
    finish(quick.unwrap_or_else(|| edge_tests(ti, pi, tj, pj, coplanar)), ti, pi, tj, pj, coplanar)
}

/// [`triangles_meet`]'s exact tests, without the side-plane rejection.
#[cfg(test)]
pub(crate) fn meet_without_rejection(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3], coplanar: bool) -> bool {
    finish(triangles_meet_edges(ti, pi, tj, pj, coplanar), ti, pi, tj, pj, coplanar)
}

fn finish(e: Edges, ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3], coplanar: bool) -> bool {
    match e {
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

/// The edge tests, after their cheap answers (diagnostics and the
/// rejection's check run them whole).
#[cfg(test)]
fn triangles_meet_edges(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3], coplanar: bool) -> Edges {
    match quick_apart(ti, pi, tj, pj) {
        Some(e) => e,
        None => edge_tests(ti, pi, tj, pj, coplanar),
    }
}

/// The cheap answers of [`triangles_meet_edges`]: two sides shared, or one
/// triangle strictly on one side of the other's plane.
fn quick_apart(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3]) -> Option<Edges> {
    const EPS: f64 = 1e-10;
    let shared = ti.iter().filter(|v| tj.contains(v)).count();
    if shared >= 2 {
        return Some(Edges::Apart);
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
            // (one square root: the largest of correctly rounded roots is
            // the root of the largest square, the same scale as
            // `overlap_on_plane_line`'s)
            let scale = pi.iter().chain(&pj).fold(0.0f64, |m, x| m.max((*x - pi[0]).length_squared())).sqrt();
            return Some(if scale == 0.0 || dmin / (n.length() * scale) > EPS { Edges::Apart } else { Edges::Miss });
        }
    }
    None
}

/// The edge tests of [`triangles_meet_edges`], for pairs [`quick_apart`]
/// leaves open.
fn edge_tests(ti: [u32; 3], pi: [DVec3; 3], tj: [u32; 3], pj: [DVec3; 3], coplanar: bool) -> Edges {
    const EPS: f64 = 1e-10;
    let shared = ti.iter().filter(|v| tj.contains(v)).count();
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

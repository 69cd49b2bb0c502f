//! The broad phase around *hubs*: vertices that thousands of triangles
//! share (the apex of a cone of Menger's vertex faces, the centroid of a
//! large bent face fanned around it, a pyramid's apex). Every box of such a
//! triangle holds the hub, so the hierarchy of [`super::bvh`] pairs all of
//! them: `self_intersections` of `conway("Y8000")` tested 32 M pairs, the
//! per-face Menger sponge of it 18 s.
//!
//! Two triangles `T₁, T₂` sharing only the vertex `v` meet beyond `v`
//! exactly when their *wedges* at `v` do (`T₁ ∩ T₂` is convex and holds
//! `v`: if it holds another point it holds the segment to it, which near
//! `v` lies in both wedges; conversely near `v` a wedge is its triangle),
//! that is when their arcs of directions on the unit sphere around `v`
//! (from one side's direction to the other's) meet. So a hub's triangles
//! are paired by the boxes of their arcs, which for a fan or a cone touch
//! only their neighbours', and every candidate still goes to the exact
//! predicate ([`super::triangles_meet`]). The other pairs (a hub's
//! triangles against the rest, and against other hubs') take their
//! triangles' boxes, each group in its own hierarchy.
//!
//! **The predicate's tolerances.** `triangles_meet` can answer "meet" for
//! triangles whose exact wedges do not meet: a corner within its 1e-10
//! (relative) of the other's plane counts as on it. Its three ways to say
//! "meet" bound how far apart the arcs can then be, as angles seen from
//! `v`, with `R` the longest side at the hub, and for a triangle `ℓ` its
//! shorter side at `v`, `s` its smallest angle's sine and `a` the distance
//! from `v` to its far side:
//! * an edge through the other's interior (`seg_hits`): margins of 1e-10
//!   against rounding of 1e-16: a real crossing, the arcs meet;
//! * an edge in the other's plane crossing it there (`in_plane_hits`):
//!   the edge is within `1e-10 · 2R / s` of that plane (heights are
//!   relative to the plane's corner angle), seen from `v` at distance at
//!   least `a`: at most `2e-10 / (s₂ · a₁ / R)` apart, which
//!   `1/q₁² + 1/q₂²` with `q = min(s, a/R)` bounds;
//! * a common piece along the line where the planes meet
//!   (`overlap_on_plane_line`, planes at least 1e-6 rad apart): a corner
//!   counted on the other's plane is within `1e-10 · 2R` of it, so within
//!   `2e-4 R` of that line, seen at distance at least `ℓ`: at most
//!   `2.4e-4 R / ℓ` from the line's direction, which the other arc holds
//!   or lies as near to.
//!
//! Each arc's box is widened by `μ = 1e-3 R/ℓ + 1e-9/q² + 1e-12` (four or
//! five times those bounds), so the boxes of two triangles that the
//! predicate can say meet always overlap. Triangles with `μ` above
//! [`MU_MAX`] (needles, sides far shorter than the hub's longest) are left
//! to the triangles' boxes, as is a triangle with two hubs; so are the
//! hubs beyond the [`HUB_MAX`] largest. `hubs_equal_the_plain_scan` checks
//! the answers against the plain hierarchy on cones, fans, folded and
//! near-coplanar fans, needles and tiny sides.

use super::bvh::{Budget, Bvh, Item};
use glam::DVec3;

/// Triangles at a vertex from which it is a hub.
const HUB_MIN: usize = 64;
/// Hubs at most (the largest): each is paired with every other's tree.
const HUB_MAX: usize = 256;
/// Widest margin of an arc's box (radians) for a triangle to join a hub.
const MU_MAX: f64 = 0.05;

const NONE: u32 = u32::MAX;

/// The pairs of the triangles in `items` for which `test` holds, as
/// [`Bvh::pairs_upto`] over all of them finds them, with hubs' pairs found
/// by their arcs (module docs); unsorted, possibly repeated.
pub(super) fn pairs_upto(p: &[DVec3], tris: &[[u32; 3]], items: Vec<Item>, test: &(impl Fn(u32, u32) -> bool + Sync), budget: &Budget) -> Vec<(u32, u32)> {
    let (hub_of, hubs) = hubs(p, tris, &items);
    if hubs.is_empty() {
        return Bvh::new(items).pairs_upto(test, budget);
    }
    let mut rest = Vec::with_capacity(items.len());
    let mut groups: Vec<Vec<Item>> = vec![Vec::new(); hubs.len()];
    for it in items {
        match hub_of[it.id as usize] {
            NONE => rest.push(it),
            g => groups[g as usize].push(it),
        }
    }
    let arcs: Vec<Vec<Item>> = groups.iter().zip(&hubs).map(|(g, &(v, r))| g.iter().map(|it| arc_item(p, tris[it.id as usize], v, r, it)).collect()).collect();
    let trees: Vec<Bvh> = std::iter::once(rest).chain(groups).map(Bvh::new).collect();
    let mut out = trees[0].pairs_upto(test, budget);
    for (i, a) in trees.iter().enumerate() {
        for b in &trees[i + 1..] {
            let (Some(x), Some(y)) = (a.bounds(), b.bounds()) else { continue };
            if x.0.cmpgt(y.1).any() || y.0.cmpgt(x.1).any() {
                continue;
            }
            out.extend(a.pairs_between_upto(b, test, budget));
        }
    }
    for a in arcs {
        out.extend(Bvh::new(a).pairs_upto(test, budget));
    }
    out
}

/// The widened margin `μ` of the triangle `t` at its corner `k` (the hub,
/// longest side there `r`), or None when it is not finite or over
/// [`MU_MAX`] (module docs).
fn margin(p: &[DVec3], t: [u32; 3], k: usize, r: f64) -> Option<f64> {
    let (v, b, c) = (p[t[k] as usize], p[t[(k + 1) % 3] as usize], p[t[(k + 2) % 3] as usize]);
    let (s1, s2, e) = (b - v, c - v, c - b);
    let (l1, l2, le) = (s1.length(), s2.length(), e.length());
    let an = s1.cross(s2).length();
    if !(l1 > 0.0 && l2 > 0.0 && le > 0.0 && an > 0.0 && r.is_finite()) {
        return None;
    }
    let s = (an / (l1 * l2)).min(an / (l1 * le)).min(an / (l2 * le));
    let q = s.min(an / le / r);
    let mu = 1e-3 * r / l1.min(l2) + 1e-9 / (q * q) + 1e-12;
    (mu <= MU_MAX).then_some(mu)
}

/// The hub of every triangle id (an index into the hubs, or [`NONE`]) and
/// the hubs: their vertex and longest side.
fn hubs(p: &[DVec3], tris: &[[u32; 3]], items: &[Item]) -> (Vec<u32>, Vec<(u32, f64)>) {
    let mut count = vec![0u32; p.len()];
    for it in items {
        for &v in &tris[it.id as usize] {
            count[v as usize] += 1;
        }
    }
    let is_hub = |v: u32| count[v as usize] as usize >= HUB_MIN;
    if !count.iter().any(|&c| c as usize >= HUB_MIN) {
        return (Vec::new(), Vec::new());
    }
    // longest side at each candidate
    let mut longest = vec![0.0f64; p.len()];
    for it in items {
        let t = tris[it.id as usize];
        for k in 0..3 {
            if is_hub(t[k]) {
                let v = p[t[k] as usize];
                let l = (p[t[(k + 1) % 3] as usize] - v).length().max((p[t[(k + 2) % 3] as usize] - v).length());
                longest[t[k] as usize] = longest[t[k] as usize].max(l);
            }
        }
    }
    // the triangles with one candidate corner and a margin within bounds
    let mut corner = vec![NONE; tris.len()];
    let mut tagged = vec![0u32; p.len()];
    for it in items {
        let t = tris[it.id as usize];
        let ks: Vec<usize> = (0..3).filter(|&k| is_hub(t[k])).collect();
        if let [k] = ks[..] {
            if margin(p, t, k, longest[t[k] as usize]).is_some() {
                corner[it.id as usize] = t[k];
                tagged[t[k] as usize] += 1;
            }
        }
    }
    let mut hubs: Vec<u32> = (0..p.len() as u32).filter(|&v| tagged[v as usize] as usize >= HUB_MIN).collect();
    hubs.sort_unstable_by_key(|&v| (std::cmp::Reverse(tagged[v as usize]), v));
    hubs.truncate(HUB_MAX);
    let mut index = vec![NONE; p.len()];
    for (g, &v) in hubs.iter().enumerate() {
        index[v as usize] = g as u32;
    }
    let hub_of = corner.iter().map(|&v| if v == NONE { NONE } else { index[v as usize] }).collect();
    (hub_of, hubs.iter().map(|&v| (v, longest[v as usize])).collect())
}

/// The box of the triangle's arc of directions at the hub `v` (its
/// corner there; longest side at the hub `r`), widened by its margin and by
/// the arc's sagitta (the arc between two unit vectors lies within that
/// of their chord).
fn arc_item(p: &[DVec3], t: [u32; 3], v: u32, r: f64, it: &Item) -> Item {
    let k = t.iter().position(|&x| x == v).expect("a hub's triangle holds it");
    let mu = margin(p, t, k, r).expect("a hub's triangle has a margin");
    let o = p[v as usize];
    let (u, w) = ((p[t[(k + 1) % 3] as usize] - o).normalize(), (p[t[(k + 2) % 3] as usize] - o).normalize());
    let sag = 1.0 - (0.5 * (1.0 + u.dot(w))).max(0.0).sqrt();
    let pad = DVec3::splat(sag + mu + 1e-12);
    Item { lo: u.min(w) - pad, hi: u.max(w) + pad, id: it.id, focus: it.focus }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle, focused.
    fn all_items(p: &[DVec3], tris: &[[u32; 3]]) -> Vec<Item> {
        tris.iter().enumerate().map(|(i, &t)| Item::of(p, t, i as u32, true)).collect()
    }

    /// The plain hierarchy's pairs (no hubs).
    fn plain(p: &[DVec3], tris: &[[u32; 3]], coplanar: bool) -> Vec<(u32, u32)> {
        let items = all_items(&p, &tris);
        let test = |i: u32, j: u32| {
            let (a, b) = (tris[i as usize], tris[j as usize]);
            a.iter().filter(|v| b.contains(v)).count() < 2 && super::super::triangles_meet(a, a.map(|v| p[v as usize]), b, b.map(|v| p[v as usize]), coplanar)
        };
        let mut out = Bvh::new(items).pairs(&test);
        out.sort_unstable();
        out.dedup();
        out
    }

    /// A closed cone over a ring of `n` points around an apex (the last
    /// point), each ring point moved by `bump(k)`, with its base fanned
    /// around a second apex below.
    fn cone(n: usize, bump: impl Fn(usize) -> DVec3, apex: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut p: Vec<DVec3> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                DVec3::new(a.cos(), a.sin(), 0.0) + bump(k)
            })
            .collect();
        p.push(apex);
        p.push(DVec3::new(0.0, 0.0, -0.5));
        let (top, bottom) = (n as u32, n as u32 + 1);
        let mut tris = Vec::new();
        for k in 0..n as u32 {
            let k1 = (k + 1) % n as u32;
            tris.push([k, k1, top]);
            tris.push([k1, k, bottom]);
        }
        (p, tris)
    }

    /// Hubs change no answer: cones (convex, wavy, folded through
    /// themselves, nearly flat), fans of nearly coplanar triangles, needles,
    /// tiny sides and a hub crossed by other triangles, in both modes.
    #[test]
    fn hubs_equal_the_plain_scan() {
        let mut rng = crate::test_rng::Xorshift::new(0x51_7cc1_b727_220a);
        let mut cases: Vec<(Vec<DVec3>, Vec<[u32; 3]>)> = Vec::new();
        for n in [64, 65, 200, 1000] {
            cases.push(cone(n, |_| DVec3::ZERO, DVec3::Z));
            // nearly flat: apex 1e-9 above the ring's plane
            cases.push(cone(n, |_| DVec3::ZERO, DVec3::Z * 1e-9));
            // exactly flat fan around the centre (both sides coplanar)
            cases.push(cone(n, |_| DVec3::ZERO, DVec3::ZERO));
            // wavy ring, folded every 7th point through the neighbours
            cases.push(cone(n, |k| DVec3::new(0.0, 0.0, 0.3 * ((k as f64) * 0.7).sin()) + if k % 7 == 3 { DVec3::new(-0.9, 0.4, 0.0) } else { DVec3::ZERO }, DVec3::Z * 0.5));
            // ring points within 1e-11 of the apex's plane, off by rounding
            cases.push(cone(n, |k| DVec3::Z * 1e-11 * ((k * 7919 % 13) as f64 - 6.0), DVec3::ZERO));
            // a flat fan folded onto itself 5e-11 above its plane: every
            // 7th spoke turned back into the wedge two before it, a contact
            // of the coplanar mode's tolerance, not of the exact wedges
            let step = std::f64::consts::TAU / n as f64;
            for lift in [5e-11, 2e-10] {
                cases.push(cone(
                    n,
                    |k| {
                        if k % 7 != 3 {
                            return DVec3::ZERO;
                        }
                        let (a, b) = (step * k as f64, step * (k as f64 - 2.5));
                        DVec3::new(b.cos() - a.cos(), b.sin() - a.sin(), lift)
                    },
                    DVec3::ZERO,
                ));
            }
        }
        // random jitter, with some needles (repeated ring points nearly) and tiny sides
        for n in [100, 400] {
            let jit: Vec<DVec3> = (0..n).map(|_| DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5)).collect();
            for amp in [1e-12, 1e-6, 1e-2, 0.5] {
                cases.push(cone(n, |k| jit[k] * amp * if k % 11 == 0 { 1e-6 } else { 1.0 }, DVec3::new(0.1, 0.0, 0.2)));
            }
            cases.push(cone(n, |k| if k % 5 == 0 { DVec3::new(-0.999, 0.0, 0.0) } else { DVec3::ZERO }, DVec3::Z * 1e-3));
        }
        // a cone pierced by triangles through its apex region
        let (mut p, mut tris) = cone(300, |_| DVec3::ZERO, DVec3::Z);
        for k in 0..40 {
            let a = k as f64 * 0.15;
            let b = p.len() as u32;
            p.push(DVec3::new(a.cos() * 0.3, a.sin() * 0.3, 1.2));
            p.push(DVec3::new(-a.cos() * 0.3, -a.sin() * 0.3, 1.2));
            p.push(DVec3::new(0.01 * a, 0.0, 0.2));
            tris.push([b, b + 1, b + 2]);
        }
        cases.push((p, tris));
        let mut hubbed = 0;
        for (c, (p, tris)) in cases.iter().enumerate() {
            let items = all_items(p, tris);
            hubbed += !hubs(p, tris, &items).1.is_empty() as usize;
            for coplanar in [false, true] {
                let got = super::super::crossing_pairs(p, tris, None, coplanar);
                assert_eq!(got, plain(p, tris, coplanar), "case {c}, coplanar {coplanar}");
            }
        }
        assert!(hubbed >= cases.len() - 2, "{hubbed} of {} cases had hubs", cases.len());
    }

    /// The arcs leave a fan's far pairs out: a cone of 4,000 triangles is
    /// tested in about as many pairs, not 8 M. (Its base is left out: two
    /// fans facing each other are paired by their triangles' boxes, all of
    /// which meet at the ring's centre.)
    #[test]
    fn a_cone_tests_its_neighbours_only() {
        let (p, mut tris) = cone(4000, |_| DVec3::ZERO, DVec3::Z);
        tris.retain(|t| !t.contains(&4001));
        let tested = std::sync::atomic::AtomicUsize::new(0);
        let test = |_: u32, _: u32| {
            tested.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            false
        };
        let items = all_items(&p, &tris);
        pairs_upto(&p, &tris, items, &test, &Budget::new(usize::MAX));
        let n = tested.into_inner();
        assert!(n < 40 * tris.len(), "{n} pairs tested");
    }
}

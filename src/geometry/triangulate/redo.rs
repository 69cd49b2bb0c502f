//! The retry pass of [`triangulate`](super::triangulate): the faces whose
//! first choice collided (a diagonal that is a mesh edge, or one two faces
//! chose) are triangulated again, in face order, each with the mesh edges,
//! the diagonals the other faces kept and the diagonals of the colliding
//! faces before it forbidden.
//!
//! **Parallel and still in face order.** A face's choice depends on the
//! faces before it only through the diagonals they accept, and a diagonal
//! joins two of a face's own vertices, so two colliding faces interact only
//! when they share two vertices that are not consecutive in either (sides
//! are mesh edges, never accepted diagonals). The colliding faces are
//! grouped into the components of that relation (union-find over those
//! vertex pairs; a face
//! of more than [`PAIR_LIMIT`] corners is joined to every colliding face
//! sharing any vertex with it instead, to keep the pairs linear), the
//! components are redone in parallel, each in face order, and the added
//! points are numbered in face order afterwards: the result is the
//! sequential pass's, at any thread count.

use super::*;
use std::collections::HashMap;
use crate::union_find::{root, union};
use rustc_hash::FxHashSet;

/// Faces up to this many corners enter the grouping by their vertex pairs.
const PAIR_LIMIT: usize = 24;
/// Colliding faces per parallel task (whole components).
const TASK: usize = 1024;
/// Marks an added point in a redone face's triangles (vertex ids are below 2^31).
const ADDED: u32 = 1 << 31;

// -------------------------------------------------------------- segment tests

fn on_segment(a: DVec2, b: DVec2, c: DVec2) -> bool {
    c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
}

/// Segments ab and cd share a point (touching included).
fn segments_meet(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let (d1, d2, d3, d4) = (cross2(a, b, c), cross2(a, b, d), cross2(c, d, a), cross2(c, d, b));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    (d1 == 0.0 && on_segment(a, b, c)) || (d2 == 0.0 && on_segment(a, b, d)) || (d3 == 0.0 && on_segment(c, d, a)) || (d4 == 0.0 && on_segment(c, d, b))
}

/// Whether the segment from corner i to corner j runs inside the polygon
/// (O'Rourke's in-cone test at both ends, no edge met), O(n).
fn is_inner_diagonal(p: &[DVec2], i: usize, j: usize) -> bool {
    let n = p.len();
    let in_cone = |a: usize, b: usize| {
        let (a0, a1) = (p[(a + n - 1) % n], p[(a + 1) % n]);
        let (pa, pb) = (p[a], p[b]);
        if cross2(pa, a1, a0) >= 0.0 {
            cross2(pa, pb, a0) > 0.0 && cross2(pb, pa, a1) > 0.0
        } else {
            !(cross2(pa, pb, a1) >= 0.0 && cross2(pb, pa, a0) >= 0.0)
        }
    };
    if !in_cone(i, j) || !in_cone(j, i) {
        return false;
    }
    (0..n).all(|k| {
        let k1 = (k + 1) % n;
        k == i || k == j || k1 == i || k1 == j || !segments_meet(p[i], p[j], p[k], p[k1])
    })
}

/// A triangulation by diagonals alone that uses none that `forbidden`
/// refuses, if one exists: dynamic programme over the sub-polygons i..j,
/// O(n³). Non-convex faces only use diagonals inside the polygon.
pub(super) fn exact(p: &[DVec2], shape: Shape, forbidden: &dyn Fn(usize, usize) -> bool, out: &mut Vec<[u32; 3]>) -> bool {
    let n = p.len();
    let geometric = shape == Shape::NonConvex;
    let id = |i: usize, j: usize| i * n + j;
    let mut ok = vec![false; n * n];
    for i in 0..n {
        for j in i + 1..n {
            ok[id(i, j)] = j == i + 1 || (i == 0 && j == n - 1) || (!forbidden(i, j) && (!geometric || is_inner_diagonal(p, i, j)));
        }
    }
    // choice[i][j]: the apex k of the triangle on i..j, or usize::MAX if none
    const NONE: usize = usize::MAX;
    let mut choice = vec![NONE; n * n];
    for len in 2..n {
        for i in 0..n - len {
            let j = i + len;
            if !ok[id(i, j)] {
                continue;
            }
            for k in i + 1..j {
                let left = k == i + 1 || choice[id(i, k)] != NONE;
                let right = j == k + 1 || choice[id(k, j)] != NONE;
                if left && right && ok[id(i, k)] && ok[id(k, j)] && (!geometric || cross2(p[i], p[k], p[j]) > 0.0) {
                    choice[id(i, j)] = k;
                    break;
                }
            }
        }
    }
    if choice[id(0, n - 1)] == NONE {
        return false;
    }
    out.clear();
    let mut stack = vec![(0, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j <= i + 1 {
            continue;
        }
        let k = choice[id(i, j)];
        out.push([i as u32, k as u32, j as u32]);
        stack.push((i, k));
        stack.push((k, j));
    }
    true
}

/// Re-triangulates a face whose first choice collided. Local indices; an
/// index n + k is the added point `added[k]`.
/// Largest face a retry gives to earcut (about a second in its quadratic
/// cases, on the rare faces that get here).
const EARCUT_RETRY_LIMIT: usize = 1 << 15;

pub(super) fn retry(
    cyc: &[u32],
    pos: &[DVec3],
    p: &[DVec2],
    shape: Shape,
    first: &[[u32; 3]],
    forbidden: &dyn Fn(usize, usize) -> bool,
    out: &mut Vec<[u32; 3]>,
    added: &mut Vec<DVec3>,
) {
    let n = cyc.len();
    added.clear();
    if shape == Shape::Convex {
        // other fans first, O(n) each
        for from in 1..n.min(8) {
            if (2..n - 1).all(|i| !forbidden(from, (from + i) % n)) {
                fan(n, from, out);
                return;
            }
        }
    }
    if n <= EXACT_LIMIT && shape != Shape::Degenerate && exact(p, shape, forbidden, out) {
        return;
    }
    // one point: the corners' mean, if the face is star-shaped from it, or
    // if it is small: a small face no diagonals fit is mostly far from planar
    // (Doo-Sabin faces around opened self-loops), where its projection
    // misleads and a fan around its centroid is the faithful surface
    let c2 = p.iter().copied().sum::<DVec2>() / n as f64;
    if shape != Shape::NonConvex || n <= EXACT_LIMIT || (0..n).all(|i| cross2(p[i], p[(i + 1) % n], c2) > 0.0) {
        added.push(cyc.iter().map(|&v| pos[v as usize]).sum::<DVec3>() / n as f64);
        out.clear();
        out.extend((0..n).map(|i| [i as u32, ((i + 1) % n) as u32, n as u32]));
        return;
    }
    // a large face's first choice came from the monotone partition, which
    // a face and its reverse (both sides of a sheet) make along the same
    // direction: the sweep along x, then earcut (bounded: it can be
    // quadratic), may choose other diagonals; failing that, the one with
    // the fewest forbidden diagonals is split below
    let mut fewest: Option<(usize, Vec<[u32; 3]>)> = None;
    if n > MONOTONE_MIN && shape == Shape::NonConvex {
        let taken = |t: &[[u32; 3]]| {
            t.iter()
                .flat_map(|t| (0..3).map(move |k| (t[k] as usize, t[(k + 1) % 3] as usize)))
                .filter(|&(i, j)| i < j && j != i + 1 && !(i == 0 && j == n - 1) && forbidden(i, j))
                .count()
        };
        let q: Vec<DVec2> = p.iter().map(|v| DVec2::new(-v.y, v.x)).collect();
        let mut candidates = Vec::new();
        if super::monotone::triangulate(&q, out) && is_disk_triangulation(n, out) && super::monotone::covers(&q, out) {
            candidates.push(out.clone());
        }
        if n <= EARCUT_RETRY_LIMIT {
            super::earcut_into(&mut earcut::Earcut::new(), &mut Vec::new(), p, out);
            if is_disk_triangulation(n, out) && super::monotone::covers(p, out) {
                candidates.push(out.clone());
            }
        }
        let mut least = taken(first);
        for c in candidates {
            let k = taken(&c);
            if k == 0 {
                out.clone_from(&c);
                return;
            }
            if k < least {
                least = k;
                fewest = Some((k, c));
            }
        }
    }
    let first = fewest.as_ref().map_or(first, |(_, c)| &c[..]);
    // split each forbidden diagonal of the first choice where it meets the
    // two triangles beside it, at a point a little off its middle
    out.clear();
    out.extend_from_slice(first);
    let mut by_edge: HashMap<(u32, u32), usize> = HashMap::new();
    for (t, tri) in out.iter().enumerate() {
        for k in 0..3 {
            by_edge.insert((tri[k], tri[(k + 1) % 3]), t);
        }
    }
    let n32 = n as u32;
    let diags: Vec<(u32, u32)> = first
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .filter(|&(i, j)| i < j && j != (i + 1) % n32 && i != (j + 1) % n32 && forbidden(i as usize, j as usize))
        .collect();
    let pt = |added: &[DVec3], k: u32| if k < n32 { pos[cyc[k as usize] as usize] } else { added[(k - n32) as usize] };
    for (i, j) in diags {
        let (Some(&t1), Some(&t2)) = (by_edge.get(&(i, j)), by_edge.get(&(j, i))) else { continue };
        let apex = |t: [u32; 3], a: u32, b: u32| t.into_iter().find(|&v| v != a && v != b).unwrap();
        let (x, y) = (apex(out[t1], i, j), apex(out[t2], j, i));
        // the middle keeps the four triangles positive (halves of two
        // positive ones); it lies on the coincident mesh edge, but nothing
        // better is known without the face's kernel
        let _ = (x, y);
        let m = n32 + added.len() as u32;
        added.push((pt(added, i) + pt(added, j)) / 2.0);
        out[t1] = [i, m, x];
        out[t2] = [j, m, y];
        let (t3, t4) = (out.len(), out.len() + 1);
        out.push([m, j, x]);
        out.push([m, i, y]);
        for (t, tri) in [(t1, out[t1]), (t2, out[t2]), (t3, out[t3]), (t4, out[t4])] {
            for k in 0..3 {
                by_edge.insert((tri[k], tri[(k + 1) % 3]), t);
            }
        }
    }
}

/// One task's redone faces: triangles (vertex ids, or `ADDED | k` for the
/// face's k-th added point) and added points, flat, with per-face ranges
/// `(index into bad, end of its triangles, end of its points)`.
#[derive(Default)]
struct TaskOut {
    tris: Vec<[u32; 3]>,
    added: Vec<DVec3>,
    faces: Vec<(u32, u32, u32)>,
}

/// Redoes the colliding faces `bad` (sorted face ids); `diags` are every
/// face's first-choice diagonals as (pair key, face), sorted. Returns the
/// new triangles of each face, in face order, and the added points, whose
/// ids start at `base`.
///
/// `grouped = false` puts every face in one component: the sequential pass,
/// which the tests compare with.
pub(super) fn redo(m: &Mesh, pos: &[DVec3], split: &[u32], bad: &[u32], diags: &[(u64, u32)], base: u32, grouped: bool) -> (Vec<(u32, Vec<[u32; 3]>)>, Vec<DVec3>) {
    let nb = bad.len();
    // the colliding faces' cycles
    let mut cyc_off = Vec::with_capacity(nb + 1);
    let mut cycles: Vec<u32> = Vec::new();
    let mut cyc = Vec::new();
    cyc_off.push(0u32);
    for &f in bad {
        face_cycle(m, FaceId(f), split, &mut cyc);
        cycles.extend_from_slice(&cyc);
        cyc_off.push(cycles.len() as u32);
    }
    let cycle = |i: usize| &cycles[cyc_off[i] as usize..cyc_off[i + 1] as usize];

    // the diagonals that stay (other faces'), among the colliding faces' vertices
    let mut in_bad = vec![false; pos.len()];
    for &v in &cycles {
        in_bad[v as usize] = true;
    }
    let taken: FxHashSet<u64> = diags
        .par_iter()
        .filter(|&&(k, f)| k != BENT_KEY && in_bad[(k >> 32) as usize] && in_bad[(k & 0xffff_ffff) as usize] && bad.binary_search(&f).is_err())
        .map(|d| d.0)
        .collect();
    drop(in_bad);
    if crate::cancel::requested() {
        return (Vec::new(), Vec::new());
    }

    // components: faces sharing a vertex pair that can be a diagonal of
    // both (not a side: sides are mesh edges, never accepted), or any vertex
    // with a large face
    let mut parent: Vec<u32> = (0..nb as u32).map(|i| if grouped { i } else { 0 }).collect();
    let mut keys: Vec<(u64, u32)> = Vec::new();
    let mut any_large = false;
    for i in (0..nb).filter(|_| grouped) {
        let c = cycle(i);
        let n = c.len();
        if n > PAIR_LIMIT {
            any_large = true;
            continue;
        }
        for a in 0..n {
            for b in a + 2..n - usize::from(a == 0) {
                keys.push((pair(c[a], c[b]), i as u32));
            }
        }
    }
    keys.par_sort_unstable();
    for w in keys.windows(2) {
        if w[0].0 == w[1].0 {
            union(&mut parent, w[0].1, w[1].1);
        }
    }
    drop(keys);
    if any_large {
        // the large face at each of its vertices, then every face meeting one
        let mut large_at = vec![u32::MAX; pos.len()];
        for i in (0..nb).filter(|&i| cycle(i).len() > PAIR_LIMIT) {
            for &v in cycle(i) {
                match large_at[v as usize] {
                    u32::MAX => large_at[v as usize] = i as u32,
                    j => union(&mut parent, i as u32, j),
                }
            }
        }
        for i in 0..nb {
            for &v in cycle(i) {
                if large_at[v as usize] != u32::MAX {
                    union(&mut parent, i as u32, large_at[v as usize]);
                }
            }
        }
    }
    // faces grouped by component, each component in face order
    let mut order: Vec<(u32, u32)> = (0..nb as u32).map(|i| (root(&mut parent, i), i)).collect();
    order.par_sort_unstable();
    // tasks of whole components
    let mut tasks: Vec<std::ops::Range<usize>> = Vec::new();
    let mut t0 = 0;
    for k in 1..=nb {
        if k == nb || (k - t0 >= TASK && order[k].0 != order[k - 1].0) {
            tasks.push(t0..k);
            t0 = k;
        }
    }

    let outs: Vec<TaskOut> = tasks
        .par_iter()
        .map(|r| {
            let mut o = TaskOut::default();
            if crate::cancel::requested() {
                return o;
            }
            let mut s = Scratch::default();
            let (mut out, mut added) = (Vec::new(), Vec::new());
            let mut local: FxHashSet<u64> = FxHashSet::default();
            for (k, &(comp, i)) in order[r.clone()].iter().enumerate() {
                if k > 0 && order[r.start + k - 1].0 != comp {
                    local.clear();
                }
                s.cyc.clear();
                s.cyc.extend_from_slice(cycle(i as usize));
                redo_face(m, pos, &mut s, &taken, &local, &mut out, &mut added);
                let cyc = &s.cyc;
                let n = cyc.len() as u32;
                for t in &out {
                    for k in 0..3 {
                        let (a, b) = (t[k], t[(k + 1) % 3]);
                        if a < b && b < n && b != a + 1 && !(a == 0 && b == n - 1) {
                            local.insert(pair(cyc[a as usize], cyc[b as usize]));
                        }
                    }
                }
                o.tris.extend(out.iter().map(|t| t.map(|k| if k < n { cyc[k as usize] } else { ADDED | (k - n) })));
                o.added.extend_from_slice(&added);
                o.faces.push((i, o.tris.len() as u32, o.added.len() as u32));
            }
            o
        })
        .collect();
    if crate::cancel::requested() {
        return (Vec::new(), Vec::new());
    }

    // in face order: the added points numbered, the triangles made global
    let mut loc = vec![(0u32, 0u32); nb]; // (task, position in its faces)
    for (t, o) in outs.iter().enumerate() {
        for (j, &(i, _, _)) in o.faces.iter().enumerate() {
            loc[i as usize] = (t as u32, j as u32);
        }
    }
    let mut redone = Vec::with_capacity(nb);
    let mut points = Vec::new();
    for (i, &(t, j)) in loc.iter().enumerate() {
        let o = &outs[t as usize];
        let (ts, ps) = if j == 0 { (0, 0) } else { (o.faces[j as usize - 1].1, o.faces[j as usize - 1].2) };
        let (_, te, pe) = o.faces[j as usize];
        let b = base + points.len() as u32;
        let global: Vec<[u32; 3]> = o.tris[ts as usize..te as usize].iter().map(|t| t.map(|v| if v & ADDED != 0 { b + (v & !ADDED) } else { v })).collect();
        points.extend_from_slice(&o.added[ps as usize..pe as usize]);
        redone.push((bad[i], global));
    }
    (redone, points)
}

/// One colliding face (its cycle in `s.cyc`): local triangles into `out`
/// (index n + k is the added point `added[k]`).
fn redo_face(m: &Mesh, pos: &[DVec3], s: &mut Scratch, taken: &FxHashSet<u64>, local: &FxHashSet<u64>, out: &mut Vec<[u32; 3]>, added: &mut Vec<DVec3>) {
    let shape = project(&s.cyc, pos, &mut s.p);
    first_choice(s, shape);
    let cyc = &s.cyc;
    let n = cyc.len();
    let forbidden = |i: usize, j: usize| {
        let (a, b) = (cyc[i], cyc[j]);
        let k = pair(a, b);
        local.contains(&k) || taken.contains(&k) || is_edge(m, a, b)
    };
    // the first choice stands if what it collided with was given up
    let free = s.local.iter().all(|t| {
        (0..3).all(|k| {
            let (i, j) = (t[k] as usize, t[(k + 1) % 3] as usize);
            j == (i + 1) % n || i == (j + 1) % n || !forbidden(i, j)
        })
    });
    if is_bent(cyc, pos) {
        added.clear();
        added.push(cyc.iter().map(|&v| pos[v as usize]).sum::<DVec3>() / n as f64);
        out.clear();
        out.extend((0..n).map(|i| [i as u32, ((i + 1) % n) as u32, n as u32]));
    } else if free {
        out.clone_from(&s.local);
        added.clear();
    } else {
        retry(cyc, pos, &s.p, shape, &s.local, &forbidden, out, added);
    }
}

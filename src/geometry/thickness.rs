//! Wall thickness of a triangle surface, for printability checks: from the
//! centroid of every triangle a ray goes along the inward normal (triangles
//! are counter-clockwise seen from outside), and the wall there is the
//! distance to the first other triangle it hits. Hits closer than 1e-9 of
//! the triangle's longest edge are contacts, not walls (a coincident sheet
//! is an intersection, which [`super::crossing`] reports), and are skipped.
//!
//! The rays are answered by a bounding volume hierarchy over the triangles
//! ([`Bvh`]): median splits on the longest axis of the centroids' box, built
//! in parallel into a layout fixed by the triangle count, so the build is
//! O(T log T) and a ray costs about O(log T) on a surface of evenly sized
//! triangles, and the whole check runs in parallel over the triangles.

use crate::error::Result;
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// Triangles per leaf.
const LEAF: usize = 4;
/// Subtrees larger than this are built on two threads.
const PAR_BUILD: usize = 1 << 13;
/// Barycentric slack of the ray-triangle test: a ray through a shared edge
/// or corner hits one of the triangles there, never slips between them.
const BARY_EPS: f64 = 1e-9;

#[derive(Clone, Copy, Default)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf (`n > 0`): the triangles `order[a..a + n]`. Inner (`n == 0`):
    /// the right child; the left child is the next node.
    a: u32,
    n: u32,
}

/// A bounding volume hierarchy over a triangle list, for nearest-hit ray
/// queries.
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

/// Nodes of the tree over `n` triangles (median splits stop at [`LEAF`]).
fn n_nodes(n: usize) -> usize {
    if n <= LEAF { 1 } else { 1 + n_nodes(n / 2) + n_nodes(n - n / 2) }
}

fn tri_box(p: &[DVec3], t: [u32; 3]) -> (DVec3, DVec3) {
    let q = t.map(|v| p[v as usize]);
    (q[0].min(q[1]).min(q[2]), q[0].max(q[1]).max(q[2]))
}

fn build(nodes: &mut [Node], base: usize, order: &mut [u32], start: usize, boxes: &[(DVec3, DVec3)], cent: &[DVec3]) {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &t in order.iter() {
        lo = lo.min(boxes[t as usize].0);
        hi = hi.max(boxes[t as usize].1);
    }
    let n = order.len();
    if n <= LEAF {
        nodes[0] = Node { lo, hi, a: start as u32, n: n as u32 };
        return;
    }
    let (mut clo, mut chi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for &t in order.iter() {
        clo = clo.min(cent[t as usize]);
        chi = chi.max(cent[t as usize]);
    }
    let ext = chi - clo;
    let ax = if ext.x >= ext.y && ext.x >= ext.z { 0 } else if ext.y >= ext.z { 1 } else { 2 };
    let mid = n / 2;
    order.select_nth_unstable_by(mid, |&x, &y| cent[x as usize][ax].total_cmp(&cent[y as usize][ax]));
    let nl = n_nodes(mid);
    let (me, rest) = nodes.split_at_mut(1);
    let (left, right) = rest.split_at_mut(nl);
    me[0] = Node { lo, hi, a: (base + 1 + nl) as u32, n: 0 };
    let (ol, or) = order.split_at_mut(mid);
    if n > PAR_BUILD {
        rayon::join(
            || build(left, base + 1, ol, start, boxes, cent),
            || build(right, base + 1 + nl, or, start + mid, boxes, cent),
        );
    } else {
        build(left, base + 1, ol, start, boxes, cent);
        build(right, base + 1 + nl, or, start + mid, boxes, cent);
    }
}

/// Entry distance of the ray `o + t d`, `t` in `[0, tmax]`, into the box,
/// or None. Axes the ray runs parallel to are tested directly (no 0 × ∞).
fn ray_box(o: DVec3, d: DVec3, inv: DVec3, lo: DVec3, hi: DVec3, tmax: f64) -> Option<f64> {
    let (mut t0, mut t1) = (0.0f64, tmax);
    for k in 0..3 {
        if d[k] == 0.0 {
            if o[k] < lo[k] || o[k] > hi[k] {
                return None;
            }
            continue;
        }
        let (mut a, mut b) = ((lo[k] - o[k]) * inv[k], (hi[k] - o[k]) * inv[k]);
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        t0 = t0.max(a);
        t1 = t1.min(b);
        if t0 > t1 {
            return None;
        }
    }
    Some(t0)
}

/// Distance along the unit ray `o + t d` to the triangle `a b c`
/// (Möller–Trumbore), or None when it misses or runs parallel to it.
fn ray_triangle(o: DVec3, d: DVec3, a: DVec3, b: DVec3, c: DVec3) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let pv = d.cross(e2);
    let det = e1.dot(pv);
    // parallel, relative to the triangle's size (d is a unit vector)
    if det.abs() <= 1e-14 * e1.length() * e2.length() {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - a;
    let u = s.dot(pv) * inv;
    if !(-BARY_EPS..=1.0 + BARY_EPS).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if v < -BARY_EPS || u + v > 1.0 + BARY_EPS {
        return None;
    }
    Some(e2.dot(q) * inv)
}

impl Bvh {
    /// The hierarchy over `tris` (indices into `p`).
    pub fn new(p: &[DVec3], tris: &[[u32; 3]]) -> Bvh {
        let boxes: Vec<(DVec3, DVec3)> = tris.par_iter().map(|&t| tri_box(p, t)).collect();
        let cent: Vec<DVec3> = boxes.par_iter().map(|b| (b.0 + b.1) * 0.5).collect();
        let mut order: Vec<u32> = (0..tris.len() as u32).collect();
        if tris.is_empty() {
            return Bvh { nodes: Vec::new(), order };
        }
        let mut nodes = vec![Node::default(); n_nodes(tris.len())];
        build(&mut nodes, 0, &mut order, 0, &boxes, &cent);
        Bvh { nodes, order }
    }

    /// The nearest triangle other than `skip` that the unit ray `o + t d`
    /// hits with `t > tmin`: `(t, triangle)`, or None.
    pub fn first_hit(&self, p: &[DVec3], tris: &[[u32; 3]], o: DVec3, d: DVec3, skip: u32, tmin: f64) -> Option<(f64, u32)> {
        if self.nodes.is_empty() {
            return None;
        }
        let inv = d.recip();
        let mut best: Option<(f64, u32)> = None;
        let mut tmax = f64::INFINITY;
        let root = self.nodes[0];
        let Some(t0) = ray_box(o, d, inv, root.lo, root.hi, tmax) else { return None };
        // (node, entry distance); depth <= log2(T) + 1 < 40 for any u32
        // count, one pending sibling per level
        let mut stack = [(0u32, 0.0f64); 64];
        stack[0] = (0, t0);
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let (k, entry) = stack[top];
            if entry > tmax {
                continue; // a nearer hit was found since it was pushed
            }
            let node = self.nodes[k as usize];
            if node.n > 0 {
                for &t in &self.order[node.a as usize..(node.a + node.n) as usize] {
                    if t == skip {
                        continue;
                    }
                    let q = tris[t as usize].map(|v| p[v as usize]);
                    if let Some(h) = ray_triangle(o, d, q[0], q[1], q[2]) {
                        if h > tmin && h < tmax {
                            tmax = h;
                            best = Some((h, t));
                        }
                    }
                }
                continue;
            }
            // the nearer child is pushed last, so visited first
            let (l, r) = (k + 1, node.a);
            let (nl, nr) = (self.nodes[l as usize], self.nodes[r as usize]);
            let dl = ray_box(o, d, inv, nl.lo, nl.hi, tmax);
            let dr = ray_box(o, d, inv, nr.lo, nr.hi, tmax);
            let mut push = |x: u32, e: f64| {
                stack[top] = (x, e);
                top += 1;
            };
            match (dl, dr) {
                (Some(a), Some(b)) if a <= b => {
                    push(r, b);
                    push(l, a);
                }
                (Some(a), Some(b)) => {
                    push(l, a);
                    push(r, b);
                }
                (Some(a), None) => push(l, a),
                (None, Some(b)) => push(r, b),
                (None, None) => {}
            }
        }
        best
    }
}

/// Wall thickness at every triangle of `tris` (indices into `p`): the
/// distance from its centroid along its inward normal to the first other
/// triangle hit (see the module doc). `+inf` where the ray leaves the
/// surface (an open or inside-out part), NaN for a triangle of zero area.
/// Interruptible ([`crate::cancel`]).
pub fn triangle_thickness(p: &[DVec3], tris: &[[u32; 3]]) -> Result<Vec<f64>> {
    let bvh = Bvh::new(p, tris);
    crate::cancel::check()?;
    let mut out = vec![f64::NAN; tris.len()];
    out.par_chunks_mut(4096).enumerate().for_each(|(c, chunk)| {
        if crate::cancel::requested() {
            return;
        }
        for (k, slot) in chunk.iter_mut().enumerate() {
            let i = c * 4096 + k;
            let [a, b, cc] = tris[i].map(|v| p[v as usize]);
            let n = (b - a).cross(cc - a);
            let len = n.length();
            if !(len > 0.0) {
                continue;
            }
            let edge = (b - a).length().max((cc - b).length()).max((a - cc).length());
            let o = (a + b + cc) / 3.0;
            *slot = bvh.first_hit(p, tris, o, -n / len, i as u32, 1e-9 * edge).map_or(f64::INFINITY, |h| h.0);
        }
    });
    crate::cancel::check()?;
    Ok(out)
}

/// The smallest value of `tri` per face (`tri_face[k]` is the face of
/// triangle `k`), NaN for faces with no measured triangle.
pub fn per_face(n_faces: usize, tri: &[f64], tri_face: &[u32]) -> Vec<f64> {
    let mut out = vec![f64::NAN; n_faces];
    for (&t, &f) in tri.iter().zip(tri_face) {
        let s = &mut out[f as usize];
        // NaN (not measured yet) gives way to any measurement
        if !(*s <= t) && !t.is_nan() {
            *s = t;
        }
    }
    out
}

/// Bytes [`Mesh::wall_thickness`] allocates per triangle (triangulation, boxes,
/// centroids, order, nodes, results), for the memory budget.
const BYTES_PER_TRIANGLE: u64 = 12 + 4 + 48 + 24 + 4 + 40 + 8 + 8;

/// A mesh's triangulation with the wall thickness of every triangle.
pub struct TriangleThickness {
    /// The vertices, then the points the triangulation adds.
    pub points: Vec<DVec3>,
    pub tris: Vec<[u32; 3]>,
    /// Source face of every triangle.
    pub tri_face: Vec<u32>,
    /// [`triangle_thickness`] of every triangle.
    pub thickness: Vec<f64>,
}

impl Mesh {
    /// Wall thickness per face: the smallest [`triangle_thickness`] over
    /// the face's triangles in [`Mesh::triangulate`]; NaN for hole faces and
    /// faces without a triangle of positive area, `+inf` where every ray
    /// leaves the surface. O(T log T), parallel, interruptible.
    pub fn wall_thickness(&self) -> Result<Vec<f64>> {
        let t = self.triangle_wall_thickness()?;
        Ok(per_face(self.n_faces(), &t.thickness, &t.tri_face))
    }

    /// [`triangle_thickness`] of the mesh's triangulation, with the
    /// triangulation (checked against the memory budget first).
    pub fn triangle_wall_thickness(&self) -> Result<TriangleThickness> {
        let n_tri: u64 = self.faces().map(|f| (self.face_degree(f) as u64).saturating_sub(2)).sum();
        crate::budget::check(
            "wall_thickness",
            &format!("a mesh of about {n_tri} triangles"),
            n_tri.saturating_mul(BYTES_PER_TRIANGLE),
        )?;
        let t = self.triangulate();
        crate::cancel::check()?;
        let mut points = self.positions().to_vec();
        points.extend_from_slice(&t.points);
        let thickness = triangle_thickness(&points, &t.tris)?;
        Ok(TriangleThickness { points, tris: t.tris, tri_face: t.tri_face, thickness })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::BuildOptions;

    /// An axis-aligned box `[0, x] × [0, y] × [0, z]` as six quads, outward.
    fn block(x: f64, y: f64, z: f64) -> Mesh {
        let p: Vec<DVec3> = (0..8).map(|i| DVec3::new(x * (i & 1) as f64, y * ((i >> 1) & 1) as f64, z * ((i >> 2) & 1) as f64)).collect();
        let faces: [i64; 24] = [0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5];
        Mesh::from_polygons(p, &[4; 6], &faces, BuildOptions::default()).expect("a box")
    }

    #[test]
    fn slab_thickness_is_exact() {
        for d in [1.0, 0.01, 1e-4, 3.7] {
            let m = block(10.0, 7.0, d);
            assert!(m.signed_volume() > 0.0);
            let w = m.wall_thickness().unwrap();
            let c = m.face_centroids();
            for (f, &t) in w.iter().enumerate() {
                // the two big faces see the slab's thickness, the sides its width or depth
                let want = if c[f].z == 0.0 || c[f].z == d { d } else if c[f].x == 0.0 || c[f].x == 10.0 { 10.0 } else { 7.0 };
                assert!((t - want).abs() <= 1e-9, "face {f}: {t} vs {want} (slab {d})");
            }
        }
    }

    #[test]
    fn inside_out_or_open_rays_escape() {
        // one triangle alone: its ray meets nothing
        let p = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert_eq!(triangle_thickness(&p, &[[0, 1, 2]]).unwrap(), vec![f64::INFINITY]);
        // a zero-area triangle is not measured
        let q = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert!(triangle_thickness(&q, &[[0, 1, 2]]).unwrap()[0].is_nan());
        assert!(triangle_thickness(&q, &[]).unwrap().is_empty());
    }

    #[test]
    fn bvh_agrees_with_brute_force() {
        // a sponge has many parallel walls at many distances: every ray's
        // first hit equals the nearest over all triangles
        let m = crate::schemes::menger_sponge::menger_sponge(2).unwrap();
        let t = m.triangulate();
        let mut p = m.positions().to_vec();
        p.extend_from_slice(&t.points);
        let got = triangle_thickness(&p, &t.tris).unwrap();
        for (i, tri) in t.tris.iter().enumerate().step_by(7) {
            let [a, b, c] = tri.map(|v| p[v as usize]);
            let n = (b - a).cross(c - a).normalize();
            let o = (a + b + c) / 3.0;
            let brute = t
                .tris
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .filter_map(|(_, u)| {
                    let q = u.map(|v| p[v as usize]);
                    ray_triangle(o, -n, q[0], q[1], q[2]).filter(|&h| h > 1e-12)
                })
                .fold(f64::INFINITY, f64::min);
            assert!((got[i] - brute).abs() <= 1e-12, "triangle {i}: {} vs {brute}", got[i]);
        }
        // the sponge's thinnest wall is one cell: a ninth of its side at level 2
        let side = p.iter().map(|q| q.x).fold(f64::NEG_INFINITY, f64::max) - p.iter().map(|q| q.x).fold(f64::INFINITY, f64::min);
        let min = got.iter().copied().fold(f64::INFINITY, f64::min);
        assert!((min - side / 9.0).abs() <= 1e-9 * side, "{min} vs {side} / 9");
    }

    #[test]
    fn node_layout_counts() {
        for n in [1, 4, 5, 9, 100, 12345] {
            let p: Vec<DVec3> = (0..3 * n).map(|k| DVec3::new(k as f64, (k % 3) as f64, 0.0)).collect();
            let tris: Vec<[u32; 3]> = (0..n as u32).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
            let b = Bvh::new(&p, &tris);
            assert_eq!(b.nodes.len(), n_nodes(n));
            let mut seen = b.order.clone();
            seen.sort_unstable();
            assert!(seen.iter().enumerate().all(|(k, &t)| t as usize == k));
        }
    }
}

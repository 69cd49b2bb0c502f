//! Exports: polygons (lossless), pyvista's padded layout, and triangles for
//! rendering and for the validation peers.

use super::{FaceId, Mesh, PolygonFaces};
use glam::{DVec2, DVec3};
use rayon::prelude::*;

impl Mesh {
    /// Every non-hole face as its vertex cycle from its first corner, repeats
    /// kept (a self-loop shows as a vertex twice in a row; a one-gon or a
    /// point-sphere as a face of size 1).
    pub fn to_polygons(&self) -> PolygonFaces {
        let mut out = PolygonFaces {
            sizes: Vec::with_capacity(self.n_faces()),
            indices: Vec::with_capacity(self.n_halfedges() + self.n_faces()),
        };
        for f in self.faces() {
            if self.is_hole(f) {
                continue;
            }
            let before = out.indices.len();
            out.indices.extend(self.face_vertices(f).map(|v| v.0));
            out.sizes.push((out.indices.len() - before) as u32);
        }
        out
    }

    /// pyvista/VTK cell layout: `[n, i0, .., i(n-1), n, ...]`, holes left out.
    pub fn to_padded_faces(&self) -> Vec<u32> {
        let p = self.to_polygons();
        let mut out = Vec::with_capacity(p.sizes.len() + p.indices.len());
        let mut k = 0;
        for &s in &p.sizes {
            out.push(s);
            out.extend_from_slice(&p.indices[k..k + s as usize]);
            k += s as usize;
        }
        out
    }

    /// Triangles of every non-hole face and the face each came from.
    ///
    /// Consecutive repeated vertices (self-loops) are dropped first; faces
    /// left with fewer than three corners (one-gons, two-gons, point-spheres)
    /// give no triangle. Triangles and convex faces are fanned; other faces
    /// are ear-clipped in the plane of their Newell normal, so star-shaped and
    /// other simple non-convex planar faces come out right.
    pub fn triangles(&self) -> (Vec<[u32; 3]>, Vec<u32>) {
        let per_face: Vec<Vec<[u32; 3]>> = (0..self.n_faces() as u32)
            .into_par_iter()
            .with_min_len(4096)
            .map(|f| {
                let f = FaceId(f);
                if self.is_hole(f) {
                    return Vec::new();
                }
                let mut cyc: Vec<u32> = self.face_vertices(f).map(|v| v.0).collect();
                dedup_cyclic(&mut cyc);
                triangulate_polygon(&cyc, &self.pos)
            })
            .collect();
        let n: usize = per_face.iter().map(|t| t.len()).sum();
        let mut tris = Vec::with_capacity(n);
        let mut tri_face = Vec::with_capacity(n);
        for (f, t) in per_face.into_iter().enumerate() {
            tri_face.extend(std::iter::repeat(f as u32).take(t.len()));
            tris.extend(t);
        }
        (tris, tri_face)
    }
}

/// Removes consecutive repeats, cyclically (`[a, a, b, c, a]` → `[a, b, c]`).
fn dedup_cyclic(c: &mut Vec<u32>) {
    c.dedup();
    while c.len() > 1 && c.first() == c.last() {
        c.pop();
    }
}

/// Triangulates one polygon cycle (no consecutive repeats).
pub(crate) fn triangulate_polygon(cyc: &[u32], pos: &[DVec3]) -> Vec<[u32; 3]> {
    let n = cyc.len();
    if n < 3 {
        return Vec::new();
    }
    if n == 3 {
        return vec![[cyc[0], cyc[1], cyc[2]]];
    }
    let p3: Vec<DVec3> = cyc.iter().map(|&v| pos[v as usize]).collect();
    let mut normal = DVec3::ZERO;
    for i in 0..n {
        normal += p3[i].cross(p3[(i + 1) % n]);
    }
    let fan = || (1..n - 1).map(|i| [cyc[0], cyc[i], cyc[i + 1]]).collect::<Vec<_>>();
    let Some(nz) = normal.try_normalize() else { return fan() };
    // 2D frame in the face plane, counter-clockwise seen from the normal
    let u = nz.any_orthonormal_vector();
    let w = nz.cross(u);
    let c = p3.iter().sum::<DVec3>() / n as f64;
    let p: Vec<DVec2> = p3.iter().map(|q| DVec2::new((*q - c).dot(u), (*q - c).dot(w))).collect();
    let cross = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    if (0..n).all(|i| cross(p[i], p[(i + 1) % n], p[(i + 2) % n]) >= 0.0) {
        return fan();
    }
    ear_clip(cyc, &p)
}

/// Ear clipping of a simple counter-clockwise polygon, O(n²). Falls back to
/// cutting the most convex corner when no strict ear exists (degenerate input).
fn ear_clip(cyc: &[u32], p: &[DVec2]) -> Vec<[u32; 3]> {
    let mut idx: Vec<usize> = (0..cyc.len()).collect();
    let mut out = Vec::with_capacity(cyc.len() - 2);
    let cross = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    while idx.len() > 3 {
        let m = idx.len();
        let mut best: Option<(usize, f64)> = None;
        let mut ear = None;
        for i in 0..m {
            let (a, b, c) = (idx[(i + m - 1) % m], idx[i], idx[(i + 1) % m]);
            let turn = cross(p[a], p[b], p[c]);
            if best.is_none_or(|(_, t)| turn > t) {
                best = Some((i, turn));
            }
            if turn <= 0.0 {
                continue;
            }
            let inside = idx.iter().any(|&k| {
                k != a && k != b && k != c && p[k] != p[a] && p[k] != p[b] && p[k] != p[c] && {
                    let (d1, d2, d3) = (cross(p[a], p[b], p[k]), cross(p[b], p[c], p[k]), cross(p[c], p[a], p[k]));
                    d1 >= 0.0 && d2 >= 0.0 && d3 >= 0.0
                }
            });
            if !inside {
                ear = Some(i);
                break;
            }
        }
        let i = ear.unwrap_or_else(|| best.unwrap().0);
        let (a, b, c) = (idx[(i + m - 1) % m], idx[i], idx[(i + 1) % m]);
        out.push([cyc[a], cyc[b], cyc[c]]);
        idx.remove(i);
    }
    out.push([cyc[idx[0]], cyc[idx[1]], cyc[idx[2]]]);
    out
}

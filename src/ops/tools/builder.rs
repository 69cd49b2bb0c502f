//! A rebuild helper for the bulk tools: faces given as vertex cycles whose
//! sides carry a tag, twins paired by (tail, head, tag) against
//! (head, tail, tag). Tags tell apart the sides of multi-edges and
//! self-loops, which a polygon list cannot (see `Mesh::from_polygons`).
//! The result goes through `Mesh::from_corner_twins`, which checks twin
//! symmetry and manifold vertices, so a tool's mistake is a `MeshError`,
//! never a broken mesh.

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use glam::DVec3;
use rustc_hash::FxHashMap;

#[derive(Default)]
pub(crate) struct Builder {
    pub pos: Vec<DVec3>,
    sizes: Vec<u32>,
    verts: Vec<u32>,
    tags: Vec<u64>,
    holes: Vec<bool>,
}

impl Builder {
    pub fn with_positions(pos: Vec<DVec3>) -> Builder {
        Builder { pos, ..Default::default() }
    }

    /// A face through `verts` in order; side j runs verts[j] → verts[j+1]
    /// and carries `tags[j]`.
    pub fn face(&mut self, verts: &[u32], tags: &[u64]) {
        debug_assert_eq!(verts.len(), tags.len());
        self.sizes.push(verts.len() as u32);
        self.verts.extend_from_slice(verts);
        self.tags.extend_from_slice(tags);
        self.holes.push(false);
    }

    /// The same face with the opposite orientation (each side keeps its tag).
    #[cfg(test)]
    pub fn face_reversed(&mut self, verts: &[u32], tags: &[u64]) {
        let n = verts.len();
        let v: Vec<u32> = (0..n).map(|j| verts[(n - j) % n]).collect();
        let t: Vec<u64> = (0..n).map(|j| tags[(2 * n - j - 1) % n]).collect();
        self.face(&v, &t);
    }

    /// Pairs the sides and builds; `what` names the tool in errors.
    pub fn build(self, what: &str) -> Result<Mesh> {
        let twin = match self.twins_by_tail() {
            Some(t) => {
                // (the two passes agree wherever the first answers)
                debug_assert!(self.twins_by_map(what).is_ok_and(|m| m == t), "{what}: twins by tail differ from the map's");
                t
            }
            None => self.twins_by_map(what)?,
        };
        let mut m = Mesh::from_corner_twins(self.pos, &self.sizes, &self.verts, &twin)
            .map_err(|e| MeshError::Precondition(format!("{what}: the result would not be a manifold ({e})")))?;
        for (f, &h) in self.holes.iter().enumerate() {
            if h {
                m.f_hole[f] = true;
            }
        }
        debug_assert!(m.validate().is_ok(), "{what}: {:?}", m.validate());
        Ok(m)
    }

    /// The twins of [`Self::twins_by_map`] when every side has exactly one
    /// reverse side and no other side shares its (tail, head, tag), found
    /// among the few sides leaving its head (sides bucketed by tail, a
    /// counting sort) instead of through a hash map of every side (8 % of
    /// a wireframe's call at 4 M sides). Any other case (a tool's mistake,
    /// point-spheres, self-loops) gives None, and the map's pass answers as
    /// it always did, and so does a vertex with more than `TAIL_SCAN_MAX`
    /// sides leaving it.
    fn twins_by_tail(&self) -> Option<Vec<u32>> {
        /// Sides leaving one vertex up to which it scans them.
        const TAIL_SCAN_MAX: usize = 64;
        let (n, nv) = (self.verts.len(), self.pos.len());
        let mut head = vec![0u32; n];
        let mut start = 0usize;
        for &s in &self.sizes {
            let s = s as usize;
            for j in 0..s {
                let (a, b) = (self.verts[start + j], self.verts[start + (j + 1) % s]);
                if a as usize >= nv || (s == 1 && a == b && self.tags[start + j] == u64::MAX) {
                    return None;
                }
                head[start + j] = b;
            }
            start += s;
        }
        let mut first = vec![0u32; nv + 1];
        for &a in &self.verts {
            first[a as usize + 1] += 1;
        }
        // a side looks through the sides leaving both its ends: Σ valence²,
        // quadratic at a vertex of high valence (the 8,000-valent apex of
        // `conway("Y8000")` after a cut: 74 ms); the map is linear there
        if first.iter().skip(1).any(|&k| k as usize > TAIL_SCAN_MAX) {
            return None;
        }
        for v in 0..nv {
            first[v + 1] += first[v];
        }
        let mut by_tail = vec![0u32; n];
        let mut fill = first[..nv].to_vec();
        for (c, &a) in self.verts.iter().enumerate() {
            by_tail[fill[a as usize] as usize] = c as u32;
            fill[a as usize] += 1;
        }
        drop(fill);
        let sides = |v: u32| &by_tail[first[v as usize] as usize..first[v as usize + 1] as usize];
        let mut twin = vec![u32::MAX; n];
        for c in 0..n {
            let (a, b, t) = (self.verts[c], head[c], self.tags[c]);
            let mut found = u32::MAX;
            for &d in sides(b) {
                if head[d as usize] == a && self.tags[d as usize] == t {
                    if found != u32::MAX {
                        return None;
                    }
                    found = d;
                }
            }
            if found == u32::MAX || found == c as u32 || sides(a).iter().any(|&e| e != c as u32 && head[e as usize] == b && self.tags[e as usize] == t) {
                return None;
            }
            twin[c] = found;
        }
        Some(twin)
    }

    /// Twins by a hash map of open sides, in face order; the error of a side
    /// left without a twin.
    fn twins_by_map(&self, what: &str) -> Result<Vec<u32>> {
        let n = self.verts.len();
        let mut twin = vec![u32::MAX; n];
        let mut open: FxHashMap<(u32, u32, u64), u32> = FxHashMap::default();
        open.reserve(n / 2 + 1);
        let mut start = 0usize;
        for &s in &self.sizes {
            let s = s as usize;
            for j in 0..s {
                let c = start + j;
                let (a, b) = (self.verts[c], self.verts[start + (j + 1) % s]);
                if s == 1 && a == b && self.tags[c] == u64::MAX {
                    continue; // a point-sphere's lone corner
                }
                if let Some(o) = open.remove(&(b, a, self.tags[c])) {
                    twin[c] = o;
                    twin[o as usize] = c as u32;
                } else {
                    open.insert((a, b, self.tags[c]), c as u32);
                }
            }
            start += s;
        }
        if let Some((&(a, b, _), _)) = open.iter().next() {
            return Err(MeshError::Precondition(format!(
                "{what}: the result would have an unmatched side ({a} -> {b}); the input is not a case this tool handles"
            )));
        }
        Ok(twin)
    }
}

/// Tag of a side: a class (which kind of edge) and an id within it.
pub(crate) fn tag(class: u64, id: usize) -> u64 {
    (class << 48) | id as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pyramid over an n-gon through the builder: the scan by tail pairs
    /// it up to its valence limit, the map beyond (the scan is quadratic
    /// at the apex), and both give the closed pyramid.
    #[test]
    fn high_valence_takes_the_map() {
        let pyramid = |n: usize| {
            let mut pos: Vec<DVec3> = (0..n)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / n as f64;
                    DVec3::new(a.cos(), a.sin(), 0.0)
                })
                .collect();
            pos.push(DVec3::Z);
            let mut b = Builder::with_positions(pos);
            let base: Vec<u32> = (0..n as u32).rev().collect();
            b.face(&base, &vec![0; n]);
            for k in 0..n as u32 {
                b.face(&[k, (k + 1) % n as u32, n as u32], &[0, 0, 0]);
            }
            b
        };
        for n in [8, 64, 65, 500] {
            let b = pyramid(n);
            let by_tail = b.twins_by_tail();
            assert_eq!(by_tail.is_some(), n <= 64, "{n}");
            let map = b.twins_by_map("test").unwrap();
            if let Some(t) = by_tail {
                assert_eq!(t, map);
            }
            let m = b.build("test").unwrap();
            assert_eq!((m.n_vertices(), m.n_edges(), m.n_faces()), (n + 1, 2 * n, n + 1));
            m.validate().unwrap();
        }
    }
}

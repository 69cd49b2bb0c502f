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
    pub fn face_reversed(&mut self, verts: &[u32], tags: &[u64]) {
        let n = verts.len();
        let v: Vec<u32> = (0..n).map(|j| verts[(n - j) % n]).collect();
        let t: Vec<u64> = (0..n).map(|j| tags[(2 * n - j - 1) % n]).collect();
        self.face(&v, &t);
    }

    /// Pairs the sides and builds; `what` names the tool in errors.
    pub fn build(self, what: &str) -> Result<Mesh> {
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
}

/// Tag of a side: a class (which kind of edge) and an id within it.
pub(crate) fn tag(class: u64, id: usize) -> u64 {
    (class << 48) | id as u64
}

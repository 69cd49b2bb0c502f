//! DeleteEdge on many edges at once, in time linear in the mesh.
//!
//! One DeleteEdge relabels the faces it merges or splits (`euler.rs`), so a
//! run of deletions that grows one face costs that face's size each time:
//! the closest-edge multi-face handle's cleanup on two 16,000-gon caps spent
//! a second deleting 16,000 edges. Here every surviving side's `next` skips
//! the deleted sides around its head (as DeleteEdge's splice does, the runs
//! of deleted sides in each rotation walked once), and the faces are the new
//! cycles.

use super::{Mesh, POINT};
use crate::error::{MeshError, Result};
use crate::mesh::EdgeId;

impl Mesh {
    /// **DeleteEdge** on every edge of `edges` (distinct, any order): the
    /// mesh equals deleting them one by one up to the numbering (same faces
    /// as vertex cycles, same holes, same point-spheres for vertices left
    /// without edges). Numbering: vertices unchanged; the surviving edges
    /// keep their order (edge k becomes k minus the deleted edges below it,
    /// half-edges `2k`, `2k + 1` as before); faces beside no deleted edge
    /// keep their order and come first, then the new cycles in the order of
    /// their smallest half-edge, then a point-sphere face for each vertex
    /// left without edges, in vertex order; new faces are not holes. When a
    /// deleted edge borders a hole, the edges are deleted one by one,
    /// highest id first, with DeleteEdge's numbering: a hole's flag after merges (a hole only when
    /// both faces were) and splits (both parts keep it) depends on their
    /// order.
    ///
    /// Errors: an edge out of range or given twice (the mesh is unchanged).
    pub fn delete_edges(&mut self, edges: &[EdgeId]) -> Result<()> {
        let ne = self.n_edges();
        let mut gone = vec![false; ne];
        for &e in edges {
            if e.idx() >= ne {
                return Err(MeshError::InvalidArgument(format!("delete_edges: edge {} out of range (mesh has {ne} edges)", e.0)));
            }
            if gone[e.idx()] {
                return Err(MeshError::InvalidArgument(format!("delete_edges: edge {} is given twice", e.0)));
            }
            gone[e.idx()] = true;
        }
        if edges.is_empty() {
            return Ok(());
        }
        let dead = |h: u32| gone[(h >> 1) as usize];
        // new edge ids: survivors in order
        let mut new_edge = vec![u32::MAX; ne];
        let kept: Vec<u32> = (0..ne as u32).filter(|&e| !gone[e as usize]).collect();
        for (k, &e) in kept.iter().enumerate() {
            new_edge[e as usize] = k as u32;
        }
        let k = kept.len() as u32;
        let remap = |h: u32| 2 * new_edge[(h >> 1) as usize] + (h & 1);
        let nh = 2 * k as usize;
        // faces beside a deleted edge are replaced by the new cycles
        let mut touched = vec![false; self.n_faces()];
        for (e, _) in gone.iter().enumerate().filter(|(_, &g)| g) {
            touched[self.he_face[2 * e] as usize] = true;
            touched[self.he_face[2 * e + 1] as usize] = true;
        }
        if touched.iter().zip(&self.f_hole).any(|(&t, &h)| t && h) {
            // a hole's flag after merges and splits depends on their order:
            // one by one, highest id first (the others keep their ids)
            let mut sorted: Vec<EdgeId> = edges.to_vec();
            sorted.sort_unstable_by(|a, b| b.cmp(a));
            for e in sorted {
                self.delete_edge(e)?;
            }
            return Ok(());
        }
        let mut next = vec![0u32; nh];
        let mut vert = vec![0u32; nh];
        for h in 0..self.he_next.len() as u32 {
            if dead(h) {
                continue;
            }
            let mut y = self.he_next[h as usize];
            while dead(y) {
                y = self.he_next[(y ^ 1) as usize];
            }
            next[remap(h) as usize] = remap(y);
            vert[remap(h) as usize] = self.he_vert[h as usize];
        }
        let mut prev = vec![0u32; nh];
        for (h, &n) in next.iter().enumerate() {
            prev[n as usize] = h as u32;
        }
        // faces: untouched ones in order, then the new cycles
        let mut face = vec![u32::MAX; nh];
        let label = |face: &mut [u32], s: u32, id: u32| {
            let mut h = s;
            loop {
                face[h as usize] = id;
                h = next[h as usize];
                if h == s {
                    break;
                }
            }
        };
        let mut f_start = Vec::with_capacity(self.n_faces());
        let mut f_hole = Vec::with_capacity(self.n_faces());
        for f in 0..self.n_faces() {
            if touched[f] {
                continue;
            }
            let s = self.f_start[f];
            let id = f_start.len() as u32;
            if s & POINT != 0 {
                f_start.push(s);
                self.v_out[(s & !POINT) as usize] = POINT | id;
            } else {
                let s = remap(s);
                f_start.push(s);
                label(&mut face, s, id);
            }
            f_hole.push(self.f_hole[f]);
        }
        for s in 0..nh as u32 {
            if face[s as usize] != u32::MAX {
                continue;
            }
            let id = f_start.len() as u32;
            label(&mut face, s, id);
            f_start.push(s);
            // no touched face was a hole
            f_hole.push(false);
        }
        // outgoing sides: a survivor of the rotation, or a point-sphere
        for v in 0..self.pos.len() {
            let o = self.v_out[v];
            if o & POINT != 0 || !dead(o) {
                if o & POINT == 0 {
                    self.v_out[v] = remap(o);
                }
                continue;
            }
            // the rotation: next outgoing side is next(twin(h))
            let mut h = self.he_next[(o ^ 1) as usize];
            while h != o && dead(h) {
                h = self.he_next[(h ^ 1) as usize];
            }
            if h != o {
                self.v_out[v] = remap(h);
            } else {
                let id = f_start.len() as u32;
                f_start.push(POINT | v as u32);
                f_hole.push(false);
                self.v_out[v] = POINT | id;
            }
        }
        self.he_next = next;
        self.he_prev = prev;
        self.he_vert = vert;
        self.he_face = face;
        self.f_start = f_start;
        self.f_hole = f_hole;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::mesh::{EdgeId, Mesh};
    use crate::primitives;
    use crate::schemes::hosts::test_meshes::{corpus, open_meshes};

    /// Faces as vertex cycles in their smallest rotation, sorted, and
    /// the point-sphere vertices and hole flags with them.
    fn cycles(m: &Mesh) -> Vec<(Vec<u32>, bool)> {
        let mut out: Vec<(Vec<u32>, bool)> = (0..m.n_faces())
            .map(|f| {
                let fid = crate::FaceId::new(f);
                let mut c: Vec<u32> = match m.face_halfedge(fid) {
                    Some(_) => m.face_halfedges(fid).map(|h| m.vertex(h).0).collect(),
                    None => vec![u32::MAX, m.f_start[f] & !super::POINT],
                };
                // the smallest rotation (a vertex can repeat in a cycle)
                let i = (0..c.len()).min_by_key(|&i| [&c[i..], &c[..i]].concat()).unwrap();
                c.rotate_left(i);
                (c, m.is_hole(fid))
            })
            .collect();
        out.sort();
        out
    }

    #[test]
    fn batch_equals_one_by_one() {
        // random edge sets on meshes with self-loops, two-gons, holes,
        // several genera: same faces, holes and point-spheres as deleting
        // the edges one at a time, a valid mesh, survivors in order
        let mut meshes = vec![primitives::cube(), primitives::torus(6, 4, 3.0, 1.0).unwrap(), crate::schemes::conway::seeds::prism(7).unwrap()];
        meshes.extend(corpus().into_iter().map(|(_, m)| m));
        for (_, m) in open_meshes() {
            // a hole split in two by an edge: both sides holes, and deleting
            // the edge must give one hole back
            let mut split = m.clone();
            let hole = (0..m.n_faces()).find(|&f| m.is_hole(crate::FaceId::new(f))).unwrap();
            let hs: Vec<_> = m.face_halfedges(crate::FaceId::new(hole)).collect();
            let e = split.insert_edge(crate::Corner::Halfedge(hs[0]), crate::Corner::Halfedge(hs[hs.len() / 2])).unwrap();
            for h in [e.halfedge(), e.halfedge().twin()] {
                let f = split.face(h).idx();
                split.f_hole[f] = true;
            }
            let holes = |m: &Mesh| (0..m.n_faces()).filter(|&f| m.is_hole(crate::FaceId::new(f))).count();
            assert_eq!(holes(&split), holes(&m) + 1);
            let mut back = split.clone();
            back.delete_edges(&[e]).unwrap();
            assert_eq!(holes(&back), holes(&m));
            meshes.push(m);
            meshes.push(split);
        }
        let mut rng = crate::test_rng::Xorshift::new(0x2545f4914f6cdd1d);
        let mut rnd = |n: usize| (rng.next_u64() % n as u64) as usize;
        let (mut compared, mut batched) = (0, 0);
        for (i, m) in meshes.iter().enumerate() {
            for trial in 0..40 {
                let ne = m.n_edges();
                let take = 1 + rnd(ne.max(1)).min(ne.saturating_sub(1));
                let mut edges: Vec<usize> = (0..ne).collect();
                for j in 0..take {
                    let r = j + rnd(ne - j);
                    edges.swap(j, r);
                }
                edges.truncate(take);
                let mut one = m.clone();
                let mut sorted = edges.clone();
                sorted.sort_unstable_by(|a, b| b.cmp(a));
                for &e in &sorted {
                    one.delete_edge(EdgeId(e as u32)).unwrap();
                }
                let mut batch = m.clone();
                batch.delete_edges(&edges.iter().map(|&e| EdgeId(e as u32)).collect::<Vec<_>>()).unwrap();
                batch.validate().unwrap_or_else(|err| panic!("mesh {i} trial {trial}: {err}"));
                assert_eq!(cycles(&batch), cycles(&one), "mesh {i} trial {trial}, edges {edges:?}");
                compared += 1;
                // survivors keep their order and ends (unless a hole made
                // it delete one by one)
                let hole_side = |e: usize| m.is_hole(m.face(crate::HalfedgeId::new(2 * e))) || m.is_hole(m.face(crate::HalfedgeId::new(2 * e + 1)));
                if edges.iter().any(|&e| hole_side(e)) {
                    continue;
                }
                batched += 1;
                let kept: Vec<usize> = (0..ne).filter(|e| !edges.contains(e)).collect();
                for (k, &e) in kept.iter().enumerate() {
                    assert_eq!(batch.he_vert[2 * k], m.he_vert[2 * e]);
                    assert_eq!(batch.he_vert[2 * k + 1], m.he_vert[2 * e + 1]);
                }
            }
        }
        assert!(compared >= 200 && batched >= 150, "{compared} compared, {batched} batched");
        let mut m = primitives::cube();
        assert!(m.delete_edges(&[EdgeId(3), EdgeId(3)]).unwrap_err().to_string().contains("twice"));
        assert!(m.delete_edges(&[EdgeId(99)]).unwrap_err().to_string().contains("out of range"));
        assert_eq!(m.n_edges(), 12);
    }
}

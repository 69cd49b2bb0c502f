//! Boundaries: the loops an open mesh's hole faces stand for, and the
//! Euler characteristic of the open surface.
//!
//! An open mesh is stored capped: each boundary loop is one face marked as a
//! hole (`f_hole`), so every edge still has two sides and every vertex one
//! disk. The queries here describe the open surface the user sees: holes are
//! no faces, their sides are the boundary edges, and χ = V − E + F counts
//! real faces only, χ = 2c − 2g − b (c components, g genus, b boundary
//! loops). The capped surface has χ + b, which gives the genus.

use super::{FaceId, Mesh, VertexId, POINT};

impl Mesh {
    /// Number of boundary loops (the hole faces).
    pub fn n_boundary_loops(&self) -> usize {
        self.n_holes()
    }

    /// True when the mesh has no boundary loop.
    pub fn is_closed(&self) -> bool {
        !self.f_hole.iter().any(|&h| h)
    }

    /// The vertices of every boundary loop, in the order its boundary edges
    /// run in the real faces (each consecutive pair, the last back to the
    /// first, is a directed side of a face), so a loop runs clockwise when
    /// seen from the side the faces' normals point to. Each loop starts at
    /// its lowest vertex index, and the loops are sorted by it. A loop of
    /// one vertex is a boundary self-loop.
    pub fn boundary_loops(&self) -> Vec<Vec<VertexId>> {
        let mut loops: Vec<Vec<VertexId>> = self
            .faces()
            .filter(|&f| self.is_hole(f))
            .map(|f| {
                // the hole runs against its real sides: twin(h) goes head(h) -> tail(h)
                let mut l: Vec<VertexId> = self.face_vertices(f).collect();
                l.reverse();
                let k = (0..l.len()).min_by_key(|&i| l[i]).unwrap_or(0);
                l.rotate_left(k);
                l
            })
            .collect();
        loops.sort_by_key(|l| l.first().copied());
        loops
    }

    /// Every boundary edge as `[tail, head]` of its real side, loop after loop
    /// in the order of [`Mesh::boundary_loops`].
    pub fn boundary_edges(&self) -> Vec<[u32; 2]> {
        let mut out = Vec::new();
        for l in self.boundary_loops() {
            for (i, &a) in l.iter().enumerate() {
                out.push([a.0, l[(i + 1) % l.len()].0]);
            }
        }
        out
    }

    /// χ = V − E + F of the open surface: hole faces are not counted.
    /// On a closed mesh this is the usual χ = 2c − 2g.
    pub fn euler_characteristic(&self) -> i64 {
        self.capped_euler_characteristic() - self.n_holes() as i64
    }

    /// χ of the capped surface (hole faces counted as faces), = 2c − 2g.
    pub fn capped_euler_characteristic(&self) -> i64 {
        self.n_vertices() as i64 - self.n_edges() as i64 + self.n_faces() as i64
    }

    /// Per component (in the order of [`Mesh::vertex_components`]): χ of the
    /// capped surface and the number of boundary loops.
    pub(crate) fn component_chi_and_loops(&self) -> (Vec<i64>, Vec<i64>) {
        let (label, n) = self.vertex_components();
        let mut chi = vec![0i64; n];
        let mut loops = vec![0i64; n];
        for &l in &label {
            chi[l as usize] += 1;
        }
        for e in 0..self.n_edges() {
            chi[label[self.he_vert[2 * e] as usize] as usize] -= 1;
        }
        for (f, &s) in self.f_start.iter().enumerate() {
            let v = if s & POINT != 0 { s & !POINT } else { self.he_vert[s as usize] };
            let c = label[v as usize] as usize;
            chi[c] += 1;
            if self.is_hole(FaceId(f as u32)) {
                loops[c] += 1;
            }
        }
        (chi, loops)
    }

    /// χ of each component of the open surface (holes not counted), in the
    /// order of [`Mesh::vertex_components`]: χ_c = 2 − 2g_c − b_c.
    pub fn component_euler_characteristics(&self) -> Vec<i64> {
        let (chi, loops) = self.component_chi_and_loops();
        chi.iter().zip(&loops).map(|(c, b)| c - b).collect()
    }

    /// Boundary loops of each component, in the order of [`Mesh::vertex_components`].
    pub fn component_boundary_loops(&self) -> Vec<i64> {
        self.component_chi_and_loops().1
    }

    /// χ of each component with its holes capped (even: a closed orientable surface).
    pub fn component_capped_euler_characteristics(&self) -> Vec<i64> {
        self.component_chi_and_loops().0
    }
}

impl Mesh {
    /// `Ok` on a closed mesh; on an open one a `Precondition` error naming
    /// `scheme`, the number of boundary loops, one boundary edge and `why`
    /// the scheme refuses them (it must never fill a hole silently).
    pub(crate) fn refuse_open(&self, scheme: &str, why: &str) -> crate::error::Result<()> {
        let b = self.n_boundary_loops();
        if b == 0 {
            return Ok(());
        }
        let e = self.boundary_edges()[0];
        Err(crate::error::MeshError::Precondition(format!(
            "{scheme}: the mesh has {b} boundary loop{} (it is open: boundary edge ({}, {}), ...); {why}",
            if b == 1 { "" } else { "s" },
            e[0],
            e[1]
        )))
    }
}

#[cfg(test)]
mod tests {
    use crate::mesh::{BuildOptions, Mesh};
    use glam::DVec3;

    fn grid(n: usize) -> Mesh {
        let pos: Vec<DVec3> = (0..=n).flat_map(|j| (0..=n).map(move |i| DVec3::new(i as f64, j as f64, 0.0))).collect();
        let mut idx = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let a = (j * (n + 1) + i) as i64;
                idx.extend([a, a + 1, a + 2 + n as i64, a + 1 + n as i64]);
            }
        }
        let opts = BuildOptions { close_boundaries: true, ..Default::default() };
        Mesh::from_polygons(pos, &vec![4; n * n], &idx, opts).unwrap()
    }

    #[test]
    fn open_grid_is_a_disk() {
        let m = grid(3);
        assert!(!m.is_closed());
        assert_eq!((m.n_boundary_loops(), m.euler_characteristic(), m.genus()), (1, 1, 0));
        assert_eq!(m.capped_euler_characteristic(), 2);
        let loops = m.boundary_loops();
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].len(), 12);
        assert_eq!(loops[0][0].0, 0);
        // the first face is 0 -> 1 -> 5 -> 4: the boundary runs 0 -> 1 as in it
        assert_eq!(loops[0][1].0, 1);
        let edges = m.boundary_edges();
        assert_eq!(edges.len(), 12);
        assert!(edges.contains(&[0, 1]) && edges.contains(&[4, 0]));
        assert_eq!((m.component_euler_characteristics(), m.component_boundary_loops()), (vec![1], vec![1]));
        m.validate().unwrap();
    }

    #[test]
    fn closed_mesh_unchanged() {
        let c = crate::primitives::cube();
        assert!(c.is_closed());
        assert_eq!((c.euler_characteristic(), c.capped_euler_characteristic()), (2, 2));
        assert!(c.boundary_loops().is_empty() && c.boundary_edges().is_empty());
        assert_eq!(c.component_euler_characteristics(), vec![2]);
    }
}

//! The corner-and-twin builds of honeycomb and vertex truncation that
//! [`super::face_vertex_columns`] replaced (issue 19, item 1), kept as the
//! reference its tests compare with, bit for bit.

use super::hosts::{FaceLayout, VertexLayout};
use crate::error::Result;
use crate::mesh::{Mesh, NONE, POINT};
use glam::DVec3;

/// Output faces of the schemes that keep every old face as one new face (in
/// old face order) and add one face per vertex after them (in old vertex
/// order): honeycomb and vertex truncation. Point-spheres are carried
/// through (a point-sphere face keeps its one corner), and so are hole marks.
struct FaceThenVertexFaces {
    /// Sizes of the output faces.
    pub sizes: Vec<u32>,
    /// `off[f]` is the first output corner of old face `f`'s image;
    /// `off[nf]` the first corner of the vertex faces.
    pub off: Vec<u32>,
    /// The output vertex of each point-sphere vertex (`NONE` for the others).
    point_id: Vec<u32>,
}

impl FaceThenVertexFaces {
    /// Old face `f` gets `per_corner · degree(f)` corners, vertex `v`
    /// `per_slot · valence(v)`. Appends the point-sphere vertices to `pos`,
    /// in vertex order. Fails only when cancelled.
    pub fn new(m: &Mesh, fl: &FaceLayout, vl: &VertexLayout, per_corner: u32, per_slot: u32, pos: &mut Vec<DVec3>) -> Result<Self> {
        let (nf, nv) = (m.n_faces(), m.n_vertices());
        let mut point_id = vec![NONE; nv];
        let n_points = m.v_out.iter().filter(|&&o| o & POINT != 0).count();
        if n_points > 0 {
            pos.reserve_exact(n_points);
            for v in 0..nv {
                if m.v_out[v] & POINT != 0 {
                    point_id[v] = pos.len() as u32;
                    pos.push(m.pos[v]);
                }
            }
        }
        let mut sizes: Vec<u32> = Vec::with_capacity(nf + nv);
        let mut off: Vec<u32> = Vec::with_capacity(nf + 1);
        off.push(0);
        for f in 0..nf {
            crate::cancel::poll(f)?;
            let d = (per_corner * fl.degree(f) as u32).max(1); // a point-sphere face keeps its one corner
            sizes.push(d);
            off.push(off[f] + d);
        }
        for v in 0..nv {
            crate::cancel::poll(v)?;
            let k = vl.valence(v);
            if k > 0 {
                sizes.push(per_slot * k);
            }
        }
        Ok(FaceThenVertexFaces { sizes, off, point_id })
    }

    /// The first corner of the vertex faces.
    #[inline]
    pub fn vertex_base(&self) -> u32 {
        self.off[self.off.len() - 1]
    }

    /// Fills the corners of the point-sphere faces, builds the mesh and
    /// copies the hole marks of the old faces to their images.
    pub fn build(&self, m: &Mesh, pos: Vec<DVec3>, mut cv: Vec<u32>, tw: &[u32]) -> Result<Mesh> {
        for (f, &s) in m.f_start.iter().enumerate() {
            if s & POINT != 0 {
                cv[self.off[f] as usize] = self.point_id[(s & !POINT) as usize];
            }
        }
        let mut out = Mesh::from_corner_twins(pos, &self.sizes, &cv, tw)?;
        out.f_hole[..m.n_faces()].copy_from_slice(&m.f_hole);
        Ok(out)
    }
}


/// Honeycomb's connectivity as the old builder made it (`new_pos`: one point per half-edge).
pub(crate) fn honeycomb(m: &Mesh, mut new_pos: Vec<DVec3>) -> Result<Mesh> {
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let nh = m.n_halfedges();
    let (next, _, face) = m.halfedge_columns();
    let faces = FaceThenVertexFaces::new(m, &fl, &vl, 1, 2, &mut new_pos)?;
    let out_off = &faces.off;
    let vb = faces.vertex_base();
    let n_corners = vb as usize + 2 * nh;
    let mut cv = vec![0u32; n_corners];
    let mut tw = vec![NONE; n_corners];
    let front = |h: usize| out_off[face[h] as usize] + fl.local(h as u32, face[h]) as u32;
    let vc_even = |g: usize| vb + 2 * vl.vidx[g];
    for h in 0..nh {
        let hp = m.he_prev[h] as usize;
        let hn = next[h] as usize;
        let cf = front(h) as usize;
        cv[cf] = h as u32;
        tw[cf] = vc_even(hn);
        let ce = vc_even(h) as usize;
        cv[ce] = h as u32;
        tw[ce] = front(hp);
        cv[ce + 1] = hp as u32;
        tw[ce + 1] = vc_even(next[hp ^ 1] as usize) + 1;
    }
    faces.build(m, new_pos, cv, &tw)
}

/// Vertex truncation's connectivity as the old builder made it (`new_pos`:
/// one cut point per half-edge, or per edge when `merge`d).
pub(crate) fn vertex_truncation(m: &Mesh, mut new_pos: Vec<DVec3>, merge: bool) -> Result<Mesh> {
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let nh = m.n_halfedges();
    let (next, _, face) = m.halfedge_columns();
    let per_corner = if merge { 1 } else { 2 };
    let faces = FaceThenVertexFaces::new(m, &fl, &vl, per_corner, 1, &mut new_pos)?;
    let out_off = &faces.off;
    let vb = faces.vertex_base();
    let n_corners = vb as usize + nh;
    let mut cv = vec![0u32; n_corners];
    let mut tw = vec![NONE; n_corners];
    let fc = |h: usize| out_off[face[h] as usize] + per_corner * fl.local(h as u32, face[h]) as u32;
    let vc = |g: usize| vb + vl.vidx[g];
    for h in 0..nh {
        let hp = m.he_prev[h] as usize;
        let hn = next[h] as usize;
        let c = fc(h) as usize;
        if merge {
            cv[c] = (h >> 1) as u32;
            tw[c] = vc(hn);
            let cg = vc(h) as usize;
            cv[cg] = (h >> 1) as u32;
            tw[cg] = fc(hp);
        } else {
            cv[c] = h as u32;
            tw[c] = fc(h ^ 1);
            cv[c + 1] = (h ^ 1) as u32;
            tw[c + 1] = vc(hn);
            let cg = vc(h) as usize;
            cv[cg] = h as u32;
            tw[cg] = fc(hp) + 1;
        }
    }
    faces.build(m, new_pos, cv, &tw)
}

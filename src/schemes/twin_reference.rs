//! The corner-and-twin builds ([`Mesh::from_corner_twins`]) of honeycomb,
//! vertex truncation and the fan triangulation that `face_vertex_columns.rs`
//! and `fan_columns.rs` replaced (issue 19, item 1), kept as the references
//! their tests compare with, bit for bit.

use super::hosts::{FaceLayout, VertexLayout, MIN_LEN};
use rayon::prelude::*;
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

/// The fan triangulation as the old builder made it.
pub(crate) fn fan_triangulate(m: &Mesh) -> Result<Option<Mesh>> {
    let nf = m.n_faces();
    let (next, _, _) = m.halfedge_columns();
    let all_triangles = m.f_start.par_iter().zip(&m.f_hole).with_min_len(MIN_LEN).all(|(&s, &hole)| {
        if hole {
            return true;
        }
        let h1 = next[s as usize];
        let h2 = next[h1 as usize];
        h1 != s && h2 != s && next[h2 as usize] == s
    });
    if all_triangles {
        return Ok(None);
    }
    super::hosts::check_output_size("loop", 3 * m.n_halfedges(), m.n_vertices() + nf)?;
    let fl = FaceLayout::new(m)?;
    let (next, vert, face) = m.halfedge_columns();
    let nv = m.n_vertices();
    // output corner base per face and centroid vertex per n-gon
    let mut base = Vec::with_capacity(nf + 1);
    let mut cvert = vec![NONE; nf];
    let mut pos = m.pos.clone();
    let mut n_faces = 0usize;
    let mut b = 0u32;
    for f in 0..nf {
        if f % 65536 == 0 {
            crate::cancel::check()?;
        }
        base.push(b);
        let n = fl.degree(f);
        if n == 3 || m.f_hole[f] {
            // triangles and holes are kept
            b += n as u32;
            n_faces += 1;
        } else {
            b += 3 * n as u32;
            n_faces += n;
            cvert[f] = pos.len() as u32;
            let hs = fl.corners(f);
            let s: DVec3 = hs.iter().map(|&h| m.pos[vert[h as usize] as usize]).sum();
            pos.push(s / n as f64);
        }
    }
    let nc = b as usize;
    debug_assert!(pos.len() >= nv);
    let mut sizes = Vec::with_capacity(n_faces);
    let mut cv = vec![0u32; nc];
    let mut tw = vec![0u32; nc];
    // the output corner of the side along input half-edge h
    let side = |h: u32| -> u32 {
        let f = face[h as usize];
        let k = fl.local(h, f) as u32;
        if cvert[f as usize] == NONE {
            base[f as usize] + k
        } else {
            base[f as usize] + 3 * k
        }
    };
    for f in 0..nf {
        let hs = fl.corners(f);
        let b = base[f] as usize;
        if cvert[f] == NONE {
            sizes.push(hs.len() as u32);
            for (k, &h) in hs.iter().enumerate() {
                cv[b + k] = vert[h as usize];
                tw[b + k] = side(h ^ 1);
            }
        } else {
            let n = hs.len();
            for (k, &h) in hs.iter().enumerate() {
                sizes.push(3);
                let c = b + 3 * k;
                cv[c] = vert[h as usize];
                cv[c + 1] = vert[next[h as usize] as usize];
                cv[c + 2] = cvert[f];
                tw[c] = side(h ^ 1);
                // spoke head(h) -> centroid pairs with centroid -> tail(next h)
                tw[c + 1] = (b + 3 * ((k + 1) % n) + 2) as u32;
                tw[c + 2] = (b + 3 * ((k + n - 1) % n) + 1) as u32;
            }
        }
    }
    let mut out = Mesh::from_corner_twins(pos, &sizes, &cv, &tw)?;
    if m.n_holes() > 0 {
        // output faces: one per kept face, n per fanned face, in face order
        let mut of = 0;
        for f in 0..nf {
            if cvert[f] == NONE {
                out.f_hole[of] = m.f_hole[f];
                of += 1;
            } else {
                of += fl.degree(f);
            }
        }
    }
    Ok(Some(out))
}


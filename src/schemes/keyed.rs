//! The one-pass builder of the Conway operators (`conway/`), TopMod's
//! remeshing schemes (`topmod/`) and column modelling (`ops/tools/column.rs`):
//! output faces as lists of (vertex, side key) corners, where the key names
//! the output edge the side leaving the corner lies on. Keys are dense
//! integers computed by index arithmetic from the input's half-edges, so
//! twins are paired by key, never by vertex ids (polyhedronisme's flags name
//! edges by their two vertices, which cannot tell two edges between the same
//! vertices apart): self-loops, multi-edges, one-gons and two-gons need no
//! special case.

use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, NONE};
use crate::schemes::hosts::{check_output_size, FaceLayout};
use glam::DVec3;

/// Output under construction (see the module docs).
pub(crate) struct Out {
    pub pos: Vec<DVec3>,
    sizes: Vec<u32>,
    cv: Vec<u32>,
    key: Vec<u32>,
    n_keys: usize,
    start: usize,
}

impl Out {
    /// An output with these vertex positions and `n_keys` edges, expecting
    /// about `faces` faces and `corners` corners.
    pub fn new(pos: Vec<DVec3>, n_keys: usize, faces: usize, corners: usize) -> Out {
        Out { pos, sizes: Vec::with_capacity(faces), cv: Vec::with_capacity(corners), key: Vec::with_capacity(corners), n_keys, start: 0 }
    }

    /// Appends a corner at vertex `v` to the current face; the side leaving
    /// it lies on output edge `key`.
    #[inline]
    pub fn c(&mut self, v: u32, key: u32) {
        self.cv.push(v);
        self.key.push(key);
    }

    /// Appends a whole face: its corners in boundary order (counter-clockwise
    /// seen from outside), each a vertex and the key of the side leaving it.
    #[inline]
    pub fn face(&mut self, corners: impl IntoIterator<Item = (u32, u32)>) {
        for (v, k) in corners {
            self.c(v, k);
        }
        self.end();
    }

    /// Closes the current face.
    #[inline]
    pub fn end(&mut self) {
        let n = self.cv.len() - self.start;
        debug_assert!(n > 0);
        self.sizes.push(n as u32);
        self.start = self.cv.len();
    }

    /// Pairs the two sides of every key and builds the mesh. Each key must
    /// be used by exactly two sides or by none (a key range may have gaps;
    /// one or three sides is an internal error: the scheme's arithmetic is
    /// wrong), in opposite directions (checked by [`Mesh::from_corner_twins`]).
    pub fn finish(self, scheme: &str) -> Result<Mesh> {
        check_output_size(scheme, self.cv.len(), self.pos.len())?;
        crate::cancel::check()?;
        const DONE: u32 = NONE - 1;
        let n = self.cv.len();
        let mut first = vec![NONE; self.n_keys];
        let mut tw = vec![NONE; n];
        let bad = |k: u32| MeshError::Invariant(format!("{scheme}: output edge {k} does not have exactly two sides (a bug in the scheme)"));
        for (c, &k) in self.key.iter().enumerate() {
            crate::cancel::poll(c)?;
            let slot = first.get_mut(k as usize).ok_or_else(|| bad(k))?;
            match *slot {
                NONE => *slot = c as u32,
                DONE => return Err(bad(k)),
                o => {
                    tw[c] = o;
                    tw[o as usize] = c as u32;
                    *slot = DONE;
                }
            }
        }
        if let Some(k) = first.iter().position(|&s| s != DONE && s != NONE) {
            return Err(bad(k as u32));
        }
        crate::cancel::check()?;
        Mesh::from_corner_twins(self.pos, &self.sizes, &self.cv, &tw)
    }
}

/// The input's columns and face layout, shared by every scheme built here.
pub(crate) struct In<'a> {
    pub m: &'a Mesh,
    pub next: &'a [u32],
    pub prev: &'a [u32],
    pub vert: &'a [u32],
    pub face: &'a [u32],
    pub fl: FaceLayout,
    pub nv: usize,
    pub ne: usize,
    pub nf: usize,
    pub nh: usize,
}

impl<'a> In<'a> {
    pub fn new(m: &'a Mesh) -> Result<In<'a>> {
        let (next, vert, face) = m.halfedge_columns();
        Ok(In { m, next, prev: &m.he_prev, vert, face, fl: FaceLayout::new(m)?, nv: m.n_vertices(), ne: m.n_edges(), nf: m.n_faces(), nh: m.n_halfedges() })
    }
    /// Position of the tail of half-edge `h`.
    #[inline]
    pub fn p(&self, h: usize) -> DVec3 {
        self.m.pos[self.vert[h] as usize]
    }
    /// Position of the head of half-edge `h`.
    #[inline]
    pub fn q(&self, h: usize) -> DVec3 {
        self.m.pos[self.vert[h ^ 1] as usize]
    }
    /// The next outgoing half-edge around the tail of `h`.
    #[inline]
    pub fn rot(&self, h: usize) -> usize {
        (self.prev[h] ^ 1) as usize
    }
    /// Centroid of every face (corner mean).
    pub fn centroids(&self) -> Vec<DVec3> {
        let mut c = vec![DVec3::ZERO; self.nf];
        crate::schemes::hosts::face_centroids(self.m, &self.fl, &mut c);
        c
    }
    /// Unit normal of every face (Newell's; zero for a degenerate face).
    pub fn normals(&self) -> Vec<DVec3> {
        (0..self.nf).map(|f| self.m.face_newell(crate::FaceId(f as u32)).normalize_or_zero()).collect()
    }
    /// The input's positions, for outputs that keep its vertices first.
    pub fn positions(&self, extra: usize) -> Vec<DVec3> {
        let mut p = Vec::with_capacity(self.nv + extra);
        p.extend_from_slice(&self.m.pos);
        p
    }
}

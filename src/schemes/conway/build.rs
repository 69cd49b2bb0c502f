//! The one builder of the Conway operators: output faces as corner lists
//! `(tail vertex, edge id)`, where the edge id names the output edge from
//! that corner to the next one. Sides are paired into twins by their edge
//! id, so a self-loop or a multi-edge is as unambiguous as any other edge
//! (polyhedronisme's flags name edges by their two vertices, which cannot
//! tell two edges between the same vertices apart).

use crate::error::{MeshError, Result};
use crate::mesh::{Mesh, NONE};
use crate::schemes::hosts::{check_output_size, FaceLayout};
use glam::DVec3;

/// Paired sides are marked with this in [`Out::finish`].
const PAIRED: u32 = NONE - 1;

/// An output mesh under construction.
pub(crate) struct Out {
    pub pos: Vec<DVec3>,
    sizes: Vec<u32>,
    cv: Vec<u32>,
    ce: Vec<u32>,
    n_edge_ids: usize,
}

impl Out {
    /// `n_edge_ids` bounds the edge ids used (they may be sparse: an id no
    /// side uses is no edge); `corners` and `faces` are capacity hints.
    pub fn new(pos: Vec<DVec3>, n_edge_ids: usize, corners: usize, faces: usize) -> Out {
        Out { pos, sizes: Vec::with_capacity(faces), cv: Vec::with_capacity(corners), ce: Vec::with_capacity(corners), n_edge_ids }
    }

    /// Appends a face: its corners in boundary order (counter-clockwise seen
    /// from outside), each a tail vertex and the id of the edge to the next.
    #[inline]
    pub fn face(&mut self, corners: impl IntoIterator<Item = (u32, u32)>) {
        let start = self.cv.len();
        for (v, e) in corners {
            self.cv.push(v);
            self.ce.push(e);
        }
        self.sizes.push((self.cv.len() - start) as u32);
    }

    /// Pairs the two sides of every edge id and builds the mesh. An id with
    /// one side or more than two is an operator bug, reported as
    /// [`MeshError::Invariant`] naming the operator.
    pub fn finish(self, name: &str) -> Result<Mesh> {
        check_output_size(name, self.cv.len(), self.pos.len())?;
        let mut first = vec![NONE; self.n_edge_ids];
        let mut tw = vec![0u32; self.cv.len()];
        for (c, &e) in self.ce.iter().enumerate() {
            crate::cancel::poll(c)?;
            let slot = &mut first[e as usize];
            match *slot {
                NONE => *slot = c as u32,
                PAIRED => return Err(MeshError::Invariant(format!("{name}: output edge {e} has more than two sides"))),
                o => {
                    tw[c] = o;
                    tw[o as usize] = c as u32;
                    *slot = PAIRED;
                }
            }
        }
        if let Some(e) = first.iter().position(|&s| s != NONE && s != PAIRED) {
            return Err(MeshError::Invariant(format!("{name}: output edge {e} has one side")));
        }
        Mesh::from_corner_twins(self.pos, &self.sizes, &self.cv, &tw)
    }
}

/// What every operator reads from its input: the half-edge columns, the
/// face layout and the face centroids.
pub(crate) struct Ctx<'a> {
    pub m: &'a Mesh,
    pub next: &'a [u32],
    pub prev: &'a [u32],
    pub vert: &'a [u32],
    pub face: &'a [u32],
    pub fl: FaceLayout,
    pub cen: Vec<DVec3>,
    pub nv: usize,
    pub ne: usize,
    pub nf: usize,
    pub nh: usize,
}

impl<'a> Ctx<'a> {
    pub fn new(m: &'a Mesh) -> Result<Ctx<'a>> {
        let (next, vert, face) = m.halfedge_columns();
        let fl = FaceLayout::new(m)?;
        let mut cen = vec![DVec3::ZERO; m.n_faces()];
        crate::schemes::hosts::face_centroids(m, &fl, &mut cen);
        crate::cancel::check()?;
        Ok(Ctx { m, next, prev: &m.he_prev, vert, face, fl, cen, nv: m.n_vertices(), ne: m.n_edges(), nf: m.n_faces(), nh: m.n_halfedges() })
    }

    #[inline]
    pub fn tail(&self, h: usize) -> u32 {
        self.vert[h]
    }
    #[inline]
    pub fn head(&self, h: usize) -> u32 {
        self.vert[h ^ 1]
    }
    #[inline]
    pub fn p(&self, v: u32) -> DVec3 {
        self.m.pos[v as usize]
    }
    #[inline]
    pub fn next(&self, h: usize) -> usize {
        self.next[h] as usize
    }
    /// The corners (half-edges) of face `f`, in cycle order.
    #[inline]
    pub fn corners(&self, f: usize) -> impl Iterator<Item = usize> + '_ {
        self.fl.corners(f).iter().map(|&h| h as usize)
    }
    /// The outgoing half-edges of `v` in rotation order (counter-clockwise
    /// seen from outside): `h, twin(prev h), …`.
    pub fn rotation(&self, v: usize) -> impl Iterator<Item = usize> + '_ {
        let s = self.m.v_out[v] as usize;
        let mut h = Some(s);
        std::iter::from_fn(move || {
            let c = h?;
            let n = (self.prev[c] ^ 1) as usize;
            h = (n != s).then_some(n);
            Some(c)
        })
    }
    /// The point a third of the way along half-edge `h` from its tail.
    #[inline]
    pub fn third(&self, h: usize) -> DVec3 {
        self.p(self.tail(h)).lerp(self.p(self.head(h)), 1.0 / 3.0)
    }
    #[inline]
    pub fn mid(&self, e: usize) -> DVec3 {
        (self.p(self.vert[2 * e]) + self.p(self.vert[2 * e + 1])) * 0.5
    }
    /// Unit normal of face `f` by Newell's method; zero for a degenerate
    /// face (two-gons, one-gons, zero area), so offsets along it vanish
    /// instead of turning into NaN.
    pub fn normal(&self, f: usize) -> DVec3 {
        let mut n = DVec3::ZERO;
        for h in self.corners(f) {
            n += self.p(self.tail(h)).cross(self.p(self.head(h)));
        }
        n.normalize_or_zero()
    }
}

/// Refuses an output of `v`, `e`, `f` elements that would exceed the memory
/// budget or 31-bit ids (`crate::budget`), before anything is allocated.
pub(crate) fn reserve(name: &str, m: &Mesh, v: usize, e: usize, f: usize) -> Result<()> {
    use crate::budget::{check, level_bytes, Counts};
    check_output_size(name, 2 * e, v)?;
    if f > crate::mesh::MAX_ELEMENTS {
        return Err(MeshError::InvalidArgument(format!("{name}: the output would have {f} faces, more than 31-bit ids allow")));
    }
    let out = Counts::plain(v as u64, e as u64, f as u64);
    check(name, &format!("an output of {v} vertices, {e} edges and {f} faces"), level_bytes(&Counts::of(m), &out))
}

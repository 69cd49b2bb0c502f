//! What the Conway operators read from their input ([`Ctx`]: the shared
//! [`In`] view and the face centroids) and their budget check; they build
//! their output with the shared keyed builder, [`crate::schemes::keyed::Out`]
//! (faces as corner lists `(tail vertex, edge id)`).

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use crate::schemes::hosts::check_output_size;
pub(crate) use crate::schemes::keyed::{In, Out};
use glam::DVec3;

/// What every operator reads from its input: the shared input view
/// ([`In`], reached through `Deref`) and the face centroids.
pub(crate) struct Ctx<'a> {
    pub i: In<'a>,
    pub cen: Vec<DVec3>,
}

impl<'a> std::ops::Deref for Ctx<'a> {
    type Target = In<'a>;
    fn deref(&self) -> &In<'a> {
        &self.i
    }
}

impl<'a> Ctx<'a> {
    pub fn new(m: &'a Mesh) -> Result<Ctx<'a>> {
        let i = In::new(m)?;
        let cen = i.centroids();
        crate::cancel::check()?;
        Ok(Ctx { i, cen })
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
}

/// Refuses an output of `v`, `e`, `f` elements that would exceed the memory
/// budget or 31-bit ids (`crate::budget`), before anything is allocated.
pub(crate) fn reserve(name: &str, m: &Mesh, v: usize, e: usize, f: usize) -> Result<()> {
    reserve_from(name, &crate::budget::Counts::of(m), v, e, f)
}

/// [`reserve`] from the input's counts (for a fused build whose input of
/// this step is never built).
pub(crate) fn reserve_from(name: &str, input: &crate::budget::Counts, v: usize, e: usize, f: usize) -> Result<()> {
    use crate::budget::{check, level_bytes, Counts};
    check_output_size(name, 2 * e, v)?;
    if f > crate::mesh::MAX_ELEMENTS {
        return Err(MeshError::InvalidArgument(format!("{name}: the output would have {f} faces, more than 31-bit ids allow")));
    }
    let out = Counts::plain(v as u64, e as u64, f as u64);
    check(name, &format!("an output of {v} vertices, {e} edges and {f} faces"), level_bytes(input, &out))
}

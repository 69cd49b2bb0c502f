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

/// How a keyed build ends: its mesh, or the dual of its mesh built
/// without it ([`Out::finish_dual`], for the compositions that end with a
/// dual: `t = dkd`, `j = da`, TopMod's "dual + X + dual").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Then {
    Mesh,
    Dual,
}

/// Output under construction (see the module docs).
#[cfg_attr(test, derive(Clone))]
pub(crate) struct Out {
    pub pos: Vec<DVec3>,
    sizes: Vec<u32>,
    cv: Vec<u32>,
    key: Vec<u32>,
    n_keys: usize,
    start: usize,
    /// Per output face, the input element it descends from, while a face
    /// parents trace records ([`crate::schemes::face_parents`]); `None`
    /// otherwise, so a plain build does no extra work.
    src: Option<Vec<u32>>,
    /// The source of the faces to come (set by [`Out::from_face`] and
    /// [`Out::from_vertex`]; `NONE` until set, which breaks the trace).
    cur: u32,
    /// The input's (V, F), given by [`Out::of`].
    input: Option<(usize, usize)>,
    /// The first `keep` output vertices are the input's vertices 0..keep.
    keep: usize,
    /// Explicit vertex sources after the kept ones (index = output vertex).
    vsrc: Option<Vec<u32>>,
}

impl Out {
    /// An output with these vertex positions and `n_keys` edges, expecting
    /// about `faces` faces and `corners` corners.
    pub fn new(pos: Vec<DVec3>, n_keys: usize, faces: usize, corners: usize) -> Out {
        let src = crate::schemes::face_parents::recording().then(|| Vec::with_capacity(faces));
        Out { pos, sizes: Vec::with_capacity(faces), cv: Vec::with_capacity(corners), key: Vec::with_capacity(corners), n_keys, start: 0, src, cur: NONE, input: None, keep: 0, vsrc: None }
    }

    /// Names the input this output is built from, for the face parents
    /// trace (a build without it records nothing usable).
    pub fn of(mut self, c: &In<'_>) -> Out {
        self.input = Some((c.nv, c.nf));
        self
    }

    /// The faces that follow descend from input face `f` (built inside it,
    /// or from one of its half-edges).
    #[inline]
    pub fn from_face(&mut self, f: usize) {
        self.cur = f as u32;
    }

    /// The faces that follow are born around input vertex `v` (their parent
    /// is the vertex's, see [`crate::schemes::face_parents`]).
    #[inline]
    pub fn from_vertex(&mut self, v: usize) {
        self.cur = crate::schemes::face_parents::VERT | v as u32;
    }

    /// The first `n` output vertices are the input's vertices 0..n.
    pub fn keeps_vertices(&mut self, n: usize) {
        self.keep = n;
    }

    /// Explicit origins of the output vertices (an input face id or
    /// `VERT | v`, per output vertex; entries below [`Out::keeps_vertices`]
    /// are ignored), computed only while a trace records.
    pub fn vertex_origins(&mut self, f: impl FnOnce() -> Vec<u32>) {
        if self.src.is_some() {
            self.vsrc = Some(f());
        }
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
        if let Some(s) = &mut self.src {
            s.push(self.cur);
        }
    }

    /// Pairs the two sides of every key and builds the mesh. Each key must
    /// be used by exactly two sides or by none (a key range may have gaps;
    /// one or three sides is an internal error: the scheme's arithmetic is
    /// wrong), in opposite directions (checked below), and the vertices must
    /// form disks (checked by [`Mesh::check_vertex_umbrellas`]).
    ///
    /// One pass over the corners, face by face, writes the half-edge columns
    /// directly: the key of a side names its edge, so the twin array, its
    /// symmetry check and the edge numbering that
    /// [`Mesh::from_corner_twins`] derives from it are not needed (they were
    /// 60-80 % of an operator's time). The numbering is the same as there:
    /// edges in the order of their first corner, that corner `2e`, its twin
    /// `2e + 1`; so is every other column (`tests::same_as_from_corner_twins`
    /// and every scheme test, which in test builds run both builders).
    pub fn finish(mut self, scheme: &str) -> Result<Mesh> {
        #[cfg(test)]
        let reference = self.clone().finish_by_twins(scheme);
        let trace = self.src.take().map(|s| (s, self.input, self.keep, self.vsrc.take()));
        let out = self.finish_direct(scheme);
        if let (Some((src, input, keep, vsrc)), Ok(m)) = (trace, &out) {
            crate::schemes::face_parents::record(step_of(m, src, input, keep, vsrc));
        }
        #[cfg(test)]
        match (&out, &reference) {
            (Ok(a), Ok(b)) => assert!(a == b, "{scheme}: the direct keyed builder differs from from_corner_twins"),
            (Err(_), Err(_)) => {}
            _ => panic!("{scheme}: direct builder {:?}, from_corner_twins {:?}", out.as_ref().err(), reference.as_ref().err()),
        }
        out
    }

    /// [`Out::finish`] or [`Out::finish_dual`].
    pub fn finish_then(self, scheme: &str, then: Then) -> Result<Mesh> {
        match then {
            Then::Mesh => self.finish(scheme),
            Then::Dual => self.finish_dual(scheme),
        }
    }

    fn finish_direct(self, scheme: &str) -> Result<Mesh> {
        let n = self.cv.len();
        let nv = self.pos.len();
        let nf = self.sizes.len();
        check_output_size(scheme, n, nv)?;
        crate::cancel::check()?;
        let bad = |k: u32| MeshError::Invariant(format!("{scheme}: output edge {k} does not have exactly two sides (a bug in the scheme)"));
        // slot[k]: 0 unused; after the first side (edge e, running to vertex
        // w) `e + 1 | w << 32`, so its twin's direction is checked when it
        // comes, without a pass of its own; DONE after the second. Zeroed
        // memory is mapped lazily, so gaps in the key range cost nothing.
        const DONE: u64 = u64::MAX;
        let mut slot = vec![0u64; self.n_keys];
        // every corner's side pairs with another one: n half-edges exactly
        let mut m = Mesh {
            pos: self.pos,
            v_out: vec![NONE; nv],
            he_next: vec![0; n],
            he_prev: vec![0; n],
            he_vert: vec![0; n],
            he_face: vec![0; n],
            f_start: vec![NONE; nf],
            f_hole: vec![false; nf],
        };
        let mut ne = 0u32;
        let mut c = 0usize;
        for (f, &size) in self.sizes.iter().enumerate() {
            crate::cancel::poll(f)?;
            if size == 0 {
                return Err(MeshError::EmptyFace { face: f });
            }
            let (s, e) = (c, c + size as usize);
            let mut first = NONE;
            let mut last = NONE;
            for c in s..e {
                let k = self.key[c];
                let v = self.cv[c];
                let w = self.cv[if c + 1 < e { c + 1 } else { s }];
                let sl = slot.get_mut(k as usize).ok_or_else(|| bad(k))?;
                let h = match *sl {
                    0 => {
                        // 2 * ne < n while corners remain: no overflow (check_output_size)
                        ne += 1;
                        *sl = ne as u64 | (w as u64) << 32;
                        2 * (ne - 1)
                    }
                    DONE => return Err(bad(k)),
                    o => {
                        *sl = DONE;
                        let h = 2 * (o as u32 - 1) + 1;
                        // twins run between the same vertices in opposite
                        // directions: this side leaves the first one's head
                        // and runs to its tail
                        if (o >> 32) as u32 != v || m.he_vert.get((h ^ 1) as usize) != Some(&w) {
                            return Err(opposite(scheme, h / 2));
                        }
                        h
                    }
                };
                if h as usize >= n {
                    return Err(bad(k)); // more edges than half the corners: some key has one side
                }
                let vo = m.v_out.get_mut(v as usize).ok_or_else(|| MeshError::InvalidArgument(format!("face {f}: corner {c} refers to vertex {v} out of range")))?;
                if *vo == NONE {
                    *vo = h; // the first corner of each vertex, as from_corner_twins
                }
                m.he_vert[h as usize] = v;
                m.he_face[h as usize] = f as u32;
                if last == NONE {
                    first = h;
                } else {
                    m.he_next[last as usize] = h;
                    m.he_prev[h as usize] = last;
                }
                last = h;
            }
            m.he_next[last as usize] = first;
            m.he_prev[first as usize] = last;
            m.f_start[f] = first;
            c = e;
        }
        if 2 * ne as usize != n {
            let k = slot.iter().position(|&s| s != 0 && s != DONE).unwrap_or(0);
            return Err(bad(k as u32));
        }
        crate::cancel::check()?;
        if let Some(v) = m.v_out.iter().position(|&o| o == NONE) {
            return Err(MeshError::InvalidArgument(format!("vertex {v} is not used by any face")));
        }
        crate::cancel::check()?;
        m.check_vertex_umbrellas()?;
        Ok(m)
    }

    /// The builder before `finish_direct`: a twin per corner by key, then
    /// [`Mesh::from_corner_twins`]. Test builds run it beside the direct one.
    #[cfg(test)]
    fn finish_by_twins(self, scheme: &str) -> Result<Mesh> {
        check_output_size(scheme, self.cv.len(), self.pos.len())?;
        const DONE: u32 = NONE - 1;
        let n = self.cv.len();
        let mut first = vec![NONE; self.n_keys];
        let mut tw = vec![NONE; n];
        let bad = |k: u32| MeshError::Invariant(format!("{scheme}: output edge {k} does not have exactly two sides (a bug in the scheme)"));
        for (c, &k) in self.key.iter().enumerate() {
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
        Mesh::from_corner_twins(self.pos, &self.sizes, &self.cv, &tw)
    }
}

/// The trace step of a finished build: face sources as recorded, vertex
/// sources kept, explicit, or else those of the face of the vertex's first
/// corner (see [`crate::schemes::face_parents`]); `None` when the build did
/// not name its input or left a face without a source.
fn step_of(m: &Mesh, face: Vec<u32>, input: Option<(usize, usize)>, keep: usize, vsrc: Option<Vec<u32>>) -> Option<crate::schemes::face_parents::Step> {
    let hf = m.halfedge_columns().2;
    step_by(m.n_vertices(), |w| hf[m.v_out[w] as usize], face, input, keep, vsrc)
}

/// [`step_of`] for an output of `nv` vertices whose first corners lie in
/// the faces `first_face(w)`.
fn step_by(nv: usize, first_face: impl Fn(usize) -> u32, face: Vec<u32>, input: Option<(usize, usize)>, keep: usize, vsrc: Option<Vec<u32>>) -> Option<crate::schemes::face_parents::Step> {
    use crate::schemes::face_parents::{Step, VERT};
    let (in_v, in_f) = input?;
    // a source out of range is a bug in a scheme's annotation: record
    // nothing (the data is dropped with a warning) rather than panic later
    let ok = |s: u32| if s & VERT != 0 { ((s & !VERT) as usize) < in_v } else { (s as usize) < in_f };
    if !face.iter().all(|&s| ok(s)) || keep > in_v || vsrc.as_ref().is_some_and(|v| v.len() != nv) {
        return None;
    }
    let vertex: Vec<u32> = (0..nv)
        .map(|w| {
            if w < keep {
                VERT | w as u32
            } else if let Some(v) = &vsrc {
                v[w]
            } else {
                face[first_face(w) as usize]
            }
        })
        .collect();
    vertex.iter().all(|&s| ok(s)).then_some(Step { in_v, in_f, face, vertex })
}

/// The error of a key whose two sides run the same way.
fn opposite(scheme: &str, e: u32) -> MeshError {
    MeshError::Invariant(format!("{scheme}: output edge {e} has its two sides in the same direction (a bug in the scheme)"))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;

    /// Faces by hand whose keys pair sides wrongly: each builder refuses them.
    #[test]
    fn refuses_bad_keys() {
        let pos = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
        // a triangle and its reverse, keys per side: a valid sphere of two triangles
        let build = |keys: [u32; 6], n_keys: usize| {
            let mut o = Out::new(pos.clone(), n_keys, 2, 6);
            o.face([(0, keys[0]), (1, keys[1]), (2, keys[2])]);
            o.face([(0, keys[3]), (2, keys[4]), (1, keys[5])]);
            o.finish("test")
        };
        let ok = build([0, 1, 2, 2, 1, 0], 3).unwrap();
        assert_eq!((ok.n_vertices(), ok.n_edges(), ok.n_faces()), (3, 3, 2));
        assert!(build([0, 1, 2, 0, 1, 2], 3).is_err()); // sides paired in the same direction
        assert!(build([0, 1, 2, 2, 1, 1], 3).is_err()); // key 1 three times, key 0 once
        assert!(build([0, 1, 2, 2, 1, 3], 4).is_err()); // keys 0 and 3 once each
        assert!(build([0, 1, 2, 2, 1, 9], 3).is_err()); // key out of range
    }

    /// The direct builder gives the same mesh as from_corner_twins (every
    /// column, hence every export) on outputs with self-loops, two-gons and
    /// genus; test builds also compare the two inside every `finish`.
    #[test]
    fn same_as_from_corner_twins() {
        use crate::schemes::hosts::test_meshes::*;
        let seeds = [primitives::dodecahedron(), primitives::torus(6, 4, 1.0, 0.4).unwrap(), cube_with_self_loop(), cube_with_two_gon(), sierpinski_tetrahedron()];
        for m in &seeds {
            for notation in ["d", "a", "k", "g", "c", "u", "w", "p", "q", "l", "r", "t", "s", "b"] {
                let out = crate::schemes::conway::conway(notation, Some(m)).unwrap();
                out.validate().unwrap();
                assert_eq!(out.genus(), m.genus(), "{notation}");
            }
            let bc = crate::schemes::topmod::doo_sabin_bc_new::doo_sabin_bc_new(m, 1.0, 1.0).unwrap();
            bc.validate().unwrap();
        }
    }
}

mod dual;
#[cfg(test)]
mod hashes;

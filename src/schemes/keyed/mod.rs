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

/// Output under construction (see the module docs). Each face is laid
/// into the half-edge columns as soon as it is closed ([`Out::end`]), so
/// no corner list is kept (issue 16: the list and its second pass were a
/// fifth of the bytes a build touched, and fresh pages cost their zeroing).
pub(crate) struct Out {
    pub pos: Vec<DVec3>,
    /// The output's columns so far: edge e's half-edges `2e, 2e + 1` exist
    /// from its first side on.
    he_next: Vec<u32>,
    he_prev: Vec<u32>,
    he_vert: Vec<u32>,
    he_face: Vec<u32>,
    v_out: Vec<u32>,
    f_start: Vec<u32>,
    /// slot[k]: 0 before key k's first side; after it (edge e, running to
    /// vertex w) `e + 1 | w << 32`, so the second side's direction is
    /// checked when it comes; DONE after the second. Zeroed memory is
    /// mapped lazily, so gaps in the key range cost little.
    slot: Vec<u64>,
    ne: u32,
    /// Corners laid so far.
    nc: usize,
    /// The open face's corners (vertex, key).
    buf: Vec<(u32, u32)>,
    /// The first error met (reported by `finish`).
    err: Option<MeshError>,
    /// The largest vertex a corner named, with its face and corner (checked
    /// against the final positions by `finish`: schemes may add positions
    /// while they add faces).
    max_v: Option<(u32, usize, usize)>,
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
    /// Test builds keep the faces for the reference builder.
    #[cfg(test)]
    rec: (Vec<u32>, Vec<u32>, Vec<u32>),
}

/// `slot` after a key's second side.
const DONE: u64 = u64::MAX;

impl Out {
    /// An output with these vertex positions and `n_keys` edges, expecting
    /// about `faces` faces and `corners` corners.
    pub fn new(pos: Vec<DVec3>, n_keys: usize, faces: usize, corners: usize) -> Out {
        let src = crate::schemes::face_parents::recording().then(|| Vec::with_capacity(faces));
        let col = || Vec::with_capacity(corners);
        Out {
            v_out: vec![NONE; pos.len()],
            pos,
            he_next: col(),
            he_prev: col(),
            he_vert: col(),
            he_face: col(),
            f_start: Vec::with_capacity(faces),
            slot: vec![0; n_keys],
            ne: 0,
            nc: 0,
            buf: Vec::new(),
            err: None,
            max_v: None,
            src,
            cur: NONE,
            input: None,
            keep: 0,
            vsrc: None,
            #[cfg(test)]
            rec: (Vec::new(), Vec::new(), Vec::new()),
        }
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
        self.buf.push((v, key));
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

    /// Closes the current face and lays it into the columns.
    #[inline]
    pub fn end(&mut self) {
        let f = self.f_start.len();
        #[cfg(test)]
        {
            self.rec.0.push(self.buf.len() as u32);
            self.rec.1.extend(self.buf.iter().map(|c| c.0));
            self.rec.2.extend(self.buf.iter().map(|c| c.1));
        }
        if let Some(s) = &mut self.src {
            s.push(self.cur);
        }
        if self.err.is_none() {
            if let Err(e) = self.lay(f) {
                self.err = Some(e);
            }
        }
        if self.f_start.len() == f {
            self.f_start.push(NONE); // a face that failed: the build is refused anyway
        }
        self.nc += self.buf.len();
        self.buf.clear();
    }

    /// Face `f` (the open one) into the columns: per corner, the half-edge
    /// its key names (the key's first side opens edge `ne`: `2 ne`, its
    /// second side is the twin), linked in the face's order.
    fn lay(&mut self, f: usize) -> Result<()> {
        let n = self.buf.len();
        if n == 0 {
            return Err(MeshError::EmptyFace { face: f });
        }
        let (mut first, mut last) = (NONE, NONE);
        for c in 0..n {
            let (v, k) = self.buf[c];
            let w = self.buf[if c + 1 < n { c + 1 } else { 0 }].0;
            let sl = self.slot.get_mut(k as usize).ok_or(Bad::Key(k))?;
            let h = match *sl {
                0 => {
                    self.ne += 1;
                    *sl = self.ne as u64 | (w as u64) << 32;
                    for col in [&mut self.he_next, &mut self.he_prev, &mut self.he_vert, &mut self.he_face] {
                        col.extend([0, 0]);
                    }
                    2 * (self.ne - 1)
                }
                DONE => return Err(Bad::Key(k).into()),
                o => {
                    *sl = DONE;
                    let h = 2 * (o as u32 - 1) + 1;
                    // twins run between the same vertices in opposite
                    // directions: this side leaves the first one's head
                    // and runs to its tail
                    if (o >> 32) as u32 != v || self.he_vert[(h ^ 1) as usize] != w {
                        return Err(Bad::Direction(h / 2).into());
                    }
                    h
                }
            };
            let vi = v as usize;
            if vi >= self.v_out.len() {
                // a vertex beyond the positions given so far (checked by `finish`)
                if self.max_v.map_or(true, |m| v > m.0) {
                    self.max_v = Some((v, f, self.nc + c));
                }
                self.v_out.resize(vi + 1, NONE);
            }
            if self.v_out[vi] == NONE {
                self.v_out[vi] = h; // the first corner of each vertex, as from_corner_twins
            }
            self.he_vert[h as usize] = v;
            self.he_face[h as usize] = f as u32;
            if last == NONE {
                first = h;
            } else {
                self.he_next[last as usize] = h;
                self.he_prev[h as usize] = last;
            }
            last = h;
        }
        self.he_next[last as usize] = first;
        self.he_prev[first as usize] = last;
        self.f_start.push(first);
        Ok(())
    }

    /// Pairs the two sides of every key and builds the mesh. Each key must
    /// be used by exactly two sides or by none (a key range may have gaps;
    /// one or three sides is an internal error: the scheme's arithmetic is
    /// wrong), in opposite directions (checked below), and the vertices must
    /// form disks (checked by [`Mesh::check_vertex_umbrellas`]).
    ///
    /// The half-edge columns are written as faces close ([`Out::end`]), face
    /// by face in one pass: the key of a side names its edge, so the twin array, its
    /// symmetry check and the edge numbering that
    /// [`Mesh::from_corner_twins`] derives from it are not needed (they were
    /// 60-80 % of an operator's time). The numbering is the same as there:
    /// edges in the order of their first corner, that corner `2e`, its twin
    /// `2e + 1`; so is every other column (`tests::same_as_from_corner_twins`
    /// and every scheme test, which in test builds run both builders).
    pub fn finish(mut self, scheme: &str) -> Result<Mesh> {
        #[cfg(test)]
        let reference = finish_by_twins(scheme, self.pos.clone(), &self.rec.0, &self.rec.1, &self.rec.2, self.slot.len());
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

    fn finish_direct(self, scheme: &str) -> Result<Mesh> {
        let (n, nv, nf) = (self.nc, self.pos.len(), self.f_start.len());
        check_output_size(scheme, n, nv)?;
        crate::cancel::check()?;
        if let Some(e) = self.err {
            return Err(match e {
                MeshError::Invariant(s) if s.starts_with(BAD) => MeshError::Invariant(format!("{scheme}{s}")),
                e => e,
            });
        }
        if let Some((v, f, c)) = self.max_v.filter(|m| m.0 as usize >= nv) {
            return Err(MeshError::InvalidArgument(format!("face {f}: corner {c} refers to vertex {v} out of range")));
        }
        // every corner's side pairs with another one: n half-edges exactly
        if 2 * self.ne as usize != n {
            let k = self.slot.iter().position(|&s| s != 0 && s != DONE).unwrap_or(0);
            return Err(MeshError::Invariant(format!("{scheme}{BAD}{}", Bad::Key(k as u32).what())));
        }
        let mut v_out = self.v_out;
        v_out.resize(nv, NONE);
        if let Some(v) = v_out.iter().position(|&o| o == NONE) {
            return Err(MeshError::InvalidArgument(format!("vertex {v} is not used by any face")));
        }
        let m = Mesh { pos: self.pos, v_out, he_next: self.he_next, he_prev: self.he_prev, he_vert: self.he_vert, he_face: self.he_face, f_start: self.f_start, f_hole: vec![false; nf] };
        crate::cancel::check()?;
        m.check_vertex_umbrellas()?;
        Ok(m)
    }

}

/// The builder before the direct one: a twin per corner by key, then
/// [`Mesh::from_corner_twins`]. Test builds run it beside the direct one.
#[cfg(test)]
fn finish_by_twins(scheme: &str, pos: Vec<DVec3>, sizes: &[u32], cv: &[u32], key: &[u32], n_keys: usize) -> Result<Mesh> {
    check_output_size(scheme, cv.len(), pos.len())?;
    const DONE: u32 = NONE - 1;
    let n = cv.len();
    let mut first = vec![NONE; n_keys];
    let mut tw = vec![NONE; n];
    let bad = |k: u32| MeshError::Invariant(format!("{scheme}: output edge {k} does not have exactly two sides (a bug in the scheme)"));
    for (c, &k) in key.iter().enumerate() {
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
    Mesh::from_corner_twins(pos, sizes, cv, &tw)
}

/// A scheme's wrong arithmetic, found while a face is laid (its message
/// gets the scheme's name in `finish`).
enum Bad {
    /// A key with other than two sides.
    Key(u32),
    /// An edge whose two sides run the same way.
    Direction(u32),
}

/// Marks the messages of [`Bad`] until `finish` names the scheme.
const BAD: &str = ": output edge ";

impl Bad {
    fn what(&self) -> String {
        match self {
            Bad::Key(k) => format!("{k} does not have exactly two sides (a bug in the scheme)"),
            Bad::Direction(e) => format!("{e} has its two sides in the same direction (a bug in the scheme)"),
        }
    }
}

impl From<Bad> for MeshError {
    fn from(b: Bad) -> MeshError {
        MeshError::Invariant(format!("{BAD}{}", b.what()))
    }
}

/// The trace step of a finished build: face sources as recorded, vertex
/// sources kept, explicit, or else those of the face of the vertex's first
/// corner (see [`crate::schemes::face_parents`]); `None` when the build did
/// not name its input or left a face without a source.
fn step_of(m: &Mesh, face: Vec<u32>, input: Option<(usize, usize)>, keep: usize, vsrc: Option<Vec<u32>>) -> Option<crate::schemes::face_parents::Step> {
    use crate::schemes::face_parents::{Step, VERT};
    let (in_v, in_f) = input?;
    // a source out of range is a bug in a scheme's annotation: record
    // nothing (the data is dropped with a warning) rather than panic later
    let ok = |s: u32| if s & VERT != 0 { ((s & !VERT) as usize) < in_v } else { (s as usize) < in_f };
    if !face.iter().all(|&s| ok(s)) || keep > in_v || vsrc.as_ref().is_some_and(|v| v.len() != m.n_vertices()) {
        return None;
    }
    let hf = m.halfedge_columns().2;
    let vertex: Vec<u32> = (0..m.n_vertices())
        .map(|w| {
            if w < keep {
                VERT | w as u32
            } else if let Some(v) = &vsrc {
                v[w]
            } else {
                face[hf[m.v_out[w] as usize] as usize]
            }
        })
        .collect();
    vertex.iter().all(|&s| ok(s)).then_some(Step { in_v, in_f, face, vertex })
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
        let mut c = crate::mesh::zeroed_points(self.nf);
        crate::schemes::hosts::face_centroids(self.m, &self.fl, &mut c);
        c
    }
    /// Unit normal of every face (Newell's; zero for a degenerate face).
    pub fn normals(&self) -> Vec<DVec3> {
        (0..self.nf).map(|f| self.m.face_unit_normal(crate::FaceId(f as u32))).collect()
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

#[cfg(test)]
mod hashes;

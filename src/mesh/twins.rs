//! Lossless flat arrays: the twin of every exported corner, and the
//! constructor that rebuilds exactly the mesh those arrays describe.
//!
//! A polygon list alone is ambiguous as soon as several face sides join the
//! same two vertices (multi-edges, self-loops): [`Mesh::from_polygons`] pairs
//! them in order of appearance, which need not be how the mesh was connected.
//! `face_sizes` + `face_indices` + [`Mesh::corner_twins`] are not ambiguous.
//!
//! # Encoding
//! Corners are numbered as in [`Mesh::to_polygons`]: every non-hole face in
//! face order, from its first corner. `twins[c]` is the corner on the other
//! side of the edge that starts at corner `c` (it starts where `c`'s side
//! ends), `-1` when that other side is a corner of a hole face (a boundary
//! side), or `-2` when `c` is the lone corner of a point-sphere (no edge
//! starts there). The two are told apart because a one-gon bounded by a
//! self-loop whose other side is a hole (an operator can leave one) is also
//! a size-1 face whose vertex is in no other exported face.
//!
//! # Canonical hole faces
//! [`Mesh::from_corner_twins_i64`] re-creates hole faces from the `-1` sides:
//! each boundary loop becomes one hole face, numbered after all given faces,
//! in order of the loop's lowest boundary corner; a hole's first corner is the
//! twin of that lowest boundary corner. The round trip `corner_twins` → rebuild is exact for every
//! mesh in which each edge has a non-hole face on at least one side and each
//! vertex meets at most one hole corner, which holds for every mesh made by
//! `close_boundaries=True` and the operators; edge and half-edge ids are
//! renumbered by first exported corner, as every constructor does.

use super::{Mesh, BuildOptions, NONE, MAX_ELEMENTS};
#[cfg(test)]
use super::FaceStart;
use crate::error::{MeshError, Result};
use glam::DVec3;
use std::borrow::Cow;

impl Mesh {
    /// The twin corner of every exported corner, aligned with
    /// `to_polygons().indices`; `-1` for a boundary side (twin in a hole face),
    /// `-2` for a point-sphere's lone corner. See the module docs.
    pub fn corner_twins(&self) -> Vec<i64> {
        use rayon::prelude::*;
        const BLOCK: usize = 4096;
        let nf = self.n_faces();
        let next = &self.he_next;
        // walk 1, per block of faces in parallel: every half-edge's exported
        // corner counted from its block's first, and the block's corner count
        let mut pos_of = vec![NONE; self.n_halfedges()];
        let counts: Vec<u32> = {
            let p = crate::schemes::hosts::SyncPtr(pos_of.as_mut_ptr());
            (0..nf.div_ceil(BLOCK))
                .into_par_iter()
                .map(|b| {
                    let mut k = 0u32;
                    for f in b * BLOCK..((b + 1) * BLOCK).min(nf) {
                        let s = self.f_start[f];
                        if self.f_hole[f] {
                            continue;
                        }
                        if s & super::POINT != 0 {
                            k += 1;
                            continue;
                        }
                        let mut h = s;
                        loop {
                            // SAFETY: every half-edge belongs to one face, whose block alone writes it.
                            unsafe { *p.get().add(h as usize) = k };
                            k += 1;
                            h = next[h as usize];
                            if h == s {
                                break;
                            }
                        }
                    }
                    k
                })
                .collect()
        };
        let mut base = Vec::with_capacity(counts.len() + 1);
        let mut acc = 0u32;
        base.push(0);
        for c in &counts {
            acc += c;
            base.push(acc);
        }
        // walk 2: each corner's twin, its block's base added
        let mut out = vec![0i64; acc as usize];
        let mut parts = Vec::with_capacity(counts.len());
        let mut rest = &mut out[..];
        for (b, &c) in counts.iter().enumerate() {
            let (head, tail) = std::mem::take(&mut rest).split_at_mut(c as usize);
            parts.push((b, head));
            rest = tail;
        }
        let face = &self.he_face;
        parts.into_par_iter().for_each(|(b, part)| {
            let mut k = 0;
            for f in b * BLOCK..((b + 1) * BLOCK).min(nf) {
                let s = self.f_start[f];
                if self.f_hole[f] {
                    continue;
                }
                if s & super::POINT != 0 {
                    part[k] = -2;
                    k += 1;
                    continue;
                }
                let mut h = s;
                loop {
                    let t = (h ^ 1) as usize;
                    let local = pos_of[t];
                    part[k] = if local == NONE { -1 } else { (base[face[t] as usize / BLOCK] + local) as i64 };
                    k += 1;
                    h = next[h as usize];
                    if h == s {
                        break;
                    }
                }
            }
        });
        out
    }

    /// [`Mesh::corner_twins`] as it was written first, sequentially: the reference of its test.
    #[cfg(test)]
    pub(crate) fn corner_twins_sequential(&self) -> Vec<i64> {
        let mut pos_of = vec![NONE; self.n_halfedges()];
        let mut k = 0u32;
        for f in self.faces() {
            if self.is_hole(f) {
                continue;
            }
            match self.face_start(f) {
                FaceStart::Point(_) => k += 1,
                FaceStart::Halfedge(_) => {
                    for h in self.face_halfedges(f) {
                        pos_of[h.idx()] = k;
                        k += 1;
                    }
                }
            }
        }
        let mut out = Vec::with_capacity(k as usize);
        for f in self.faces() {
            if self.is_hole(f) {
                continue;
            }
            match self.face_start(f) {
                FaceStart::Point(_) => out.push(-2),
                FaceStart::Halfedge(_) => {
                    for h in self.face_halfedges(f) {
                        let t = pos_of[h.twin().idx()];
                        out.push(if t == NONE { -1 } else { t as i64 });
                    }
                }
            }
        }
        out
    }

    /// Rebuilds a mesh from positions, face sizes, flat corner vertices and
    /// [`Mesh::corner_twins`] (all as the user passed them, checked here):
    /// same faces, same corner order, the same corners joined by edges, hole
    /// faces re-created canonically (module docs).
    ///
    /// Rejects, naming the corner and its face: twins out of range, a corner
    /// its own twin, asymmetric twins, twins not running between the same two
    /// vertices in opposite directions, boundary sides whose holes would be
    /// ambiguous; and every input error of [`Mesh::from_polygons`] about
    /// positions, sizes and indices.
    pub fn from_corner_twins_i64(positions: Vec<DVec3>, sizes: &[i64], indices: &[i64], twins: &[i64]) -> Result<Mesh> {
        check_twins_size(positions.len(), indices.len(), sizes.len())?;
        if let Some((sizes_u, verts, twin)) = closed_fast(&positions, sizes, indices, twins)? {
            let holes = vec![false; sizes_u.len()];
            return Mesh::build(positions, &sizes_u, &verts, &twin, holes, true);
        }
        Self::from_corner_twins_i64_general(positions, sizes, indices, twins)
    }

    /// [`Mesh::from_corner_twins_i64`] with int32 indices and twins (as a
    /// PLY file stores them), without an int64 copy of either unless the
    /// mesh has holes or point-spheres or the input is refused.
    pub fn from_corner_twins_i32(positions: Vec<DVec3>, sizes: &[i64], indices: &[i32], twins: &[i32]) -> Result<Mesh> {
        check_twins_size(positions.len(), indices.len(), sizes.len())?;
        if let Some((sizes_u, verts, twin)) = closed_fast(&positions, sizes, indices, twins)? {
            let holes = vec![false; sizes_u.len()];
            return Mesh::build(positions, &sizes_u, &verts, &twin, holes, true);
        }
        let wide = |a: &[i32]| a.iter().map(|&x| x as i64).collect::<Vec<i64>>();
        Self::from_corner_twins_i64_general(positions, sizes, &wide(indices), &wide(twins))
    }

    /// [`Mesh::from_corner_twins_i64`] for every input (holes, point-spheres,
    /// errors), sequential: what the closed fast path falls back to.
    fn from_corner_twins_i64_general(positions: Vec<DVec3>, sizes: &[i64], indices: &[i64], twins: &[i64]) -> Result<Mesh> {
        let nv = positions.len();
        let n = indices.len();
        if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite { vertex: v });
        }
        let mut offsets = Vec::with_capacity(sizes.len() + 1);
        offsets.push(0usize);
        for (f, &s) in sizes.iter().enumerate() {
            if s <= 0 {
                return Err(if s == 0 {
                    MeshError::EmptyFace { face: f }
                } else {
                    MeshError::InvalidArgument(format!("face {f} has negative size {s}"))
                });
            }
            // checked: user sizes near 2^63 would wrap the sum
            let acc = offsets[f].checked_add(s as usize).ok_or_else(|| {
                MeshError::InvalidArgument(format!("face sizes add up to more than the {n} face indices given"))
            })?;
            offsets.push(acc);
        }
        if offsets[sizes.len()] != n {
            return Err(MeshError::InvalidArgument(format!(
                "face sizes add up to {} but {n} face indices were given",
                offsets[sizes.len()]
            )));
        }
        if twins.len() != n {
            return Err(MeshError::InvalidArgument(format!("twins: {} entries for {n} face indices", twins.len())));
        }
        // face of every corner, and the corner after it in its face
        let mut face = vec![0u32; n];
        let mut next = vec![0u32; n];
        for f in 0..sizes.len() {
            let (s, e) = (offsets[f], offsets[f + 1]);
            for c in s..e {
                face[c] = f as u32;
                next[c] = if c + 1 == e { s } else { c + 1 } as u32;
            }
        }
        for (c, &i) in indices.iter().enumerate() {
            if i < 0 || i as usize >= nv {
                let f = face[c] as usize;
                return Err(MeshError::IndexOutOfRange { face: f, position: c - offsets[f], index: i, n_vertices: nv });
            }
        }
        let verts: Vec<u32> = indices.iter().map(|&i| i as u32).collect();
        let mut uses = vec![0u32; nv];
        for &v in &verts {
            uses[v as usize] += 1;
        }
        let head = |c: usize| verts[next[c] as usize];
        let is_point = |c: usize| twins[c] == -2;
        // --- the twins themselves
        // range first, so the symmetry check below can index by any twin
        if let Some(c) = twins.iter().position(|&t| t < -2 || t >= n as i64) {
            return Err(MeshError::InvalidArgument(format!(
                "twins: corner {c} of face {} has twin {}, out of range (-1 for a boundary side, -2 for a point-sphere, or 0..{n})",
                face[c], twins[c]
            )));
        }
        // a point-sphere is a face of one corner whose vertex is in no other face
        if let Some(c) = (0..n).find(|&c| twins[c] == -2 && (sizes[face[c] as usize] != 1 || uses[verts[c] as usize] != 1)) {
            return Err(MeshError::InvalidArgument(format!(
                "twins: corner {c} of face {} has twin -2 (a point-sphere) but {}",
                face[c],
                if sizes[face[c] as usize] != 1 { "its face has other corners".to_string() } else { format!("its vertex {} is in other faces", verts[c]) }
            )));
        }
        for (c, &t) in twins.iter().enumerate() {
            let f = face[c];
            if t < 0 {
                continue;
            }
            let t = t as usize;
            if t == c {
                return Err(MeshError::InvalidArgument(format!("twins: corner {c} of face {f} is its own twin")));
            }
            if twins[t] != c as i64 {
                return Err(MeshError::InvalidArgument(format!(
                    "twins: corner {c} of face {f} has twin {t}, but the twin of corner {t} (face {}) is {}, not {c}; twins must be symmetric",
                    face[t], twins[t]
                )));
            }
            if verts[t] != head(c) {
                return Err(MeshError::InvalidArgument(format!(
                    "twins: corner {c} of face {f} runs from vertex {} to {}, but its twin {t} (face {}) starts at vertex {}; twins must run between the same two vertices in opposite directions",
                    verts[c],
                    head(c),
                    face[t],
                    verts[t]
                )));
            }
        }
        // --- boundary sides (twin -1, not a point-sphere) and their holes
        let boundary: Vec<u32> = (0..n).filter(|&c| twins[c] == -1 && !is_point(c)).map(|c| c as u32).collect();
        let mut entering = vec![NONE; nv];
        let mut leaving = vec![NONE; nv];
        for &u in &boundary {
            let (a, b) = (verts[u as usize] as usize, head(u as usize) as usize);
            for (slot, v, what) in [(&mut leaving, a, "left"), (&mut entering, b, "entered")] {
                if slot[v] != NONE {
                    return Err(MeshError::InvalidArgument(format!(
                        "twins: vertex {v} is {what} by two boundary sides (corners {} of face {} and {u} of face {}, twin -1): the hole faces would be ambiguous",
                        slot[v], face[slot[v] as usize], face[u as usize]
                    )));
                }
                slot[v] = u;
            }
        }
        let mut sizes_u: Vec<u32> = sizes.iter().map(|&s| s as u32).collect();
        let mut corner_verts = verts.clone();
        let mut twin: Vec<u32> = twins.iter().map(|&t| if t < 0 { NONE } else { t as u32 }).collect();
        let mut seen = vec![false; n];
        for &u0 in &boundary {
            if seen[u0 as usize] {
                continue;
            }
            // the hole runs against the boundary: after the twin of side u
            // (a -> b) comes the twin of the side entering a
            let base = corner_verts.len();
            let mut u = u0;
            loop {
                seen[u as usize] = true;
                twin[u as usize] = corner_verts.len() as u32;
                twin.push(u);
                corner_verts.push(head(u as usize));
                let a = verts[u as usize] as usize;
                let side = u;
                u = entering[a];
                if u == NONE {
                    return Err(MeshError::InvalidArgument(format!(
                        "twins: the boundary side at corner {side} of face {} leaves vertex {a}, which no boundary side enters: the boundary is not a closed loop",
                        face[side as usize]
                    )));
                }
                if u == u0 {
                    break;
                }
            }
            sizes_u.push((corner_verts.len() - base) as u32);
        }
        let n_given = sizes.len();
        let mut m = Mesh::from_corner_twins(positions, &sizes_u, &corner_verts, &twin)?;
        for f in n_given..m.f_hole.len() {
            m.f_hole[f] = true;
        }
        Ok(m)
    }

    /// Whether the mesh has two edges between the same two distinct vertices.
    pub fn has_multi_edges(&self) -> bool {
        use rayon::prelude::*;
        // per vertex, the heads of its outgoing half-edges (self-loops aside, whose two
        // half-edges both leave it): a head met twice is a second edge to the same vertex.
        // In parallel and without a sort of every edge (that took 44 ms of an OBJ save of
        // 1M triangles, sequential).
        (0..self.n_vertices() as u32).into_par_iter().with_min_len(1 << 12).any(|v| {
            let mut few = [0u32; 16];
            let (mut k, mut many) = (0usize, Vec::new());
            for h in self.vertex_halfedges(super::VertexId(v)) {
                let w = self.head(h).0;
                if w == v {
                    continue;
                }
                if k < few.len() {
                    if few[..k].contains(&w) {
                        return true;
                    }
                    few[k] = w;
                    k += 1;
                } else {
                    many.push(w);
                }
            }
            // a vertex of valence above 16: all its heads sorted
            !many.is_empty() && {
                many.extend_from_slice(&few);
                many.sort_unstable();
                many.windows(2).any(|p| p[0] == p[1])
            }
        })
    }

    /// Whether a polygon list alone (OBJ, OFF) gives this mesh back:
    /// [`Mesh::from_polygons`] of the exports, with `allow_multi_edges` and
    /// `close_boundaries` where needed, reproduces the same twins and holes.
    /// Cheap (no rebuild) unless the mesh has self-loops, multi-edges or holes.
    pub fn polygons_are_lossless(&self) -> bool {
        if self.n_self_loops() == 0 && self.n_holes() == 0 && !self.has_multi_edges() {
            return true;
        }
        let (sizes, idx) = self.to_polygons().to_i64();
        let opts = BuildOptions { close_boundaries: self.n_holes() > 0, allow_multi_edges: true };
        match Mesh::from_polygons(self.pos.clone(), &sizes, &idx, opts) {
            Ok(m) => m.n_edges() == self.n_edges() && m.n_holes() == self.n_holes() && m.corner_twins() == self.corner_twins(),
            Err(_) => false,
        }
    }
}

/// The size limits of [`Mesh::from_corner_twins_i64`].
fn check_twins_size(nv: usize, n: usize, nf: usize) -> Result<()> {
    if nv > MAX_ELEMENTS || n > MAX_ELEMENTS / 2 || nf > MAX_ELEMENTS / 2 {
        return Err(MeshError::InvalidArgument(format!(
            "mesh too large: at most {MAX_ELEMENTS} vertices and {} corners",
            MAX_ELEMENTS / 2
        )));
    }
    Ok(())
}

/// The common case of [`Mesh::from_corner_twins_i64`], a closed mesh (every
/// twin a corner): checked and converted to the builder's columns in
/// parallel, `(sizes, vertices, twins)` ready for [`Mesh::build`] with the
/// twins vouched for. `None` when any twin is negative or any check fails:
/// the sequential path then handles holes and point-spheres and names the
/// problem. (With that path alone, rebuilding a 960k-quad torus took 154 ms
/// on one thread, of which the builder needs 63 ms; with this one, 88-105.)
fn closed_fast<'a, T: IndexColumn>(
    positions: &[DVec3],
    sizes: &[i64],
    indices: &'a [T],
    twins: &'a [T],
) -> Result<Option<(Vec<u32>, Cow<'a, [u32]>, Cow<'a, [u32]>)>> {
    use super::build::{first_bad_face, first_index};
    use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
    let (nv, n) = (positions.len(), indices.len());
    if twins.len() != n || first_index(positions, |p| !p.is_finite()).is_some() {
        crate::cancel::check()?;
        return Ok(None);
    }
    let mut offsets = Vec::with_capacity(sizes.len() + 1);
    let mut acc = 0u64;
    offsets.push(0u32);
    for &s in sizes {
        if s <= 0 || s as u64 > n as u64 - acc {
            return Ok(None);
        }
        acc += s as u64;
        offsets.push(acc as u32);
    }
    if acc != n as u64 {
        return Ok(None);
    }
    // range-checked (and int64 converted) in one pass each; a negative twin
    // (a boundary side or a point-sphere) is out of range here too
    let out = AtomicBool::new(false);
    let verts = T::as_u32(indices, nv, &out)?;
    let twin = T::as_u32(twins, n, &out)?;
    if out.load(Relaxed) {
        return Ok(None);
    }
    let sizes_u = crate::cancel::par_collect(sizes.len(), |f| sizes[f] as u32)?;
    let bad = first_bad_face(&offsets, &verts, &twin, nv);
    // a cancelled search finds nothing: never build on it
    crate::cancel::check()?;
    Ok(bad.is_none().then_some((sizes_u, verts, twin)))
}

/// A column of indices or twins as [`closed_fast`] reads it: `u32` values,
/// with `out` set when one is outside `0..end`.
trait IndexColumn: Copy + Sync + Sized {
    fn as_u32<'a>(s: &'a [Self], end: usize, out: &std::sync::atomic::AtomicBool) -> Result<Cow<'a, [u32]>>;
}

impl IndexColumn for i64 {
    /// Converted in one parallel pass.
    fn as_u32<'a>(s: &'a [i64], end: usize, out: &std::sync::atomic::AtomicBool) -> Result<Cow<'a, [u32]>> {
        let col = crate::cancel::par_collect(s.len(), |c| {
            let x = s[c];
            if x < 0 || x >= end as i64 {
                out.store(true, std::sync::atomic::Ordering::Relaxed);
            }
            x as u32
        })?;
        Ok(Cow::Owned(col))
    }
}

impl IndexColumn for i32 {
    /// Read in place: checked in one parallel pass, then the same bits read
    /// as `u32` (no copy: a 1M-triangle PLY's two int32 columns would have
    /// been 24 MB of fresh pages).
    fn as_u32<'a>(s: &'a [i32], end: usize, out: &std::sync::atomic::AtomicBool) -> Result<Cow<'a, [u32]>> {
        if super::build::first_index(s, |&x| x < 0 || x as i64 >= end as i64).is_some() {
            out.store(true, std::sync::atomic::Ordering::Relaxed);
        }
        crate::cancel::check()?;
        // SAFETY: i32 and u32 have the same size and alignment and every bit
        // pattern is a valid u32; the slice borrows `s` for as long.
        Ok(Cow::Borrowed(unsafe { std::slice::from_raw_parts(s.as_ptr().cast::<u32>(), s.len()) }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;

    fn round_trip(m: &Mesh) -> Mesh {
        let p = m.to_polygons();
        let (sizes, idx) = p.to_i64();
        let back = Mesh::from_corner_twins_i64(m.positions().to_vec(), &sizes, &idx, &m.corner_twins()).unwrap();
        back.validate().unwrap();
        assert_eq!(back.to_polygons(), p);
        assert_eq!(back.corner_twins(), m.corner_twins());
        assert_eq!((back.n_edges(), back.n_holes(), back.genus()), (m.n_edges(), m.n_holes(), m.genus()));
        back
    }

    #[test]
    fn twins_round_trip_primitives_and_multi_edges() {
        let cube = primitives::cube();
        round_trip(&cube);
        assert!(cube.polygons_are_lossless());
        // a handle between two faces: two edges join the same vertex pair
        let mut h = cube.clone();
        let c1 = h.corner(crate::mesh::FaceId(0), 0).unwrap();
        let c2 = h.corner(crate::mesh::FaceId(1), 0).unwrap();
        h.insert_edge(c1, c2).unwrap();
        round_trip(&h);
        let s = crate::schemes::sqrt3::sqrt3(&h).unwrap();
        round_trip(&s);
        let mut p = Mesh::new();
        p.create_vertex(DVec3::ZERO).unwrap();
        assert_eq!(p.corner_twins(), vec![-2]);
        round_trip(&p);
        round_trip(&Mesh::new());
    }

    #[test]
    fn closed_fast_path_builds_what_the_general_path_builds() {
        // the fast path (every twin a corner) against the sequential one, on
        // closed meshes with multi-edges, self-loops, two-gons and any genus
        let mut checked = 0;
        for (name, m) in crate::schemes::hosts::test_meshes::corpus() {
            let tw = m.corner_twins();
            if m.n_holes() > 0 || tw.iter().any(|&t| t < 0) {
                continue;
            }
            let (sizes, idx) = m.to_polygons().to_i64();
            let pos = m.positions().to_vec();
            assert!(closed_fast(&pos, &sizes, &idx, &tw).unwrap().is_some(), "{name}");
            let fast = Mesh::from_corner_twins_i64(pos.clone(), &sizes, &idx, &tw).unwrap();
            let (idx32, tw32): (Vec<i32>, Vec<i32>) = (idx.iter().map(|&i| i as i32).collect(), tw.iter().map(|&t| t as i32).collect());
            let narrow = Mesh::from_corner_twins_i32(pos.clone(), &sizes, &idx32, &tw32).unwrap();
            let general = Mesh::from_corner_twins_i64_general(pos, &sizes, &idx, &tw).unwrap();
            assert_eq!(fast, general, "{name}");
            assert_eq!(narrow, general, "{name}");
            checked += 1;
        }
        assert!(checked >= 5, "only {checked} closed meshes in the corpus");
        // bad closed input falls back, so the general path names the problem
        let cube = primitives::cube();
        let (sizes, idx) = cube.to_polygons().to_i64();
        let mut tw = cube.corner_twins();
        tw.swap(0, 1);
        assert!(closed_fast(cube.positions(), &sizes, &idx, &tw).unwrap().is_none());
        let e = Mesh::from_corner_twins_i64(cube.positions().to_vec(), &sizes, &idx, &tw).unwrap_err().to_string();
        assert!(e.contains("twins: corner 0 of face 0"), "{e}");
        let mut bad = idx.clone();
        bad[5] = 8;
        let e = Mesh::from_corner_twins_i64(cube.positions().to_vec(), &sizes, &bad, &cube.corner_twins()).unwrap_err().to_string();
        assert!(e.contains("vertex index 8 at position"), "{e}");
        // int32 input: the same messages, and holes rebuilt as from int64
        let bad32: Vec<i32> = bad.iter().map(|&i| i as i32).collect();
        let tw32: Vec<i32> = cube.corner_twins().iter().map(|&t| t as i32).collect();
        let e32 = Mesh::from_corner_twins_i32(cube.positions().to_vec(), &sizes, &bad32, &tw32).unwrap_err().to_string();
        assert_eq!(e32, e);
        let open = ("open", crate::schemes::hosts::test_meshes::cube_with_hole());
        for (name, m) in crate::schemes::hosts::test_meshes::corpus().into_iter().chain([open]) {
            let ((sizes, i64s), tw) = (m.to_polygons().to_i64(), m.corner_twins());
            let i32s: Vec<i32> = i64s.iter().map(|&i| i as i32).collect();
            let tw32: Vec<i32> = tw.iter().map(|&t| t as i32).collect();
            let a = Mesh::from_corner_twins_i64(m.positions().to_vec(), &sizes, &i64s, &tw).unwrap();
            assert_eq!(Mesh::from_corner_twins_i32(m.positions().to_vec(), &sizes, &i32s, &tw32).unwrap(), a, "{name}");
        }
    }

    #[test]
    fn holes_are_recreated_canonically() {
        let pos = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let opts = BuildOptions { close_boundaries: true, allow_multi_edges: false };
        let m = Mesh::from_polygons(pos, &[3, 3], &[0, 1, 2, 0, 2, 3], opts).unwrap();
        assert_eq!(m.n_holes(), 1);
        let t = m.corner_twins();
        assert_eq!(t.iter().filter(|&&x| x == -1).count(), 4);
        round_trip(&m);
        assert!(m.polygons_are_lossless());
    }

    #[test]
    fn bad_twins_name_corner_and_face() {
        let m = primitives::tetrahedron();
        let (sizes, idx) = m.to_polygons().to_i64();
        let mut t = m.corner_twins();
        t.swap(0, 1);
        let e = Mesh::from_corner_twins_i64(m.positions().to_vec(), &sizes, &idx, &t).unwrap_err().to_string();
        assert!(e.contains("corner 0 of face 0"), "{e}");
        let mut t = m.corner_twins();
        t[5] = 99;
        let e = Mesh::from_corner_twins_i64(m.positions().to_vec(), &sizes, &idx, &t).unwrap_err().to_string();
        assert!(e.contains("corner 5 of face 1") && e.contains("out of range"), "{e}");
        let e = Mesh::from_corner_twins_i64(m.positions().to_vec(), &[i64::MAX, i64::MAX, 14], &idx, &m.corner_twins());
        assert!(e.is_err());
    }

    #[test]
    fn from_polygons_size_sum_does_not_wrap() {
        let pos = vec![DVec3::ZERO; 4];
        let idx = [0i64; 14];
        let e = Mesh::from_polygons(pos, &[i64::MAX, i64::MAX, 14], &idx, BuildOptions::default()).unwrap_err();
        assert!(e.to_string().contains("add up to"), "{e}");
    }
}

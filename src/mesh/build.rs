//! Construction: from polygons (with full validation of user input) and from
//! corners with explicit twins (the one-pass builder every bulk scheme uses).

use super::{Mesh, NONE, POINT, MAX_ELEMENTS};
use crate::error::{MeshError, Result};
use glam::DVec3;
use rayon::prelude::*;

/// Polygon faces as flat vertex indices plus one size per face, the layout
/// of `face_sizes` / `face_indices` exports.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolygonFaces {
    pub sizes: Vec<u32>,
    pub indices: Vec<u32>,
}

/// Options of [`Mesh::from_polygons`].
#[derive(Clone, Copy, Debug, Default)]
pub struct BuildOptions {
    /// Cap every boundary loop with a face marked as a hole (kept out of exports)
    /// instead of rejecting the open mesh.
    pub close_boundaries: bool,
    /// Accept an edge whose two vertices are shared by more than one pair of
    /// face sides, pairing them in order of appearance (a multi-edge). Without
    /// it such an edge is a non-manifold-edge error.
    pub allow_multi_edges: bool,
}

impl Mesh {
    /// Builds a mesh from positions and polygon faces given as flat indices and
    /// face sizes (both as the user passed them: `i64`, checked here).
    ///
    /// Rejects, naming the face/vertex: NaN/inf coordinates, empty faces, out
    /// of range indices, unreferenced vertices, an edge with more than two face
    /// sides, two faces traversing an edge the same way, non-manifold vertices,
    /// and boundaries unless `close_boundaries`.
    ///
    /// A face of size 1 whose vertex appears in no other face is a
    /// point-sphere; otherwise it is a one-gon bounded by a self-loop. Twins
    /// are found by vertex pair; an edge between `a` and `b` matches the one
    /// side going `a → b` with the one going `b → a`; self-loop sides at one
    /// vertex pair up in order of appearance.
    pub fn from_polygons(
        positions: Vec<DVec3>,
        sizes: &[i64],
        indices: &[i64],
        opts: BuildOptions,
    ) -> Result<Mesh> {
        let nv = positions.len();
        if nv > MAX_ELEMENTS || indices.len() > MAX_ELEMENTS / 2 {
            return Err(MeshError::InvalidArgument(format!(
                "mesh too large: at most {MAX_ELEMENTS} vertices and {} corners",
                MAX_ELEMENTS / 2
            )));
        }
        if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite { vertex: v });
        }
        // sizes and indices
        let mut offsets = Vec::with_capacity(sizes.len() + 1);
        offsets.push(0usize);
        for (f, &s) in sizes.iter().enumerate() {
            if s <= 0 {
                if s == 0 {
                    return Err(MeshError::EmptyFace { face: f });
                }
                return Err(MeshError::InvalidArgument(format!("face {f} has negative size {s}")));
            }
            offsets.push(offsets[f] + s as usize);
        }
        if *offsets.last().unwrap() != indices.len() {
            return Err(MeshError::InvalidArgument(format!(
                "face sizes add up to {} but {} face indices were given",
                offsets.last().unwrap(),
                indices.len()
            )));
        }
        let mut verts = Vec::with_capacity(indices.len());
        let mut face_of = Vec::with_capacity(indices.len());
        for f in 0..sizes.len() {
            for (k, &i) in indices[offsets[f]..offsets[f + 1]].iter().enumerate() {
                if i < 0 || i as usize >= nv {
                    return Err(MeshError::IndexOutOfRange { face: f, position: k, index: i, n_vertices: nv });
                }
                verts.push(i as u32);
                face_of.push(f as u32);
            }
        }
        let n = verts.len();
        // head vertex of every corner's side
        let mut head = vec![0u32; n];
        for f in 0..sizes.len() {
            let (s, e) = (offsets[f], offsets[f + 1]);
            for c in s..e {
                head[c] = verts[if c + 1 == e { s } else { c + 1 }];
            }
        }
        // corners per vertex: point-spheres are size-1 faces whose vertex is used once
        let mut uses = vec![0u32; nv];
        for &v in &verts {
            uses[v as usize] += 1;
        }
        if let Some(v) = uses.iter().position(|&u| u == 0) {
            return Err(MeshError::InvalidArgument(format!(
                "vertex {v} is not used by any face; remove unreferenced vertices first"
            )));
        }
        let is_point = |c: usize| -> bool {
            let f = face_of[c] as usize;
            offsets[f + 1] - offsets[f] == 1 && uses[verts[c] as usize] == 1
        };

        // --- pair corners into edges: bucket sides by their smaller vertex
        let mut bucket_start = vec![0u32; nv + 1];
        for c in 0..n {
            if !is_point(c) {
                bucket_start[verts[c].min(head[c]) as usize + 1] += 1;
            }
        }
        for v in 0..nv {
            bucket_start[v + 1] += bucket_start[v];
        }
        let mut fill = bucket_start.clone();
        let mut bucket = vec![0u32; bucket_start[nv] as usize];
        for c in 0..n {
            if !is_point(c) {
                let lo = verts[c].min(head[c]) as usize;
                bucket[fill[lo] as usize] = c as u32;
                fill[lo] += 1;
            }
        }
        let mut twin = vec![NONE; n];
        let mut unmatched: Vec<u32> = Vec::new();
        let mut group: Vec<(u32, u32)> = Vec::new(); // (other vertex, corner)
        for lo in 0..nv {
            let b = &bucket[bucket_start[lo] as usize..bucket_start[lo + 1] as usize];
            group.clear();
            group.extend(b.iter().map(|&c| {
                let (t, h) = (verts[c as usize], head[c as usize]);
                (if t as usize == lo { h } else { t }, c)
            }));
            group.sort_unstable();
            let mut i = 0;
            while i < group.len() {
                let hi = group[i].0;
                let mut j = i;
                while j < group.len() && group[j].0 == hi {
                    j += 1;
                }
                let sides = &group[i..j];
                pair_sides(lo as u32, hi, sides, &verts, &face_of, opts, &mut twin, &mut unmatched)?;
                i = j;
            }
        }

        // --- cap boundaries with hole faces
        let mut sizes_u: Vec<u32> = sizes.iter().map(|&s| s as u32).collect();
        let mut holes = vec![false; sizes.len()];
        if !unmatched.is_empty() {
            // twin corner t of boundary side u (a -> b) runs b -> a; the hole
            // continues at a with the twin of the boundary side entering a.
            let mut entering = vec![NONE; nv];
            for &u in &unmatched {
                let hv = head[u as usize] as usize;
                if entering[hv] != NONE {
                    return Err(MeshError::NonManifoldVertex { vertex: hv });
                }
                entering[hv] = u;
            }
            let mut seen = vec![false; n];
            for &u0 in &unmatched {
                if seen[u0 as usize] {
                    continue;
                }
                // walk the loop backwards along boundary sides
                let mut loop_sides = Vec::new();
                let mut u = u0;
                loop {
                    seen[u as usize] = true;
                    loop_sides.push(u);
                    let tail = verts[u as usize] as usize;
                    u = entering[tail];
                    if u == NONE {
                        return Err(MeshError::NonManifoldVertex { vertex: tail });
                    }
                    if u == u0 {
                        break;
                    }
                }
                // hole corners: twin of u starts at head(u); order so next(t_u) = t_{entering(tail u)}
                let base = verts.len();
                for (k, &u) in loop_sides.iter().enumerate() {
                    verts.push(head[u as usize]);
                    twin.push(u);
                    twin[u as usize] = (base + k) as u32;
                }
                sizes_u.push(loop_sides.len() as u32);
                holes.push(true);
            }
        }
        Mesh::build(positions, &sizes_u, &verts, &twin, holes)
    }

    /// The one-pass builder for schemes: faces as `sizes` + flat tail vertices
    /// (`corner_verts`), and for every corner the index of its twin corner (the
    /// corner of the other side of the edge that starts at it), or `u32::MAX`
    /// for the lone corner of a point-sphere face.
    ///
    /// Checks that twins are symmetric and run between the same two vertices in
    /// opposite directions, and that every vertex is manifold; all user input
    /// checks of [`Mesh::from_polygons`] are the caller's business.
    pub fn from_corner_twins(
        positions: Vec<DVec3>,
        sizes: &[u32],
        corner_verts: &[u32],
        twin: &[u32],
    ) -> Result<Mesh> {
        let holes = vec![false; sizes.len()];
        Mesh::build(positions, sizes, corner_verts, twin, holes)
    }

    fn build(positions: Vec<DVec3>, sizes: &[u32], verts: &[u32], twin: &[u32], f_hole: Vec<bool>) -> Result<Mesh> {
        let n = verts.len();
        let nv = positions.len();
        let nf = sizes.len();
        if twin.len() != n {
            return Err(MeshError::InvalidArgument(format!("{} twins for {n} corners", twin.len())));
        }
        if n > MAX_ELEMENTS || nv > MAX_ELEMENTS || nf > MAX_ELEMENTS {
            return Err(MeshError::InvalidArgument("mesh too large for 31-bit ids".into()));
        }
        let mut offsets = Vec::with_capacity(nf + 1);
        offsets.push(0u32);
        for (f, &s) in sizes.iter().enumerate() {
            if s == 0 {
                return Err(MeshError::EmptyFace { face: f });
            }
            offsets.push(offsets[f] + s);
        }
        if offsets[nf] as usize != n {
            return Err(MeshError::InvalidArgument(format!(
                "face sizes add up to {} but {n} corners were given",
                offsets[nf]
            )));
        }
        // every corner: a vertex in range and a symmetric twin that starts
        // where the corner's side ends (checked from both sides, this also
        // makes the twin end where the corner starts)
        let bad = (0..nf).into_par_iter().with_min_len(1024).find_first(|&f| {
            let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
            (s..e).any(|c| {
                let t = twin[c];
                let cn = if c + 1 == e { s } else { c + 1 };
                verts[c] as usize >= nv
                    || if t == NONE {
                        e - s != 1
                    } else {
                        t as usize >= n || t as usize == c || twin[t as usize] != c as u32 || verts[t as usize] != verts[cn]
                    }
            })
        });
        if let Some(f) = bad {
            let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
            let c = (s..e)
                .find(|&c| {
                    let t = twin[c];
                    verts[c] as usize >= nv || t == NONE || t as usize >= n || t as usize == c || twin[t as usize] != c as u32
                })
                .unwrap_or(s);
            return Err(MeshError::InvalidArgument(if verts[c] as usize >= nv {
                format!("face {f}: corner {c} refers to vertex {} out of range", verts[c])
            } else if twin[c] == NONE {
                format!("face {f}: a corner without twin must be the only corner of a point-sphere face")
            } else {
                format!("face {f}: corner {c} and its twin {} are not symmetric partners running between the same vertices in opposite directions", twin[c])
            }));
        }
        // half-edge ids: edges numbered by their first corner (2e), the twin gets 2e + 1
        let he_of = number_halfedges(twin);
        let nh = n - twin.iter().filter(|&&t| t == NONE).count();
        let mut m = Mesh {
            pos: positions,
            v_out: vec![NONE; nv],
            // every entry is written below; zeroed (calloc) memory is mapped
            // lazily, so its page faults are taken by the parallel fill
            he_next: vec![0; nh],
            he_prev: vec![0; nh],
            he_vert: vec![0; nh],
            he_face: vec![0; nh],
            f_start: vec![NONE; nf],
            f_hole,
        };
        // the half-edge columns, face by face in parallel. Writes are disjoint:
        // `he_of` is a bijection from the corners with a twin onto 0..nh, and
        // every half-edge is the `next` of exactly one corner.
        {
            let cols = [
                SyncPtr(m.he_next.as_mut_ptr()),
                SyncPtr(m.he_prev.as_mut_ptr()),
                SyncPtr(m.he_vert.as_mut_ptr()),
                SyncPtr(m.he_face.as_mut_ptr()),
            ];
            let f_start = SyncPtr(m.f_start.as_mut_ptr());
            (0..nf).into_par_iter().with_min_len(1024).for_each(|f| {
                let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
                if twin[s] == NONE {
                    return; // point-sphere face: set below
                }
                // SAFETY: see the block comment; f_start[f] is written by face f only.
                unsafe {
                    *f_start.at(f) = he_of[s];
                    for c in s..e {
                        let cn = if c + 1 == e { s } else { c + 1 };
                        let (h, hn) = (he_of[c] as usize, he_of[cn]);
                        *cols[0].at(h) = hn;
                        *cols[1].at(hn as usize) = h as u32;
                        *cols[2].at(h) = verts[c];
                        *cols[3].at(h) = f as u32;
                    }
                }
            });
        }
        // the first corner of each vertex, as documented for exports
        for (c, &v) in verts.iter().enumerate().rev() {
            if twin[c] != NONE {
                m.v_out[v as usize] = he_of[c];
            }
        }
        for f in 0..nf {
            let s = offsets[f] as usize;
            if twin[s] == NONE {
                let v = verts[s];
                if m.v_out[v as usize] != NONE {
                    return Err(MeshError::NonManifoldVertex { vertex: v as usize });
                }
                m.v_out[v as usize] = POINT | f as u32;
                m.f_start[f] = POINT | v;
            }
        }
        if let Some(v) = m.v_out.par_iter().position_first(|&o| o == NONE) {
            return Err(MeshError::InvalidArgument(format!("vertex {v} is not used by any face")));
        }
        m.check_vertex_umbrellas()?;
        Ok(m)
    }

    /// Every vertex's outgoing half-edges must form one rotation cycle (a disk).
    ///
    /// The rotation cycles partition the half-edges by tail, so the cycles
    /// through each vertex's `v_out` add up to all half-edges exactly when no
    /// vertex has a second one. Only when they do not is the culprit looked for.
    pub(crate) fn check_vertex_umbrellas(&self) -> Result<()> {
        let nh = self.n_halfedges();
        let walk = |v: usize| -> usize {
            let o = self.v_out[v];
            if o & POINT != 0 {
                return 0;
            }
            let mut h = o;
            let mut k = 0usize;
            loop {
                k += 1;
                h = self.he_prev[h as usize] ^ 1;
                if h == o || k > nh {
                    return k;
                }
            }
        };
        let total: usize = (0..self.n_vertices()).into_par_iter().with_min_len(4096).map(walk).sum();
        if total == nh {
            return Ok(());
        }
        let mut out_deg = vec![0usize; self.n_vertices()];
        for &v in &self.he_vert {
            out_deg[v as usize] += 1;
        }
        let v = (0..self.n_vertices()).find(|&v| walk(v) != out_deg[v]).unwrap_or(0);
        Err(MeshError::NonManifoldVertex { vertex: v })
    }
}

/// Half-edge id of every corner with a twin: edges numbered by their first
/// corner in corner order; that corner gets `2e`, its twin `2e + 1`.
fn number_halfedges(twin: &[u32]) -> Vec<u32> {
    let n = twin.len();
    let is_first = |c: usize| twin[c] != NONE && twin[c] as usize > c;
    // parallel exclusive scan of edge starts over fixed chunks
    let counts: Vec<u32> = (0..n.div_ceil(PAR_CHUNK))
        .into_par_iter()
        .map(|k| (k * PAR_CHUNK..((k + 1) * PAR_CHUNK).min(n)).filter(|&c| is_first(c)).count() as u32)
        .collect();
    let mut base = Vec::with_capacity(counts.len());
    let mut acc = 0u32;
    for c in counts {
        base.push(acc);
        acc += c;
    }
    let mut first_ids = vec![NONE; n];
    first_ids.par_chunks_mut(PAR_CHUNK).enumerate().for_each(|(k, chunk)| {
        let mut e = base[k];
        for (i, slot) in chunk.iter_mut().enumerate() {
            if is_first(k * PAR_CHUNK + i) {
                *slot = 2 * e;
                e += 1;
            }
        }
    });
    (0..n)
        .into_par_iter()
        .with_min_len(PAR_CHUNK)
        .map(|c| {
            let t = twin[c];
            if t == NONE {
                NONE
            } else if t as usize > c {
                first_ids[c]
            } else {
                first_ids[t as usize] + 1
            }
        })
        .collect()
}

/// Work unit of the parallel loops: large enough to amortize rayon's overhead.
const PAR_CHUNK: usize = 1 << 14;

/// A raw column pointer shared by the parallel fill in [`Mesh::build`], whose
/// writes are disjoint by construction.
#[derive(Copy, Clone)]
struct SyncPtr(*mut u32);
// SAFETY: only used for the disjoint writes documented at its use.
unsafe impl Send for SyncPtr {}
unsafe impl Sync for SyncPtr {}

impl SyncPtr {
    /// A method, not a field access, so closures capture the `Sync` wrapper.
    #[inline]
    fn at(self, i: usize) -> *mut u32 {
        // SAFETY: callers index within the column's length.
        unsafe { self.0.add(i) }
    }
}

/// Pairs the face sides between vertices `lo` and `hi` (`lo <= hi`).
#[allow(clippy::too_many_arguments)]
fn pair_sides(
    lo: u32,
    hi: u32,
    sides: &[(u32, u32)],
    verts: &[u32],
    face_of: &[u32],
    opts: BuildOptions,
    twin: &mut [u32],
    unmatched: &mut Vec<u32>,
) -> Result<()> {
    // the common case, one side each way, without allocating
    if let [(_, c0), (_, c1)] = *sides {
        if lo != hi && (verts[c0 as usize] == lo) != (verts[c1 as usize] == lo) {
            twin[c0 as usize] = c1;
            twin[c1 as usize] = c0;
            return Ok(());
        }
    }
    let faces = || sides.iter().map(|&(_, c)| face_of[c as usize] as usize).collect::<Vec<_>>();
    let link = |twin: &mut [u32], a: u32, b: u32| {
        twin[a as usize] = b;
        twin[b as usize] = a;
    };
    if lo == hi {
        // self-loop sides have no direction to tell apart: pair in order
        if sides.len() > 2 && !opts.allow_multi_edges {
            return Err(MeshError::NonManifoldEdge { a: lo as usize, b: hi as usize, faces: faces() });
        }
        for p in sides.chunks(2) {
            if p.len() == 2 {
                link(twin, p[0].1, p[1].1);
            } else if opts.close_boundaries {
                unmatched.push(p[0].1);
            } else {
                return Err(MeshError::Boundary { a: lo as usize, b: hi as usize, face: face_of[p[0].1 as usize] as usize });
            }
        }
        return Ok(());
    }
    let (fwd, bwd): (Vec<u32>, Vec<u32>) = {
        let mut f = Vec::new();
        let mut b = Vec::new();
        for &(_, c) in sides {
            if verts[c as usize] == lo { f.push(c) } else { b.push(c) }
        }
        (f, b)
    };
    match (fwd.len(), bwd.len()) {
        (1, 1) => link(twin, fwd[0], bwd[0]),
        (1, 0) | (0, 1) => {
            let c = fwd.first().or(bwd.first()).copied().unwrap();
            if !opts.close_boundaries {
                let (a, b) = if fwd.is_empty() { (hi, lo) } else { (lo, hi) };
                return Err(MeshError::Boundary { a: a as usize, b: b as usize, face: face_of[c as usize] as usize });
            }
            unmatched.push(c);
        }
        (2, 0) | (0, 2) => {
            let (f1, f2) = (face_of[sides[0].1 as usize] as usize, face_of[sides[1].1 as usize] as usize);
            let (a, b) = if fwd.is_empty() { (hi, lo) } else { (lo, hi) };
            return Err(MeshError::InconsistentOrientation { a: a as usize, b: b as usize, face1: f1, face2: f2 });
        }
        (nf, nb) if nf == nb && opts.allow_multi_edges => {
            for (&a, &b) in fwd.iter().zip(&bwd) {
                link(twin, a, b);
            }
        }
        _ => return Err(MeshError::NonManifoldEdge { a: lo as usize, b: hi as usize, faces: faces() }),
    }
    Ok(())
}

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

impl PolygonFaces {
    /// Sizes and indices as the int64 arrays [`Mesh::from_polygons`] and
    /// [`Mesh::from_corner_twins_i64`] take (a round trip's input).
    pub fn to_i64(&self) -> (Vec<i64>, Vec<i64>) {
        (self.sizes.iter().map(|&s| s as i64).collect(), self.indices.iter().map(|&i| i as i64).collect())
    }
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
    pub fn from_polygons(positions: Vec<DVec3>, sizes: &[i64], indices: &[i64], opts: BuildOptions) -> Result<Mesh> {
        Self::from_polygons_of(positions, sizes, indices, opts)
    }

    /// [`Mesh::from_polygons`] with int32 indices (a PLY file's, and the face
    /// arrays of many libraries), read as they are: no int64 copy.
    pub fn from_polygons_i32(positions: Vec<DVec3>, sizes: &[i64], indices: &[i32], opts: BuildOptions) -> Result<Mesh> {
        Self::from_polygons_of(positions, sizes, indices, opts)
    }

    fn from_polygons_of<T: Copy + Sync + Into<i64>>(positions: Vec<DVec3>, sizes: &[i64], indices: &[T], opts: BuildOptions) -> Result<Mesh> {
        let nv = positions.len();
        if nv > MAX_ELEMENTS || indices.len() > MAX_ELEMENTS / 2 {
            return Err(MeshError::InvalidArgument(format!(
                "mesh too large: at most {MAX_ELEMENTS} vertices and {} corners",
                MAX_ELEMENTS / 2
            )));
        }
        if let Some(v) = first_index(&positions, |p| !p.is_finite()) {
            return Err(MeshError::NonFinite { vertex: v });
        }
        // sizes and indices
        if let Some(f) = first_index(sizes, |&s| s <= 0) {
            if sizes[f] == 0 {
                return Err(MeshError::EmptyFace { face: f });
            }
            return Err(MeshError::InvalidArgument(format!("face {f} has negative size {}", sizes[f])));
        }
        let mut offsets = Vec::with_capacity(sizes.len() + 1);
        offsets.push(0usize);
        let mut acc = 0usize;
        for (f, &s) in sizes.iter().enumerate() {
            crate::cancel::poll(f)?;
            // checked: user sizes near 2^63 would wrap the sum
            acc = acc.checked_add(s as usize).ok_or_else(|| {
                MeshError::InvalidArgument(format!("face sizes add up to more than the {} face indices given", indices.len()))
            })?;
            offsets.push(acc);
        }
        if *offsets.last().unwrap() != indices.len() {
            return Err(MeshError::InvalidArgument(format!(
                "face sizes add up to {} but {} face indices were given",
                offsets.last().unwrap(),
                indices.len()
            )));
        }
        // the first bad index in corner order, i.e. of the lowest face
        if let Some(c) = first_index(indices, |&i| {
            let i: i64 = i.into();
            i < 0 || i as usize >= nv
        }) {
            let f = face_of(&offsets, c as u32);
            return Err(MeshError::IndexOutOfRange { face: f, position: c - offsets[f], index: indices[c].into(), n_vertices: nv });
        }
        // par_collect: the columns' pages are mapped in one call per chunk before the fill
        let mut verts: Vec<u32> = crate::cancel::par_collect(indices.len(), |c| Into::<i64>::into(indices[c]) as u32)?;
        let n = verts.len();
        // head vertex of every corner's side: the next corner's vertex, except
        // at the end of a face, which wraps to its first corner
        let mut head: Vec<u32> = crate::cancel::par_collect(n, |c| if c + 1 < n { verts[c + 1] } else { 0 })?;
        for f in 0..sizes.len() {
            crate::cancel::poll(f)?;
            head[offsets[f + 1] - 1] = verts[offsets[f]];
        }
        crate::cancel::check()?;
        // corners per vertex: point-spheres are size-1 faces whose vertex is used once
        let mut uses = vec![0u32; nv];
        for &v in &verts {
            uses[v as usize] += 1;
        }
        if let Some(v) = first_index(&uses, |&u| u == 0) {
            return Err(MeshError::InvalidArgument(format!(
                "vertex {v} is not used by any face; remove unreferenced vertices first"
            )));
        }
        // a side from a vertex to itself lies in a one-gon or ends at a repeat
        // of its vertex, so (used once) it is the corner of a size-1 face
        let is_point = |c: usize| -> bool { head[c] == verts[c] && uses[verts[c] as usize] == 1 };

        // --- pair corners into edges: bucket sides by their smaller vertex
        // (a counting sort, in parallel over corner chunks: chunk k fills its
        // own slots of every bucket, after those of chunks < k)
        let lo_of: Vec<u32> = crate::cancel::par_collect(n, |c| if is_point(c) { NONE } else { verts[c].min(head[c]) })?;
        let n_chunks = rayon::current_num_threads().clamp(1, 8).min(n.div_ceil(PAR_CHUNK)).max(1);
        let chunk_len = n.div_ceil(n_chunks).max(1);
        let mut fill: Vec<Vec<u32>> = lo_of
            .par_chunks(chunk_len)
            .map(|ch| {
                let mut cnt = vec![0u32; nv];
                for (i, &lo) in ch.iter().enumerate() {
                    // cancelled: garbage counts, the check below reports it
                    if i % 65536 == 0 && crate::cancel::requested() {
                        break;
                    }
                    if lo != NONE {
                        cnt[lo as usize] += 1;
                    }
                }
                cnt
            })
            .collect();
        crate::cancel::check()?;
        let mut bucket_start = vec![0u32; nv + 1];
        let mut acc = 0u32;
        for v in 0..nv {
            crate::cancel::poll(v)?;
            bucket_start[v] = acc;
            for cnt in fill.iter_mut() {
                let k = cnt[v];
                cnt[v] = acc;
                acc += k;
            }
        }
        bucket_start[nv] = acc;
        let mut bucket = vec![0u32; acc as usize];
        super::populate(&mut bucket, acc as usize);
        {
            let out = SyncPtr(bucket.as_mut_ptr());
            lo_of.par_chunks(chunk_len).zip(fill.par_iter_mut()).enumerate().for_each(|(k, (ch, slot))| {
                for (i, &lo) in ch.iter().enumerate() {
                    // cancelled: stop early (writes stay in their ranges)
                    if i % 65536 == 0 && crate::cancel::requested() {
                        break;
                    }
                    if lo != NONE {
                        // SAFETY: slot[lo] runs through the slots reserved for
                        // chunk k in bucket lo (the prefix above gives every
                        // (bucket, chunk) pair its own range), so no two
                        // writes, in this chunk or another, hit the same index.
                        unsafe { *out.at(slot[lo as usize] as usize) = (k * chunk_len + i) as u32 };
                        slot[lo as usize] += 1;
                    }
                }
            });
        }
        drop(fill);
        drop(lo_of);
        crate::cancel::check()?;
        // pair each bucket's sides, in parallel over vertex ranges; the error
        // reported is the one of the lowest vertex, as in a sequential sweep,
        // and unmatched sides are listed in vertex order
        let mut twin = crate::cancel::par_filled(n, NONE)?;
        let tw = SyncPtr(twin.as_mut_ptr());
        let pieces: Vec<Result<Vec<u32>>> = (0..nv.div_ceil(VERTEX_CHUNK))
            .into_par_iter()
            .map(|k| {
                crate::cancel::check()?;
                let mut unmatched: Vec<u32> = Vec::new();
                let mut group: Vec<(u32, u32)> = Vec::new(); // (other vertex, corner)
                for lo in k * VERTEX_CHUNK..((k + 1) * VERTEX_CHUNK).min(nv) {
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
                        // SAFETY: pair_sides writes twin only at the corners of
                        // `sides`, all in bucket lo; every corner is in at most
                        // one bucket, and each bucket is paired by one task.
                        unsafe { pair_sides(lo as u32, hi, sides, &verts, &offsets, opts, tw, &mut unmatched)? };
                        i = j;
                    }
                }
                Ok(unmatched)
            })
            .collect();
        drop(bucket);
        let mut unmatched: Vec<u32> = Vec::new();
        for p in pieces {
            unmatched.extend(p?);
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
        // Without hole faces every twin comes from `pair_sides`, which links
        // a side a -> b only with a side b -> a (a self-loop side with one at
        // the same vertex) and leaves only point-sphere corners (faces of
        // size 1) without twin: the twin check of `build` cannot fail, so it
        // is skipped. Hole corners are checked.
        Mesh::build(positions, &sizes_u, &verts, &twin, holes, unmatched.is_empty())
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
        Mesh::build(positions, sizes, corner_verts, twin, holes, false)
    }

    /// [`Mesh::from_corner_twins`] with some faces marked as holes
    /// (boundary loops), for the schemes that keep a mesh open.
    pub fn from_corner_twins_with_holes(
        positions: Vec<DVec3>,
        sizes: &[u32],
        corner_verts: &[u32],
        twin: &[u32],
        holes: Vec<bool>,
    ) -> Result<Mesh> {
        if holes.len() != sizes.len() {
            return Err(MeshError::InvalidArgument(format!("{} hole flags for {} faces", holes.len(), sizes.len())));
        }
        Mesh::build(positions, sizes, corner_verts, twin, holes, false)
    }

    /// `twins_valid`: the caller guarantees what the twin check below tests
    /// (vertices in range, symmetric twins running between the same vertices
    /// in opposite directions, twinless corners alone in their face); the
    /// unsafe fill relies on it.
    pub(super) fn build(positions: Vec<DVec3>, sizes: &[u32], verts: &[u32], twin: &[u32], f_hole: Vec<bool>, twins_valid: bool) -> Result<Mesh> {
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
            if f % 65536 == 0 {
                crate::cancel::check()?;
            }
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
        crate::cancel::check()?;
        // every corner: a vertex in range and a symmetric twin (debug builds
        // check even when the caller vouches for the twins)
        let bad = if twins_valid && !cfg!(debug_assertions) { None } else { first_bad_face(&offsets, verts, twin, nv) };
        crate::cancel::check()?;
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
        crate::cancel::check()?;
        // half-edge ids: edges numbered by their first corner (2e), the twin gets 2e + 1
        let (he_of, ne) = number_halfedges(twin)?;
        crate::cancel::check()?;
        let nh = 2 * ne;
        let (v_out, f_start) = (crate::cancel::par_filled(nv, NONE)?, crate::cancel::par_filled(nf, NONE)?);
        let mut m = Mesh {
            pos: positions,
            v_out,
            // every entry is written below, onto pages mapped first in one
            // call per chunk (crate::mesh::populate)
            he_next: vec![0; nh],
            he_prev: vec![0; nh],
            he_vert: vec![0; nh],
            he_face: vec![0; nh],
            f_start,
            f_hole,
        };
        for col in [&mut m.he_next, &mut m.he_prev, &mut m.he_vert, &mut m.he_face] {
            super::populate(col, nh);
        }
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
                // cancelled: the check after the loop returns before any read
                if twin[s] == NONE || crate::cancel::requested() {
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
        crate::cancel::check()?;
        // the first corner of each vertex, as documented for exports
        for (c, &v) in verts.iter().enumerate().rev() {
            if c % 65536 == 0 {
                crate::cancel::check()?;
            }
            if twin[c] != NONE {
                m.v_out[v as usize] = he_of[c];
            }
        }
        for f in 0..nf {
            crate::cancel::poll(f)?;
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
        if let Some(v) = first_index(&m.v_out, |&o| o == NONE) {
            return Err(MeshError::InvalidArgument(format!("vertex {v} is not used by any face")));
        }
        crate::cancel::check()?;
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
        // cancelled: walks stop at once and the sum is not looked at
        let total: usize = (0..self.n_vertices())
            .into_par_iter()
            .with_min_len(4096)
            .map(|v| if crate::cancel::requested() { 0 } else { walk(v) })
            .sum();
        crate::cancel::check()?;
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
/// Also returns the number of edges. Cancellable ([`crate::cancel`]).
pub(crate) fn number_halfedges(twin: &[u32]) -> Result<(Vec<u32>, usize)> {
    let n = twin.len();
    let is_first = |c: usize| twin[c] != NONE && twin[c] as usize > c;
    // parallel exclusive scan of edge starts over fixed chunks
    let counts: Vec<u32> = (0..n.div_ceil(PAR_CHUNK))
        .into_par_iter()
        // cancelled: the numbering is garbage, and the caller's next check returns
        .map(|k| if crate::cancel::requested() { 0 } else { (k * PAR_CHUNK..((k + 1) * PAR_CHUNK).min(n)).filter(|&c| is_first(c)).count() as u32 })
        .collect();
    let mut base = Vec::with_capacity(counts.len());
    let mut acc = 0u32;
    for c in counts {
        base.push(acc);
        acc += c;
    }
    // only the first corners' entries are read below: zeroed (calloc)
    // memory, no sequential memset, its pages mapped in one call per chunk
    let mut first_ids = vec![0u32; n];
    super::populate(&mut first_ids, n);
    first_ids.par_chunks_mut(PAR_CHUNK).enumerate().for_each(|(k, chunk)| {
        if crate::cancel::requested() {
            return;
        }
        let mut e = base[k];
        for (i, slot) in chunk.iter_mut().enumerate() {
            if is_first(k * PAR_CHUNK + i) {
                *slot = 2 * e;
                e += 1;
            }
        }
    });
    // written chunk by chunk, stopping once cancelled (`cancel::par_collect`:
    // a rayon collect wrote all 4 bytes per corner of fresh memory, up to
    // half a second of Ctrl-C latency on a 2M-face Sierpinski step)
    let he_of = crate::cancel::par_collect(n, |c| {
        let t = twin[c];
        if t == NONE {
            NONE
        } else if t as usize > c {
            first_ids[c]
        } else {
            first_ids[t as usize].wrapping_add(1) // wraps only when cancelled
        }
    })?;
    Ok((he_of, acc as usize))
}

/// Work unit of the parallel loops: large enough to amortize rayon's overhead.
const PAR_CHUNK: usize = 1 << 14;
/// Vertices per task of the parallel pairing in [`Mesh::from_polygons`].
const VERTEX_CHUNK: usize = 1 << 12;

/// The index of the first element of `s` satisfying `pred`, searched in
/// parallel over chunks (rayon's per-item `position_first` costs several ns
/// per element; a chunk scan vectorizes).
pub(crate) fn first_index<T: Sync>(s: &[T], pred: impl Fn(&T) -> bool + Sync) -> Option<usize> {
    let k = s.par_chunks(PAR_CHUNK).position_first(|ch| ch.iter().any(&pred))?;
    let base = k * PAR_CHUNK;
    s[base..].iter().position(&pred).map(|i| base + i)
}

/// The first face (`offsets`: the prefix of its sizes) with a corner whose
/// vertex is out of `0..nv`, or whose twin is not a symmetric partner that
/// starts where the corner's side ends (checked from both sides, this also
/// makes the twin end where the corner starts); a twinless corner (`NONE`)
/// must be alone in its face. Searched in parallel; a cancelled search
/// returns `None`, so callers check [`crate::cancel`] before trusting it.
pub(super) fn first_bad_face(offsets: &[u32], verts: &[u32], twin: &[u32], nv: usize) -> Option<usize> {
    let n = verts.len();
    first_in_range(offsets.len() - 1, |f| {
        if crate::cancel::requested() {
            return false;
        }
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
    })
}

/// The first `i` in `0..n` satisfying `pred`, searched like [`first_index`].
pub(crate) fn first_in_range(n: usize, pred: impl Fn(usize) -> bool + Sync) -> Option<usize> {
    let chunk = 4096;
    let k = (0..n.div_ceil(chunk)).into_par_iter().find_first(|&k| (k * chunk..((k + 1) * chunk).min(n)).any(&pred))?;
    (k * chunk..((k + 1) * chunk).min(n)).find(|&i| pred(i))
}

/// The face of corner `c`, given the prefix of face sizes (all sizes > 0).
fn face_of(offsets: &[usize], c: u32) -> usize {
    offsets.partition_point(|&o| o <= c as usize) - 1
}

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
///
/// # Safety
/// `twin` points to a column of one entry per corner, and no other thread
/// writes the entries of the corners in `sides` (the only ones written).
unsafe fn pair_sides(
    lo: u32,
    hi: u32,
    sides: &[(u32, u32)],
    verts: &[u32],
    offsets: &[usize],
    opts: BuildOptions,
    twin: SyncPtr,
    unmatched: &mut Vec<u32>,
) -> Result<()> {
    let link = |twin: SyncPtr, a: u32, b: u32| {
        // SAFETY: a and b are corners of `sides` (the caller's contract).
        unsafe {
            *twin.at(a as usize) = b;
            *twin.at(b as usize) = a;
        }
    };
    // the common case, one side each way, without allocating
    if let [(_, c0), (_, c1)] = *sides {
        if lo != hi && (verts[c0 as usize] == lo) != (verts[c1 as usize] == lo) {
            link(twin, c0, c1);
            return Ok(());
        }
    }
    let face_of = |c: u32| face_of(offsets, c);
    let faces = || sides.iter().map(|&(_, c)| face_of(c)).collect::<Vec<_>>();
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
                return Err(MeshError::Boundary { a: lo as usize, b: hi as usize, face: face_of(p[0].1) });
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
                return Err(MeshError::Boundary { a: a as usize, b: b as usize, face: face_of(c) });
            }
            unmatched.push(c);
        }
        (2, 0) | (0, 2) => {
            let (f1, f2) = (face_of(sides[0].1), face_of(sides[1].1));
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

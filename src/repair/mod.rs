//! The repair path for polygon soups and sloppy meshes (STL files, scanner
//! output, meshes from other libraries): raw polygons in, polygons that
//! [`Mesh::from_polygons`] accepts out, with a [`RepairReport`] of what changed.
//!
//! Steps, in this order (each linear or `n log n`):
//! 1. validate the input (ranges, sizes, finite coordinates), like `from_polygons`;
//! 2. merge vertices within `tolerance` ([`weld::weld`]; default `1e-9` times
//!    the bounding-box diagonal, `0` merges exactly equal positions only);
//! 3. drop degenerate faces: consecutive repeated vertices collapse, then a
//!    face with fewer than three corners, or thinner than the tolerance
//!    (twice its area ≤ `tolerance` × its longest edge; exactly zero area when
//!    `tolerance == 0`), is dropped;
//! 4. drop duplicate faces (the same vertex cycle up to rotation and
//!    direction; the first is kept);
//! 5. pair face sides into edges; an edge with more than two sides keeps
//!    consistently oriented pairs in face order and detaches the rest
//!    ([`orient::pair_sides`]);
//! 6. orient every face-connected component consistently (the majority of
//!    its faces wins) and outward (a closed component with negative signed
//!    volume is reversed); edges of non-orientable pieces are cut;
//! 7. split pinched vertices: one vertex per umbrella ([`pinch::split`]);
//! 8. remove unreferenced vertices (output vertices keep the input order of
//!    their lowest merged vertex; split copies follow).
//!
//! Boundaries that remain are counted, not closed: the caller decides
//! (`close_boundaries`).

mod orient;
mod pinch;
mod weld;

pub use orient::inside_out_components;

use crate::error::{MeshError, Result};
use crate::mesh::{BuildOptions, Mesh, MAX_ELEMENTS};
use glam::DVec3;
use rayon::prelude::*;
use std::hash::{Hash, Hasher};

pub(crate) const NONE: u32 = u32::MAX;

/// The default merge tolerance relative to the bounding-box diagonal: far
/// below any modelled feature, far above float noise from exporters.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-9;

/// What each step of [`repair`] changed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RepairReport {
    /// The absolute merge tolerance used.
    pub tolerance: f64,
    /// Input vertices merged into an earlier one (input V − clusters).
    pub vertices_merged: usize,
    /// Faces dropped with fewer than three distinct corners or zero area.
    pub degenerate_faces_dropped: usize,
    /// Faces dropped as repeats of an earlier face.
    pub duplicate_faces_dropped: usize,
    /// Edges that had more than two faces; faces beyond the kept pairs were detached.
    pub non_manifold_edges_split: usize,
    /// Faces reversed to agree with the majority of their component.
    pub faces_flipped: usize,
    /// Closed components reversed because their signed volume was negative.
    pub components_flipped: usize,
    /// Edges cut because their two faces could not be oriented alike (non-orientable pieces).
    pub non_orientable_edges_cut: usize,
    /// Extra vertices made by splitting pinched (non-manifold) vertices.
    pub pinched_vertices_split: usize,
    /// Vertices (after merging) that no remaining face uses.
    pub unreferenced_vertices_removed: usize,
    /// Boundary loops left in the output.
    pub boundary_loops: usize,
}

/// Repaired polygons, ready for [`Mesh::from_polygons`].
#[derive(Clone, Debug)]
pub struct Repaired {
    pub positions: Vec<DVec3>,
    pub sizes: Vec<i64>,
    pub indices: Vec<i64>,
    pub report: RepairReport,
}

/// Faces in flat form with the face of every corner.
pub(crate) struct Faces {
    pub verts: Vec<u32>,
    /// `n_faces + 1` offsets into `verts`.
    pub off: Vec<u32>,
    pub face: Vec<u32>,
}

impl Faces {
    fn new(verts: Vec<u32>, off: Vec<u32>) -> Faces {
        let mut face = vec![0u32; verts.len()];
        for g in 0..off.len() - 1 {
            face[off[g] as usize..off[g + 1] as usize].fill(g as u32);
        }
        Faces { verts, off, face }
    }
    pub fn n_faces(&self) -> usize {
        self.off.len() - 1
    }
    pub fn corners(&self, g: usize) -> std::ops::Range<usize> {
        self.off[g] as usize..self.off[g + 1] as usize
    }
    pub fn next(&self, c: usize) -> usize {
        let g = self.face[c] as usize;
        if c + 1 == self.off[g + 1] as usize { self.off[g] as usize } else { c + 1 }
    }
    pub fn prev(&self, c: usize) -> usize {
        let g = self.face[c] as usize;
        if c == self.off[g] as usize { self.off[g + 1] as usize - 1 } else { c - 1 }
    }
}

/// Repairs raw polygons (`sizes` and flat `indices` as the user passed them)
/// in the steps of the module docs. `tolerance`: `None` for the default
/// ([`DEFAULT_RELATIVE_TOLERANCE`] × bounding-box diagonal), else a finite
/// number ≥ 0. Errors name the face, vertex or parameter; nothing else fails.
pub fn repair(positions: &[DVec3], sizes: &[i64], indices: &[i64], tolerance: Option<f64>) -> Result<Repaired> {
    validate(positions, sizes, indices)?;
    let tol = match tolerance {
        None => {
            let (lo, hi) = positions.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
            if positions.is_empty() { 0.0 } else { DEFAULT_RELATIVE_TOLERANCE * (hi - lo).length() }
        }
        Some(t) if t.is_finite() && t >= 0.0 => t,
        Some(t) => {
            return Err(MeshError::InvalidArgument(format!("repair: tolerance = {} must be a finite number >= 0", crate::error::num(t))));
        }
    };
    let mut report = RepairReport { tolerance: tol, ..Default::default() };

    // 2. merge
    let (cluster_pos, cluster) = merge_vertices(positions, tol);
    let n_clusters = cluster_pos.len();
    report.vertices_merged = positions.len() - n_clusters;

    // 3. degenerate faces
    let mut verts: Vec<u32> = Vec::with_capacity(indices.len());
    let mut off: Vec<u32> = Vec::with_capacity(sizes.len() + 1);
    off.push(0);
    let mut start = 0usize;
    for &s in sizes {
        let face = &indices[start..start + s as usize];
        start += s as usize;
        let base = verts.len();
        for &i in face {
            let v = cluster[i as usize];
            if verts.len() == base || verts[verts.len() - 1] != v {
                verts.push(v);
            }
        }
        while verts.len() > base + 1 && verts[verts.len() - 1] == verts[base] {
            verts.pop();
        }
        if verts.len() - base < 3 || thin(&verts[base..], &cluster_pos, tol) {
            verts.truncate(base);
            report.degenerate_faces_dropped += 1;
        } else {
            off.push(verts.len() as u32);
        }
    }

    // 4. duplicate faces
    let (verts, off, dups) = drop_duplicates(verts, off);
    report.duplicate_faces_dropped = dups;
    let mut faces = Faces::new(verts, off);

    // 5.–6. edges and orientation
    let (mut twin, nm) = orient::pair_sides(&faces);
    report.non_manifold_edges_split = nm;
    let o = orient::orient(&faces, &cluster_pos, &mut twin);
    report.faces_flipped = o.faces_flipped;
    report.components_flipped = o.components_flipped;
    report.non_orientable_edges_cut = o.cuts;
    apply_flips(&mut faces, &mut twin, &o.flip);

    // 7.–8. umbrellas and numbering
    let (out_vert, source, extra) = pinch::split(&faces, &twin, n_clusters);
    report.pinched_vertices_split = extra;
    report.unreferenced_vertices_removed = n_clusters - (source.len() - extra);
    report.boundary_loops = boundary_loops(&faces, &twin, &out_vert, source.len());

    let positions = source.iter().map(|&c| cluster_pos[c as usize]).collect();
    let sizes = faces.off.windows(2).map(|w| (w[1] - w[0]) as i64).collect();
    let indices = out_vert.iter().map(|&v| v as i64).collect();
    Ok(Repaired { positions, sizes, indices, report })
}

/// Merges vertices within `tol` (≥ 0; 0: exactly equal positions only) as
/// step 2 of [`repair`] does: the distinct positions (each cluster at its
/// lowest member, in that member's order) and the cluster of every input vertex.
pub fn merge_vertices(positions: &[DVec3], tol: f64) -> (Vec<DVec3>, Vec<u32>) {
    let (cluster, n) = weld::weld(positions, tol);
    let mut out = crate::mesh::zeroed_points(n);
    let mut seen = vec![false; n];
    for (v, &c) in cluster.iter().enumerate() {
        if !seen[c as usize] {
            seen[c as usize] = true;
            out[c as usize] = positions[v];
        }
    }
    (out, cluster)
}

/// [`repair`], then [`Mesh::from_polygons`] (capping the boundaries left
/// when `close_boundaries`; without it they are a `Boundary` error).
pub fn repair_mesh(
    positions: &[DVec3],
    sizes: &[i64],
    indices: &[i64],
    tolerance: Option<f64>,
    close_boundaries: bool,
) -> Result<(Mesh, RepairReport)> {
    let r = repair(positions, sizes, indices, tolerance)?;
    let opts = BuildOptions { close_boundaries, allow_multi_edges: false };
    let m = Mesh::from_polygons(r.positions, &r.sizes, &r.indices, opts)?;
    Ok((m, r.report))
}

/// The input checks of `from_polygons`, with checked size arithmetic.
fn validate(positions: &[DVec3], sizes: &[i64], indices: &[i64]) -> Result<()> {
    let nv = positions.len();
    if nv > MAX_ELEMENTS || indices.len() > MAX_ELEMENTS / 2 {
        return Err(MeshError::InvalidArgument(format!(
            "repair: mesh too large: at most {MAX_ELEMENTS} vertices and {} corners",
            MAX_ELEMENTS / 2
        )));
    }
    if let Some(v) = positions.iter().position(|p| !p.is_finite()) {
        return Err(MeshError::NonFinite { vertex: v });
    }
    let mut total = 0usize;
    for (f, &s) in sizes.iter().enumerate() {
        if s == 0 {
            return Err(MeshError::EmptyFace { face: f });
        }
        if s < 0 {
            return Err(MeshError::InvalidArgument(format!("face {f} has negative size {s}")));
        }
        total = match total.checked_add(s as usize) {
            Some(t) if t <= indices.len() => t,
            _ => {
                return Err(MeshError::InvalidArgument(format!(
                    "face sizes up to face {f} add up to more than the {} face indices given",
                    indices.len()
                )))
            }
        };
    }
    if total != indices.len() {
        return Err(MeshError::InvalidArgument(format!(
            "face sizes add up to {total} but {} face indices were given",
            indices.len()
        )));
    }
    if let Some(c) = indices.iter().position(|&i| i < 0 || i as usize >= nv) {
        let mut f = 0;
        let mut s = 0usize;
        while s + sizes[f] as usize <= c {
            s += sizes[f] as usize;
            f += 1;
        }
        return Err(MeshError::IndexOutOfRange { face: f, position: c - s, index: indices[c], n_vertices: nv });
    }
    Ok(())
}

/// A face is degenerate when twice its area (Newell) is at most `tol` times
/// its longest edge: thinner than the merge tolerance.
fn thin(face: &[u32], pos: &[DVec3], tol: f64) -> bool {
    let k = face.len();
    let mut n = DVec3::ZERO;
    let mut longest = 0.0f64;
    for i in 0..k {
        let (p, q) = (pos[face[i] as usize], pos[face[(i + 1) % k] as usize]);
        n += p.cross(q);
        longest = longest.max(p.distance(q));
    }
    n.length() <= tol * longest
}

/// The start and direction (+1 or -1 as `true`/`false`) of the least
/// rotation of a cycle read forwards or backwards: equal cycles up to
/// rotation and direction get equal canonical sequences.
fn canonical(face: &[u32]) -> (usize, bool) {
    let k = face.len();
    let fwd = least_rotation(k, |i| face[i % k]);
    let bwd_r = least_rotation(k, |i| face[(k - i % k) % k]);
    let bwd = (k - bwd_r) % k;
    let at = |s: usize, f: bool, i: usize| if f { face[(s + i) % k] } else { face[(s + k - i % k) % k] };
    let smaller_fwd = (0..k).map(|i| at(fwd, true, i)).le((0..k).map(|i| at(bwd, false, i)));
    if smaller_fwd { (fwd, true) } else { (bwd, false) }
}

/// Booth's least rotation of the cycle `s(0..k)`, linear.
fn least_rotation(k: usize, s: impl Fn(usize) -> u32) -> usize {
    if k <= 3 {
        return (0..k).min_by_key(|&i| (s(i), s(i + 1), s(i + 2))).unwrap_or(0);
    }
    let mut fail = vec![-1i64; 2 * k];
    let mut r = 0usize;
    for j in 1..2 * k {
        let sj = s(j);
        let mut i = fail[j - r - 1];
        while i != -1 && sj != s(r + i as usize + 1) {
            if sj < s(r + i as usize + 1) {
                r = j - i as usize - 1;
            }
            i = fail[i as usize];
        }
        if i == -1 && sj != s(r) {
            if sj < s(r) {
                r = j;
            }
            fail[j - r] = -1;
        } else {
            fail[j - r] = i + 1;
        }
    }
    r % k
}

/// Drops every face equal to an earlier one up to rotation and direction
/// (hash of the canonical cycle, a parallel sort, exact comparison within
/// equal hashes). Returns the kept faces and the number dropped.
fn drop_duplicates(verts: Vec<u32>, off: Vec<u32>) -> (Vec<u32>, Vec<u32>, usize) {
    let nf = off.len() - 1;
    let face = |g: usize| &verts[off[g] as usize..off[g + 1] as usize];
    let canon: Vec<(usize, bool)> = (0..nf).into_par_iter().with_min_len(4096).map(|g| canonical(face(g))).collect();
    let read = |g: usize, i: usize| {
        let (s, f) = canon[g];
        let c = face(g);
        let k = c.len();
        if f { c[(s + i) % k] } else { c[(s + k - i % k) % k] }
    };
    let mut keyed: Vec<(u64, u32)> = (0..nf)
        .into_par_iter()
        .with_min_len(4096)
        .map(|g| {
            let mut h = rustc_hash::FxHasher::default();
            let k = face(g).len();
            k.hash(&mut h);
            for i in 0..k {
                read(g, i).hash(&mut h);
            }
            (h.finish(), g as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    let mut drop_face = vec![false; nf];
    let mut dups = 0;
    let mut i = 0;
    while i < nf {
        let mut j = i + 1;
        while j < nf && keyed[j].0 == keyed[i].0 {
            j += 1;
        }
        for x in i + 1..j {
            let gx = keyed[x].1 as usize;
            let kx = face(gx).len();
            let dup = (i..x).any(|y| {
                let gy = keyed[y].1 as usize;
                !drop_face[gy] && face(gy).len() == kx && (0..kx).all(|t| read(gx, t) == read(gy, t))
            });
            if dup {
                drop_face[gx] = true;
                dups += 1;
            }
        }
        i = j;
    }
    if dups == 0 {
        return (verts, off, 0);
    }
    let mut v2 = Vec::with_capacity(verts.len());
    let mut o2 = vec![0u32];
    for g in 0..nf {
        if !drop_face[g] {
            v2.extend_from_slice(face(g));
            o2.push(v2.len() as u32);
        }
    }
    (v2, o2, dups)
}

/// Reverses the faces marked in `flip`: face `v0 v1 … v(k-1)` becomes
/// `v0 v(k-1) … v1`, so side `i` (from `v(i)` to `v(i+1)`) becomes the side
/// at corner `k-1-i`; twins are renumbered to match.
fn apply_flips(f: &mut Faces, twin: &mut Vec<u32>, flip: &[bool]) {
    if !flip.iter().any(|&b| b) {
        return;
    }
    let perm = |c: usize| -> u32 {
        let g = f.face[c] as usize;
        if !flip[g] {
            return c as u32;
        }
        let (s, e) = (f.off[g] as usize, f.off[g + 1] as usize);
        (s + (e - s - 1 - (c - s))) as u32
    };
    let mut t2 = vec![NONE; twin.len()];
    for c in 0..twin.len() {
        if twin[c] != NONE {
            t2[perm(c) as usize] = perm(twin[c] as usize);
        }
    }
    for g in 0..f.n_faces() {
        if flip[g] {
            let (s, e) = (f.off[g] as usize, f.off[g + 1] as usize);
            f.verts[s + 1..e].reverse();
        }
    }
    *twin = t2;
}

/// Loops of unpaired sides: after the umbrella split every vertex has at most
/// one boundary side leaving it, so they chain into disjoint cycles.
fn boundary_loops(f: &Faces, twin: &[u32], out_vert: &[u32], nv: usize) -> usize {
    let mut leaving = vec![NONE; nv];
    for c in 0..twin.len() {
        if twin[c] == NONE {
            leaving[out_vert[c] as usize] = c as u32;
        }
    }
    let mut seen = vec![false; twin.len()];
    let mut loops = 0;
    for c0 in 0..twin.len() {
        if twin[c0] != NONE || seen[c0] {
            continue;
        }
        loops += 1;
        let mut c = c0;
        while !seen[c] {
            seen[c] = true;
            let nxt = leaving[out_vert[f.next(c)] as usize];
            if nxt == NONE {
                break;
            }
            c = nxt as usize;
        }
    }
    loops
}

#[cfg(test)]
mod tests;

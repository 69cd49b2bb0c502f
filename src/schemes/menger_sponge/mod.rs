//! The classic cubic Menger sponge as one closed manifold polygon mesh.
//!
//! The level-`n` sponge is the cube `[-1, 1]³` cut into `3ⁿ` cells per side,
//! keeping the cell `(x, y, z)` when at no base-3 digit position two or more
//! of `x, y, z` have the digit 1 (`20ⁿ` cells). The mesh is the boundary of
//! that solid: every unit square between a kept cell and a removed cell or
//! the outside, oriented outward. Coplanar unit squares are **kept** (not
//! merged), so every face is a quad and every vertex a grid point; the
//! dissertation lists this sponge as future work (ch. VIII).
//!
//! # Manifoldness
//!
//! Two kept cells meeting only along a grid edge (with the other two cells
//! around it removed) would give an edge with four boundary squares; cells
//! meeting only at a corner would pinch a vertex. Neither occurs: a brute
//! force scan of every 2×2 edge window and 2×2×2 vertex window finds none for
//! levels 1–4, and the builder re-checks the 2×2×2 window of every vertex it
//! makes (its link must be one cycle of squares), at every level, returning
//! an error otherwise. So no vertex duplication is needed.
//!
//! # Counts and genus
//!
//! Faces: the 20 level-`(n−1)` blocks are glued along 24 shared faces, each a
//! level-`(n−1)` Sierpinski carpet of `8ⁿ⁻¹` squares seen from both sides, so
//! `Fₙ = 20 Fₙ₋₁ − 48·8ⁿ⁻¹`, `F₀ = 6`, i.e. `Fₙ = 2·20ⁿ + 4·8ⁿ`; `Eₙ = 2Fₙ`.
//!
//! Genus, derived independently of the mesh: the solid `Sₙ` is a compact
//! 3-manifold with connected boundary, so `genus(∂Sₙ) = 1 − χ(Sₙ)`. Count
//! `χ(Sₙ)` on the cubical complex by inclusion–exclusion over the 20 blocks:
//! every open cell of the level-1 arrangement shared by `m ≥ 2` blocks is
//! counted `m − 1` times too often. In the level-1 arrangement the shared
//! cells are 24 squares (m = 2), edges with `Σ(m − 1) = 96` and vertices with
//! `Σ(m − 1) = 96`. At level `n` a shared square carries an open carpet with
//! `χ = χ(Cₙ₋₁) = 1 − (8ⁿ⁻¹ − 1)/7` (its boundary circle has χ = 0), a shared
//! edge an open segment (χ = −1), a shared vertex a point (χ = 1):
//!
//! ```text
//! χ(Sₙ) = 20 χ(Sₙ₋₁) − 24 χ(Cₙ₋₁) + 96 − 96,   χ(S₀) = 1
//!       = −(3/19)·20ⁿ − (2/7)·8ⁿ + 192/133
//! genusₙ = (21·20ⁿ + 38·8ⁿ − 59) / 133  =  0, 5, 81, 1409, 26433, 514625, …
//! Vₙ = Fₙ + 2 − 2·genusₙ
//! ```
//!
//! (The multiplicities 24/96/96 and `χ(S₁..₃) = −4, −80, −1408` were checked
//! by counting the cells of the union of cubes directly.)
//!
//! # Construction, in output time
//!
//! Only the `20ⁿ` kept cells are visited (`Fₙ ≥ 2·20ⁿ`, so this is linear in
//! the output). A row of cells `(x, y, ·)` is empty when `x` and `y` share a
//! digit 1, and otherwise keeps the `z` whose digit-1 mask avoids
//! `ones(x) | ones(y)`: a pattern that depends on that `n`-bit mask alone.
//! So a kept cell's compact index is `row_start[x, y] + z_rank[mask][z]`, two
//! lookups in tables of `9ⁿ` and `2ⁿ·3ⁿ` entries; no `27ⁿ` array exists.
//!
//! Every boundary vertex and every boundary grid edge is *owned* by the first
//! kept cell around it in a fixed order, which numbers it by its place among
//! its owner's (a bit mask and a prefix sum per cell). The half-edges of grid
//! edge `e` are `2e` (towards increasing coordinate) and `2e + 1`, so a face
//! corner knows its half-edge, and its twin is `h ^ 1`, without any pairing:
//! the half-edge columns are written directly, in parallel per slab `x`, and
//! no general builder runs. Faces come in the order of the grid scan (cells in
//! `x, y, z` order, then directions `−x, +x, −y, +y, −z, +z`), each from the same
//! first corner; vertices and edges are numbered by owner cell.
//! What a cell contributes depends on its 27-bit neighbourhood alone, and
//! only 321 neighbourhoods occur at levels 0–5: each one's masks, owners
//! and corners are worked out once per process (`recipes.rs`), and a cell
//! keeps its recipe's index from pass 1 to pass 3.
//! Memory beside the mesh: 14 bytes per kept cell.

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

#[cfg(test)]
mod reference;
mod recipes;
mod tables;

use recipes::{Recipe, Recipes, MAX_OWNERS, MISS};
use tables::{split_lens, Cells, Stencils};

/// Highest level built (level 6 would need ~10 GB).
pub const MAX_LEVEL: u32 = 5;

/// Faces of the level-`n` sponge: `2·20ⁿ + 4·8ⁿ`.
pub fn menger_sponge_faces(level: u32) -> u64 {
    2 * 20u64.pow(level) + 4 * 8u64.pow(level)
}

/// Genus of the level-`n` sponge's surface: `(21·20ⁿ + 38·8ⁿ − 59)/133`.
pub fn menger_sponge_genus(level: u32) -> u64 {
    (21 * 20u64.pow(level) + 38 * 8u64.pow(level) - 59) / 133
}

/// The classic Menger sponge of `level` (0 = the cube `[-1, 1]³`) as one
/// connected, outward-oriented closed manifold of unit quads. See the module
/// docs for the counts and the construction; levels above [`MAX_LEVEL`] are
/// refused.
pub fn menger_sponge(level: u32) -> Result<Mesh> {
    build(level, Recipes::table())
}

/// [`menger_sponge`] with the recipes of `rec` (the tests hand it an empty
/// table: every cell's recipe is then built on the spot).
fn build(level: u32, rec: &Recipes) -> Result<Mesh> {
    if level > MAX_LEVEL {
        return Err(MeshError::InvalidArgument(format!(
            "menger_sponge: level {level} is too large (at most {MAX_LEVEL}; level 6 has 128 M faces)"
        )));
    }
    let nf = menger_sponge_faces(level);
    let nv_expect = nf + 2 - 2 * menger_sponge_genus(level);
    let kept = 20u64.pow(level);
    let counts = crate::budget::Counts::plain(nv_expect, 2 * nf, nf);
    crate::budget::check("menger_sponge", &format!("level {level}"), crate::budget::mesh_bytes(&counts) + 14 * kept)?;
    // both fixed for all levels: built once per process
    let st = Stencils::get();
    let g = Cells::new(level);
    let n = g.n;
    let nc = g.row_start[n * n] as usize;
    debug_assert_eq!(nc as u64, kept);
    // small levels in one job: waking threads costs more than they save
    let min_len = if nc < 1 << 16 { n } else { 1 };

    // --- pass 1: per kept cell, exposed faces and the edges and vertices it owns
    let mut fmask = vec![0u8; nc];
    let mut emask = vec![0u16; nc];
    let mut vmask = vec![0u8; nc];
    // per kept cell: its recipe's index ([`MISS`]: built on the spot)
    let mut rid = vec![0u16; nc];
    let slab_counts: Vec<Option<[usize; 3]>> = {
        let lens = || (0..n).map(|x| g.slab(x).len());
        let (fs, es, vs) = (split_lens(&mut fmask, lens()), split_lens(&mut emask, lens()), split_lens(&mut vmask, lens()));
        let is = split_lens(&mut rid, lens());
        fs.into_par_iter()
            .zip(es)
            .zip(vs)
            .zip(is)
            .enumerate()
            .with_min_len(min_len)
            .map(|(x, (((fs, es), vs), ids))| {
                if crate::cancel::requested() {
                    return Some([0; 3]); // the check after the loop reports it
                }
                let base = g.slab(x).start;
                let (mut cf, mut ce, mut cv, mut ok) = (0, 0, 0, true);
                g.for_slab(x, |row, _, _, z, ci| {
                    let nb = g.neighbourhood(row, z);
                    let built;
                    let (r, id) = match rec.find(nb) {
                        Some((r, id)) => (r, id),
                        None => {
                            built = Recipe::build(st, nb);
                            (&built, MISS)
                        }
                    };
                    ok &= r.ok;
                    let k = ci - base;
                    (fs[k], es[k], vs[k], ids[k]) = (r.fmask, r.emask, r.vmask, id);
                    cf += ones8(r.fmask) as usize;
                    ce += ones16(r.emask) as usize;
                    cv += ones8(r.vmask) as usize;
                });
                ok.then_some([cf, ce, cv])
            })
            .collect()
    };
    crate::cancel::check()?;
    let Some(slab_counts) = slab_counts.into_iter().collect::<Option<Vec<_>>>() else {
        return Err(MeshError::Invariant("menger_sponge: a vertex whose cells do not meet in one disk (non-manifold)".into()));
    };
    let mut slab_start = vec![[0usize; 3]; n + 1];
    for x in 0..n {
        for k in 0..3 {
            slab_start[x + 1][k] = slab_start[x][k] + slab_counts[x][k];
        }
    }
    let [nf, ne, nv] = slab_start[n];
    debug_assert_eq!((nf as u64, ne as u64, nv as u64), (menger_sponge_faces(level), 2 * nf as u64, nv_expect));
    if ne != 2 * nf || nv as u64 != nv_expect {
        return Err(MeshError::Invariant(format!("menger_sponge: {nv} vertices, {ne} edges for {nf} faces")));
    }

    // --- pass 2: first owned edge and vertex id per cell
    let mut eoff = vec![0u32; nc];
    let mut voff = vec![0u32; nc];
    {
        let lens = || (0..n).map(|x| g.slab(x).len());
        let (eo, vo) = (split_lens(&mut eoff, lens()), split_lens(&mut voff, lens()));
        eo.into_par_iter().zip(vo).enumerate().with_min_len(min_len).for_each(|(x, (eo, vo))| {
            let r = g.slab(x);
            let (mut e, mut v) = (slab_start[x][1] as u32, slab_start[x][2] as u32);
            for (k, ci) in r.enumerate() {
                (eo[k], vo[k]) = (e, v);
                e += ones16(emask[ci]);
                v += ones8(vmask[ci]);
            }
        });
    }

    // --- pass 3: positions and half-edge columns, slab by slab
    let nh = 2 * ne;
    let mut m = Mesh {
        pos: crate::mesh::zeroed_points(nv),
        v_out: vec![0; nv],
        // zeroed (calloc) memory is mapped lazily: the parallel fill takes its page faults
        he_next: vec![0; nh],
        he_prev: vec![0; nh],
        he_vert: vec![0; nh],
        he_face: vec![0; nh],
        f_start: vec![0; nf],
        f_hole: vec![false; nf],
    };
    {
        let pos = SyncPtr(m.pos.as_mut_ptr());
        let v_out = SyncPtr(m.v_out.as_mut_ptr());
        let cols = [SyncPtr(m.he_next.as_mut_ptr()), SyncPtr(m.he_prev.as_mut_ptr()), SyncPtr(m.he_vert.as_mut_ptr()), SyncPtr(m.he_face.as_mut_ptr())];
        let f_start = SyncPtr(m.f_start.as_mut_ptr());
        let scale = 2.0 / n as f64;
        let (g, fmask, emask, vmask, eoff, voff, rid) = (&g, &fmask, &emask, &vmask, &eoff, &voff, &rid);
        (0..n).into_par_iter().with_min_len(min_len).for_each(|x| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let mut f = slab_start[x][0];
            g.for_slab(x, |row, x, y, z, ci| {
                let vm = vmask[ci];
                for i in 0..8 {
                    if vm & (1 << i) != 0 {
                        let p = DVec3::new((x + (i & 1)) as f64, (y + ((i >> 1) & 1)) as f64, (z + (i >> 2)) as f64) * scale - DVec3::ONE;
                        let v = voff[ci] + ones8(vm & ((1 << i) - 1));
                        // SAFETY: v < nv, and vertex v is owned by this cell only.
                        unsafe { pos.write(v as usize, p) };
                    }
                }
                if fmask[ci] == 0 {
                    return;
                }
                let built;
                let r = match rid[ci] {
                    MISS => {
                        built = Recipe::build(st, g.neighbourhood(row, z));
                        &built
                    }
                    i => rec.get(i),
                };
                // the owner cells of this cell's edges and corners, then
                // their ids: the owner's first id plus its owned ones below
                let mut own = [0usize; MAX_OWNERS + 1];
                own[0] = ci;
                for (o, &b) in own[1..].iter_mut().zip(&r.owners[..r.n_owners as usize]) {
                    *o = g.index_bit(row, z, b as usize);
                }
                let mut eid = [0u32; 12];
                for j in 0..r.n_edges as usize {
                    let oi = own[r.edge_slot[j] as usize];
                    eid[j] = eoff[oi] + ones16(emask[oi] & r.edge_below[j]);
                }
                let mut vid = [0u32; 8];
                for j in 0..r.n_verts as usize {
                    let oi = own[r.vert_slot[j] as usize];
                    vid[j] = voff[oi] + ones8(vmask[oi] & r.vert_below[j]);
                }
                for q in &r.faces[..r.n_faces as usize] {
                    let h = q.map(|c| 2 * eid[c.edge as usize] + c.neg as u32);
                    // SAFETY: a manifold boundary (checked in pass 1) has each
                    // grid-edge direction in exactly one face, so half-edge h
                    // and the v_out of its tail are written by this corner only;
                    // face f belongs to this slab.
                    unsafe {
                        f_start.write(f, h[0]);
                        for (e, c) in q.iter().enumerate() {
                            let (hn, v) = (h[(e + 1) % 4], vid[c.vert as usize]);
                            cols[0].write(h[e] as usize, hn);
                            cols[1].write(hn as usize, h[e]);
                            cols[2].write(h[e] as usize, v);
                            cols[3].write(h[e] as usize, f as u32);
                            if c.v_out {
                                v_out.write(v as usize, h[e]);
                            }
                        }
                    }
                    f += 1;
                }
            });
        });
    }
    crate::cancel::check()?;
    #[cfg(debug_assertions)]
    m.validate()?;
    Ok(m)
}

/// Set bits of every byte. The portable x86-64 target has no `popcnt`
/// instruction, and `count_ones` compiled to a bit-twiddling sequence that
/// took 15 % of a level-3 build under `perf`; a lookup is one load.
static ONES: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        t[i] = (i as u8).count_ones() as u8;
        i += 1;
    }
    t
};

#[inline]
fn ones8(x: u8) -> u32 {
    ONES[x as usize] as u32
}

#[inline]
fn ones16(x: u16) -> u32 {
    (ONES[(x & 0xff) as usize] + ONES[(x >> 8) as usize]) as u32
}

/// A raw pointer shared by the parallel writers of disjoint slots.
#[derive(Clone, Copy)]
struct SyncPtr<T>(*mut T);
unsafe impl<T: Send> Send for SyncPtr<T> {}
unsafe impl<T: Send> Sync for SyncPtr<T> {}
impl<T> SyncPtr<T> {
    /// # Safety
    /// `i` is in bounds and no other thread writes slot `i`.
    unsafe fn write(self, i: usize, v: T) {
        unsafe { self.0.add(i).write(v) }
    }
}

#[cfg(test)]
mod tests {
    use super::tables::manifold_patterns;
    use super::*;

    #[test]
    fn counts_genus_volume() {
        let genera = [0u64, 5, 81, 1409, 26433];
        for level in 0..=3u32 {
            let m = menger_sponge(level).unwrap();
            m.validate().unwrap();
            assert_eq!(m.n_faces() as u64, menger_sponge_faces(level));
            assert_eq!(m.n_edges(), 2 * m.n_faces());
            assert_eq!(m.n_components(), 1);
            assert_eq!(m.genus() as u64, menger_sponge_genus(level));
            assert_eq!(menger_sponge_genus(level), genera[level as usize]);
            assert_eq!(m.n_vertices() as i64, m.n_faces() as i64 + 2 - 2 * m.genus());
            let vol = 8.0 * (20.0f64 / 27.0).powi(level as i32);
            assert!((m.signed_volume() - vol).abs() < 1e-9 * vol, "level {level}: {}", m.signed_volume());
            assert_eq!(m.face_size_histogram().keys().copied().collect::<Vec<_>>(), vec![4]);
        }
        assert_eq!(menger_sponge_genus(4), genera[4]);
        assert!(menger_sponge(MAX_LEVEL + 1).is_err());
    }

    /// Every face as its cycle of positions (bit patterns), from its first corner.
    fn face_cycles(m: &Mesh) -> Vec<[[u64; 3]; 4]> {
        let pf = m.to_polygons();
        assert!(pf.sizes.iter().all(|&s| s == 4));
        let p = |v: u32| m.pos[v as usize].to_array().map(f64::to_bits);
        pf.indices.chunks(4).map(|q| [p(q[0]), p(q[1]), p(q[2]), p(q[3])]).collect()
    }

    #[test]
    fn same_mesh_as_the_grid_scan() {
        for level in 0..=3u32 {
            let new = menger_sponge(level).unwrap();
            let old = reference::menger_sponge_grid(level).unwrap();
            new.validate().unwrap();
            assert_eq!((new.n_vertices(), new.n_edges(), new.n_faces()), (old.n_vertices(), old.n_edges(), old.n_faces()));
            assert_eq!(new.genus(), old.genus());
            let key = |m: &Mesh| {
                let mut v: Vec<[u64; 3]> = m.pos.iter().map(|p| p.to_array().map(f64::to_bits)).collect();
                v.sort_unstable();
                v
            };
            assert_eq!(key(&new), key(&old), "level {level}: vertex sets differ");
            // same faces in the same order, each from the same first corner
            assert_eq!(face_cycles(&new), face_cycles(&old), "level {level}: faces differ");
        }
    }

    /// Recipes built on the spot (a neighbourhood missing from the table)
    /// give the same mesh as the table's, every column.
    #[test]
    fn recipes_built_on_the_spot_give_the_same_mesh() {
        for level in 0..=3u32 {
            let a = menger_sponge(level).unwrap();
            let b = build(level, &Recipes::empty()).unwrap();
            assert!(a == b && a.pos == b.pos, "level {level}");
        }
    }

    #[test]
    fn level_4_is_valid() {
        let m = menger_sponge(4).unwrap();
        m.validate().unwrap();
        assert_eq!(m.genus() as u64, menger_sponge_genus(4));
    }

    #[test]
    fn bit_counts_are_count_ones() {
        for x in 0..=u16::MAX {
            assert_eq!(ones16(x), x.count_ones(), "{x}");
        }
        for x in 0..=u8::MAX {
            assert_eq!(ones8(x), x.count_ones(), "{x}");
        }
    }

    #[test]
    fn vertex_windows() {
        let t = manifold_patterns();
        // one kept cell, or all but one: a disk
        for k in 0..8 {
            assert!(t[1 << k] && t[255 ^ (1 << k)]);
        }
        // two cells meeting at the point only, or along an edge only: pinched
        assert!(!t[0b1000_0001] && !t[0b0000_1001]);
        // two face neighbours: a disk
        assert!(t[0b0000_0011]);
    }
}

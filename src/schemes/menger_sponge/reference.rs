//! The grid-scan builder the sponge had before its output-time one (test
//! reference only): it scans all `27ⁿ` cells for exposed faces and all
//! `(3ⁿ + 1)³` grid points for vertices, then pairs corners by their
//! neighbour cells and builds through [`Mesh::from_corner_twins`], which
//! checks twins and vertex umbrellas. The tests compare the two.

use crate::error::{MeshError, Result};
use crate::mesh::Mesh;
use super::{menger_sponge_faces, MAX_LEVEL};
use glam::DVec3;
use rayon::prelude::*;

struct Grid {
    n: usize,
    /// Bitmask of the base-3 digit positions equal to 1, per coordinate.
    ones: Vec<u32>,
}

impl Grid {
    #[inline]
    fn kept(&self, x: i64, y: i64, z: i64) -> bool {
        let n = self.n as i64;
        if x < 0 || y < 0 || z < 0 || x >= n || y >= n || z >= n {
            return false;
        }
        let (a, b, c) = (self.ones[x as usize], self.ones[y as usize], self.ones[z as usize]);
        (a & b) | (b & c) | (a & c) == 0
    }
    #[inline]
    fn cell(&self, p: [i64; 3]) -> usize {
        (p[0] as usize * self.n + p[1] as usize) * self.n + p[2] as usize
    }
}

/// Direction `d` in 0..6: axis `d / 2`, negative for even `d`.
#[inline]
fn dir_vec(d: usize) -> [i64; 3] {
    let mut v = [0i64; 3];
    v[d / 2] = if d % 2 == 1 { 1 } else { -1 };
    v
}

#[inline]
fn add(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The 4 grid points of the face of cell `c` facing direction `d`,
/// counter-clockwise seen from outside.
#[inline]
fn quad(c: [i64; 3], d: usize) -> [[i64; 3]; 4] {
    let a = d / 2;
    let (u, v) = ((a + 1) % 3, (a + 2) % 3);
    let mut p = c;
    let mut eu = [0i64; 3];
    let mut ev = [0i64; 3];
    eu[u] = 1;
    ev[v] = 1;
    if d % 2 == 1 {
        p[a] += 1;
        [p, add(p, eu), add(add(p, eu), ev), add(p, ev)]
    } else {
        [p, add(p, ev), add(add(p, eu), ev), add(p, eu)]
    }
}

/// The sponge of `level` built by the grid scan.
pub(super) fn menger_sponge_grid(level: u32) -> Result<Mesh> {
    if level > MAX_LEVEL {
        return Err(MeshError::InvalidArgument(format!(
            "menger_sponge: level {level} is too large (at most {MAX_LEVEL}; level 6 has 128 M faces)"
        )));
    }
    let nf = menger_sponge_faces(level);
    let grid = 9 * (3u64.pow(level) + 1).pow(3);
    let c = crate::budget::Counts::plain(nf, 2 * nf, nf);
    crate::budget::check("menger_sponge", &format!("level {level}"), crate::budget::build_bytes(&c) + grid)?;
    let n = 3usize.pow(level);
    let ones: Vec<u32> = (0..n)
        .map(|t| {
            let (mut t, mut m, mut k) = (t, 0u32, 0);
            while t > 0 {
                if t % 3 == 1 {
                    m |= 1 << k;
                }
                t /= 3;
                k += 1;
            }
            m
        })
        .collect();
    let g = Grid { n, ones };
    let slab = n * n;

    // --- exposed-face mask per cell, face offsets per cell
    let mut mask = vec![0u8; n * slab];
    mask.par_chunks_mut(slab).enumerate().for_each(|(x, row)| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        for y in 0..n {
            for z in 0..n {
                let c = [x as i64, y as i64, z as i64];
                if !g.kept(c[0], c[1], c[2]) {
                    continue;
                }
                let mut m = 0u8;
                for d in 0..6 {
                    let q = add(c, dir_vec(d));
                    if !g.kept(q[0], q[1], q[2]) {
                        m |= 1 << d;
                    }
                }
                row[y * n + z] = m;
            }
        }
    });
    crate::cancel::check()?;
    let slab_faces: Vec<u32> = mask.par_chunks(slab).map(|r| r.iter().map(|m| m.count_ones()).sum()).collect();
    let mut slab_start = Vec::with_capacity(n + 1);
    slab_start.push(0usize);
    for &s in &slab_faces {
        slab_start.push(slab_start.last().unwrap() + s as usize);
    }
    let nf = slab_start[n];
    debug_assert_eq!(nf as u64, menger_sponge_faces(level));
    let mut off = vec![0u32; n * slab];
    off.par_chunks_mut(slab).enumerate().for_each(|(x, row)| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let mut k = slab_start[x] as u32;
        for (o, m) in row.iter_mut().zip(&mask[x * slab..(x + 1) * slab]) {
            *o = k;
            k += m.count_ones();
        }
    });
    crate::cancel::check()?;
    let face_id = |c: [i64; 3], d: usize| -> u32 {
        let i = g.cell(c);
        off[i] + (mask[i] & ((1u8 << d) - 1)).count_ones()
    };

    // --- vertices: grid points with kept and removed cells around them
    let gp = n + 1;
    let mut vid = vec![u32::MAX; gp * gp * gp];
    vid.par_chunks_mut(gp * gp).enumerate().for_each(|(x, row)| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        for y in 0..gp {
            for z in 0..gp {
                let (mut any_in, mut any_out) = (false, false);
                for k in 0..8 {
                    let c = (x as i64 - (k & 1) as i64, y as i64 - ((k >> 1) & 1) as i64, z as i64 - ((k >> 2) & 1) as i64);
                    if g.kept(c.0, c.1, c.2) {
                        any_in = true;
                    } else {
                        any_out = true;
                    }
                }
                if any_in && any_out {
                    row[y * gp + z] = 0;
                }
            }
        }
    });
    crate::cancel::check()?;
    let mut nv = 0u32;
    for (i, v) in vid.iter_mut().enumerate() {
        crate::cancel::poll(i)?;
        if *v == 0 {
            *v = nv;
            nv += 1;
        }
    }
    let scale = 2.0 / n as f64;
    let mut pos = vec![DVec3::ZERO; nv as usize];
    {
        let pos_ptr = SyncPtr(pos.as_mut_ptr());
        vid.par_chunks(gp * gp).enumerate().for_each(|(x, row)| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            for y in 0..gp {
                for z in 0..gp {
                    let v = row[y * gp + z];
                    if v != u32::MAX {
                        let p = DVec3::new(x as f64, y as f64, z as f64) * scale - DVec3::ONE;
                        // SAFETY: every grid point has its own id, so writes never alias.
                        unsafe { pos_ptr.write(v as usize, p) };
                    }
                }
            }
        });
    }
    crate::cancel::check()?;
    let vid_of = |p: [i64; 3]| vid[(p[0] as usize * gp + p[1] as usize) * gp + p[2] as usize];

    // --- corners and twins, slab by slab
    let mut cv = vec![0u32; 4 * nf];
    let mut tw = vec![0u32; 4 * nf];
    let mut chunks = Vec::with_capacity(n);
    {
        let (mut rc, mut rt) = (&mut cv[..], &mut tw[..]);
        for x in 0..n {
            let len = 4 * slab_faces[x] as usize;
            let (a, b) = std::mem::take(&mut rc).split_at_mut(len);
            let (c, d) = std::mem::take(&mut rt).split_at_mut(len);
            chunks.push((x, a, c));
            rc = b;
            rt = d;
        }
    }
    crate::cancel::check()?;
    let bad = std::sync::atomic::AtomicBool::new(false);
    chunks.into_par_iter().for_each(|(x, cvs, tws)| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let mut k = 0usize;
        for y in 0..n {
            for z in 0..n {
                let c = [x as i64, y as i64, z as i64];
                let m = mask[g.cell(c)];
                for d in 0..6 {
                    if m & (1 << d) == 0 {
                        continue;
                    }
                    let q = quad(c, d);
                    let nrm = dir_vec(d);
                    for e in 0..4 {
                        let (p0, p1) = (q[e], q[(e + 1) % 4]);
                        cvs[k + e] = vid_of(p0);
                        // the in-plane axis across the edge and its side
                        let b = (0..3).find(|&i| p0[i] != p1[i]).unwrap();
                        let ax = 3 - d / 2 - b;
                        let side = if p0[ax] == c[ax] + 1 { 1 } else { 0 };
                        let u_dir = 2 * ax + side;
                        let u = dir_vec(u_dir);
                        let c1 = add(c, u);
                        let c2 = add(c1, nrm);
                        let k1 = g.kept(c1[0], c1[1], c1[2]);
                        let (nc, nd) = if g.kept(c2[0], c2[1], c2[2]) {
                            if !k1 {
                                bad.store(true, std::sync::atomic::Ordering::Relaxed);
                            }
                            (c2, u_dir ^ 1) // concave: the neighbour's face looking back
                        } else if k1 {
                            (c1, d) // coplanar
                        } else {
                            (c, u_dir) // convex: this cell's side face
                        };
                        let nq = quad(nc, nd);
                        let j = (0..4).find(|&j| nq[j] == p1 && nq[(j + 1) % 4] == p0).unwrap_or(0);
                        tws[k + e] = 4 * face_id(nc, nd) + j as u32;
                    }
                    k += 4;
                }
            }
        }
    });
    if bad.into_inner() {
        return Err(MeshError::Invariant("menger_sponge: two cells meet along an edge only (non-manifold)".into()));
    }
    crate::cancel::check()?;
    Mesh::from_corner_twins(pos, &vec![4u32; nf], &cv, &tw)
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

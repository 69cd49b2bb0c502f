//! The dual of a keyed output without building the output first (issue
//! 16): most of the catalog's compositions end with a dual (Hart's
//! `t = dkd`, `z = dk`, `j = da`, `s = dg`, `b = dkda`, `o = dee`, `v = dwd`;
//! TopMod's "dual + X + dual"), and building the mesh only to walk around
//! its vertices once doubled their cost.
//!
//! [`Out::finish_dual`] gives exactly `dual(out.finish())`: the same
//! positions (face centroids summed from each face's first corner), the
//! same vertex, half-edge and face order, the same `v_out` and `f_start`
//! (`crate::schemes::dual`'s one-pass walk, whose numbering is
//! `from_corner_twins`'): test builds compare the two at every call.
//!
//! One pass over the corners pairs the sides by key (and checks their
//! directions) and links every corner to the next one around its vertex:
//! around a vertex the corner after `g` is `twin(prev g)`, so when the
//! sides of corners `a` and `c` pair, the corner after `a` in its face
//! follows `c` around their common vertex and vice versa. A walk around
//! every vertex in order then writes the dual's columns; a vertex whose
//! corners form more than one cycle (not a disk) leaves corners unwalked,
//! which is reported as [`MeshError::NonManifoldVertex`], as `finish` does.

use super::{opposite, step_by, Out};
use crate::error::{MeshError, Result};
use crate::mesh::{Columns, Mesh, NONE};
use crate::schemes::face_parents;
use crate::schemes::hosts::check_output_size;
use glam::DVec3;

impl Out {
    /// `dual(self.finish(scheme))` in one go (see the module docs); while a
    /// face parents trace records, it records the two steps `finish` and
    /// `dual` would.
    pub fn finish_dual(mut self, scheme: &str) -> Result<Mesh> {
        #[cfg(test)]
        let reference = face_parents::paused(|| self.clone().finish(scheme).and_then(|m| crate::schemes::dual::dual(&m)));
        let trace = self.src.take().map(|s| (s, self.input, self.keep, self.vsrc.take()));
        let (nv, nf) = (self.pos.len(), self.sizes.len());
        let out = self.dual_direct(scheme, trace.is_some());
        if let (Some((src, input, keep, vsrc)), Ok((_, Some(ff)))) = (trace, &out) {
            face_parents::record(step_by(nv, |w| ff[w], src, input, keep, vsrc));
            // the dual's face w is born around vertex w, its vertex f is face f's centroid
            let v = face_parents::VERT;
            face_parents::record(Some(face_parents::Step { in_v: nv, in_f: nf, face: (0..nv as u32).map(|i| v | i).collect(), vertex: (0..nf as u32).collect() }));
        }
        let out = out.map(|(m, _)| m);
        #[cfg(test)]
        match (&out, &reference) {
            (Ok(a), Ok(b)) => assert!(a == b && a.pos.iter().zip(&b.pos).all(|(p, q)| p.to_array().map(f64::to_bits) == q.to_array().map(f64::to_bits)), "{scheme}: finish_dual differs from dual(finish)"),
            (Err(_), Err(_)) => {}
            _ => panic!("{scheme}: finish_dual {:?}, dual(finish) {:?}", out.as_ref().err(), reference.as_ref().err()),
        }
        out
    }

    /// The dual's mesh and, when `first_faces`, the face of every output
    /// vertex's first corner (for the face parents trace).
    fn dual_direct(self, scheme: &str, first_faces: bool) -> Result<(Mesh, Option<Vec<u32>>)> {
        let n = self.cv.len();
        let nv = self.pos.len();
        let nf = self.sizes.len();
        // the dual has a vertex per face and a face per vertex
        check_output_size(scheme, n, nf)?;
        crate::cancel::check()?;
        let bad = |k: u32| MeshError::Invariant(format!("{scheme}: output edge {k} does not have exactly two sides (a bug in the scheme)"));
        // slot[k]: 0 unused; after the first side (corner a, followed in its
        // face by corner an) `a + 1 | an << 32`; DONE after the second
        const DONE: u64 = u64::MAX;
        let mut slot = vec![0u64; self.n_keys];
        // per corner: the next corner around its vertex, the key of the side
        // before it in its face (the edge the dual side leaving it crosses),
        // its face; one array, so the walk below reads one place per corner
        let mut cr = vec![[0u32; 3]; n];
        let mut vfirst = vec![NONE; nv];
        let mut pos = Vec::with_capacity(nf);
        let mut pairs = 0usize;
        let mut s = 0usize;
        for (f, &size) in self.sizes.iter().enumerate() {
            crate::cancel::poll(f)?;
            if size == 0 {
                return Err(MeshError::EmptyFace { face: f });
            }
            let e = s + size as usize;
            let mut sum = DVec3::ZERO;
            for c in s..e {
                let v = self.cv[c];
                let nx = if c + 1 < e { c + 1 } else { s };
                let pv = if c > s { c - 1 } else { e - 1 };
                let w = self.cv[nx];
                // the centroid as `face_centroids` sums it: from the first corner
                sum += *self.pos.get(v as usize).ok_or_else(|| MeshError::InvalidArgument(format!("face {f}: corner {c} refers to vertex {v} out of range")))?;
                let vf = &mut vfirst[v as usize];
                if *vf == NONE {
                    *vf = c as u32; // the vertex's first corner: finish's v_out
                }
                cr[c][1] = self.key[pv];
                cr[c][2] = f as u32;
                let k = self.key[c];
                let sl = slot.get_mut(k as usize).ok_or_else(|| bad(k))?;
                match *sl {
                    0 => *sl = (c as u64 + 1) | (nx as u64) << 32,
                    DONE => return Err(bad(k)),
                    o => {
                        *sl = DONE;
                        let (a, an) = ((o as u32 - 1) as usize, (o >> 32) as usize);
                        // opposite directions: this side runs from a's head to a's tail
                        if self.cv[an] != v || self.cv[a] != w {
                            return Err(opposite(scheme, k));
                        }
                        // the corner after a side's head, around that vertex, is its twin's
                        cr[nx][0] = a as u32;
                        cr[an][0] = c as u32;
                        pairs += 1;
                    }
                }
            }
            pos.push(sum / size as f64);
            s = e;
        }
        if 2 * pairs != n {
            let k = slot.iter().position(|&s| s != 0 && s != DONE).unwrap_or(0);
            return Err(bad(k as u32));
        }
        if let Some(v) = vfirst.iter().position(|&c| c == NONE) {
            return Err(MeshError::InvalidArgument(format!("vertex {v} is not used by any face")));
        }
        crate::cancel::check()?;
        // the walk: output face w lists w's corners from its first one; the
        // side leaving corner c crosses the edge keyed cr[c][1], whose first
        // visit numbers the output edge (every used slot is DONE here)
        let mut cols = Columns::new(pos, n, nv);
        cols.v_out.fill(NONE);
        let mut ne = 0u32;
        let mut walked = 0usize;
        for (w, &s) in vfirst.iter().enumerate() {
            crate::cancel::poll(w)?;
            let (mut c, mut last) = (s as usize, NONE);
            loop {
                let [r, k, f] = cr[c];
                let sl = &mut slot[k as usize];
                let i = if *sl == DONE {
                    *sl = ne as u64;
                    ne += 1;
                    2 * (ne - 1)
                } else {
                    2 * *sl as u32 + 1
                };
                cols.he_vert[i as usize] = f;
                cols.he_face[i as usize] = w as u32;
                let o = &mut cols.v_out[f as usize];
                if *o == NONE {
                    *o = i;
                }
                if last == NONE {
                    cols.f_start[w] = i;
                } else {
                    cols.he_next[last as usize] = i;
                    cols.he_prev[i as usize] = last;
                }
                last = i;
                walked += 1;
                c = r as usize;
                if c == s as usize {
                    break;
                }
            }
            let first = cols.f_start[w];
            cols.he_next[last as usize] = first;
            cols.he_prev[first as usize] = last;
        }
        if walked != n {
            // some vertex's corners form several cycles: name the first
            let mut deg = vec![0usize; nv];
            self.cv.iter().for_each(|&v| deg[v as usize] += 1);
            let cycle = |s: u32| {
                let (mut c, mut k) = (cr[s as usize][0], 1);
                while c != s {
                    c = cr[c as usize][0];
                    k += 1;
                }
                k
            };
            let v = (0..nv).find(|&v| cycle(vfirst[v]) != deg[v]).unwrap_or(0);
            return Err(MeshError::NonManifoldVertex { vertex: v });
        }
        let ff = first_faces.then(|| vfirst.iter().map(|&c| cr[c as usize][2]).collect());
        Ok((Mesh::from_columns(cols)?, ff))
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    /// A vertex whose corners form two cycles (two tetrahedra sharing a
    /// vertex, as faces of one output) is refused by both builders alike.
    #[test]
    fn refuses_a_pinched_vertex() {
        let mut pos = vec![DVec3::ZERO; 7];
        for (i, p) in pos.iter_mut().enumerate() {
            *p = DVec3::new(i as f64, (i * i) as f64, (i % 3) as f64);
        }
        // two tetrahedra 0123 and 0456, keys per directed edge pair
        let tets = [[0u32, 1, 2, 3], [0, 4, 5, 6]];
        let build = || {
            let mut o = super::Out::new(pos.clone(), 12, 8, 24);
            for (t, q) in tets.iter().enumerate() {
                let [a, b, c, d] = *q;
                let key = |x: u32, y: u32| {
                    let local = |v: u32| [a, b, c, d].iter().position(|&u| u == v).unwrap() as u32;
                    let (i, j) = (local(x).min(local(y)), local(x).max(local(y)));
                    6 * t as u32 + i * (7 - i) / 2 + j - i - 1
                };
                for f in [[a, b, c], [a, c, d], [a, d, b], [b, d, c]] {
                    o.face((0..3).map(|i| (f[i], key(f[i], f[(i + 1) % 3]))));
                }
            }
            o
        };
        assert!(matches!(build().finish("test"), Err(crate::error::MeshError::NonManifoldVertex { vertex: 0 })));
        assert!(matches!(build().finish_dual("test"), Err(crate::error::MeshError::NonManifoldVertex { vertex: 0 })));
    }
}

//! Doo-Sabin subdivision (D. Doo & M. Sabin, "Behaviour of recursive division
//! surfaces near extraordinary points", CAD 10(6), 1978), one level.
//!
//! Mask: Doo & Sabin's weights. Corner k of an n-gon with corners
//! `x₀ … x_{n−1}` gets the new point `Σᵢ αᵢ₋ₖ xᵢ`, with
//! `α₀ = 1/4 + 5/(4n)` and `αᵢ = (3 + 2 cos(2πi/n))/(4n)` (i ≠ 0).
//! Computed in O(n) per face (one `sin_cos` per face, the multiples by
//! rotation) as
//! `x_k/4 + 3/(4n) Σ x + 1/(2n) (cos θ_k C + sin θ_k S)`, `θ_k = 2πk/n`,
//! `C = Σ cos θᵢ xᵢ`, `S = Σ sin θᵢ xᵢ`. The weights sum to 1 for n ≥ 2; a
//! one-gon's point is its vertex.
//!
//! Connectivity (the dual host): one new vertex per corner; each old n-gon
//! gives an n-gon of its corner points (F-face), each old edge a quad
//! (E-face) and each old valence-k vertex a k-gon (V-face). Self-loops and
//! two-gons need nothing special: a zero-length self-loop (Sierpinski
//! output) separates corners of two different faces, whose points differ,
//! so the loop opens into a tube (the Sierpinski paper, §6 and Fig. 11–14).
//!
//! Counts (H = 2E): V' = H, E' = 2H = 4E, F' = F + E + V; every new vertex is
//! 4-valent. Output vertex `c` is the corner `c` in face order; faces are
//! laid out `[F-faces | E-faces | V-faces]`.
//!
//! Stencils and correspondence ([`doo_sabin_level`]): the scheme is linear;
//! the row of corner k of an n-gon is `Σᵢ αᵢ₋ₖ xᵢ` (n terms). Origins: an
//! output element comes from the lowest-dimensional input element it lies
//! in: a corner point lies inside its face → (FACE, f) (not its vertex: it
//! is a point of the face's refinement, one per corner); the F-face of f →
//! (FACE, f), the E-face of e → (EDGE, e), the V-face of v → (VERTEX, v);
//! an F-face's sides lie inside f → (FACE, f), the other edges (between an
//! E-face and a V-face) cross edge e → (EDGE, e).

use super::hosts::{check_output_size, edge_origins_by_corner, refuse_holes, with_point_spheres, FaceLayout, SyncPtr, VertexLayout, MIN_LEN};
use super::level::{with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// One level of Doo-Sabin subdivision. See the module docs.
pub fn doo_sabin(m: &Mesh) -> Result<Mesh> {
    with_point_spheres("doo_sabin", m, step)
}

/// Doo & Sabin's weight αᵢ for an n-gon.
pub fn doo_sabin_weight(n: usize, i: usize) -> f64 {
    let nf = n as f64;
    let w = (3.0 + 2.0 * (std::f64::consts::TAU * i as f64 / nf).cos()) / (4.0 * nf);
    if i == 0 {
        w + 0.25
    } else {
        w
    }
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("doo_sabin", 4 * m.n_halfedges(), m.n_halfedges())?;
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (next, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;

    // --- positions: per face Σx, C, S, then per corner
    let sums: Vec<[DVec3; 3]> = (0..nf)
        .into_par_iter()
        .with_min_len(MIN_LEN)
        .map(|f| {
            let mut s = [DVec3::ZERO; 3];
            if crate::cancel::requested() {
                return s; // the check below reports it
            }
            let hs = fl.corners(f);
            let n = hs.len();
            let (ds, dc) = (std::f64::consts::TAU / n as f64).sin_cos();
            let (mut cs, mut sn) = (1.0, 0.0);
            for &h in hs {
                let x = p[vert[h as usize] as usize];
                s[0] += x;
                s[1] += x * cs;
                s[2] += x * sn;
                // (cos, sin) of the next multiple of 2π/n
                (cs, sn) = (cs * dc - sn * ds, sn * dc + cs * ds);
            }
            s
        })
        .collect();
    crate::cancel::check()?;
    let mut pos = vec![DVec3::ZERO; nh];
    // corner c belongs to the face whose range holds it: walk faces in parallel
    // by splitting the buffer along face offsets
    let mut chunks: Vec<&mut [DVec3]> = Vec::with_capacity(nf);
    let mut rest: &mut [DVec3] = &mut pos;
    for f in 0..nf {
        crate::cancel::poll(f)?;
        let (a, b) = rest.split_at_mut(fl.degree(f));
        chunks.push(a);
        rest = b;
    }
    chunks.into_par_iter().with_min_len(MIN_LEN).enumerate().for_each(|(f, out)| {
        if crate::cancel::requested() {
            return; // the check after the loop reports it
        }
        let hs = fl.corners(f);
        let n = hs.len();
        if n == 1 {
            out[0] = p[vert[hs[0] as usize] as usize];
            return;
        }
        let nf64 = n as f64;
        let [s, c, sn] = sums[f];
        let base = s * (0.75 / nf64);
        let (ds, dc) = (std::f64::consts::TAU / nf64).sin_cos();
        let (mut ck, mut sk) = (1.0, 0.0);
        for (k, &h) in hs.iter().enumerate() {
            out[k] = p[vert[h as usize] as usize] * 0.25 + base + (c * ck + sn * sk) * (0.5 / nf64);
            (ck, sk) = (ck * dc - sk * ds, sk * dc + ck * ds);
        }
    });

    crate::cancel::check()?;
    // --- connectivity
    let (hu, eu) = (nh as u32, ne as u32);
    let vbase = hu + 4 * eu;
    let nc = 2 * nh + 4 * ne;
    let mut cv = vec![0u32; nc];
    let mut tw = vec![0u32; nc];
    let mut sizes = Vec::with_capacity(nf + ne + nv);
    sizes.extend((0..nf).map(|f| fl.degree(f) as u32));
    sizes.extend(std::iter::repeat(4u32).take(ne));
    sizes.extend((0..nv).map(|v| vl.valence(v)));
    let cidx = &fl.cidx;
    {
        let (cf, rest_c) = cv.split_at_mut(nh);
        let (ce, cvf) = rest_c.split_at_mut(4 * ne);
        let (tf, rest_t) = tw.split_at_mut(nh);
        let (te, tvf) = rest_t.split_at_mut(4 * ne);
        // F-faces: corner c is vertex c
        cf.par_iter_mut().zip(tf.par_iter_mut()).with_min_len(MIN_LEN).enumerate().for_each(|(c, (v, t))| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let h = fl.fh[c];
            *v = c as u32;
            *t = hu + 4 * (h >> 1) + 2 * (h & 1);
        });
        // E-faces [p(next a), p(a), p(next b), p(b)]
        ce.par_chunks_mut(4).zip(te.par_chunks_mut(4)).with_min_len(MIN_LEN).enumerate().for_each(|(e, (v, t))| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let (a, b) = (2 * e, 2 * e + 1);
            let (na, nb) = (next[a] as usize, next[b] as usize);
            v[0] = cidx[na];
            v[1] = cidx[a];
            v[2] = cidx[nb];
            v[3] = cidx[b];
            t[0] = cidx[a];
            t[1] = vbase + vl.vidx[nb];
            t[2] = cidx[b];
            t[3] = vbase + vl.vidx[na];
        });
        // V-faces in rotation order: corner of x, twin on the E-face of rotate(x)
        let (cvf, tvf) = (SyncPtr(cvf.as_mut_ptr()), SyncPtr(tvf.as_mut_ptr()));
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|x| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let slot = vl.vidx[x] as usize;
            let r = prev[x] ^ 1;
            // SAFETY: vidx is a permutation of 0..nh, so every slot is written once.
            unsafe {
                *cvf.get().add(slot) = cidx[x];
                *tvf.get().add(slot) = hu + 4 * (r >> 1) + 1 + 2 * (r & 1);
            }
        });
    }
    crate::cancel::check()?;
    Mesh::from_corner_twins(pos, &sizes, &cv, &tw)
}

/// One level with what `req` asks for (see the module docs); without
/// requests it is [`doo_sabin`].
pub fn doo_sabin_level(m: &Mesh, req: &Request) -> Result<Level> {
    refuse_holes("doo_sabin", m)?;
    with_point_spheres_level(m, req, |m, req| {
        let mesh = step(m)?;
        if !req.stencils && !req.origins {
            return Ok(Level::plain(mesh));
        }
        let fl = FaceLayout::new(m)?;
        let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
        let (_, vert, face) = m.halfedge_columns();
        let stencils = if req.stencils {
            Some(Stencils::build(nh, nv, |c, row| {
                let f = face[fl.fh[c] as usize] as usize;
                let hs = fl.corners(f);
                let (n, k) = (hs.len(), c - fl.off[f] as usize);
                for (i, &h) in hs.iter().enumerate() {
                    row.add(vert[h as usize], if n == 1 { 1.0 } else { doo_sabin_weight(n, (i + n - k) % n) });
                }
            })?)
        } else {
            None
        };
        let origins = if req.origins {
            let mut o = Origins::with_capacity(nh, mesh.n_edges(), nf + ne + nv);
            o.vertex_kind = vec![FACE; nh];
            o.vertex.extend(fl.fh.iter().map(|&h| face[h as usize]));
            o.face_kind.extend(std::iter::repeat(FACE).take(nf).chain(std::iter::repeat(EDGE).take(ne)).chain(std::iter::repeat(VERTEX).take(nv)));
            o.face.extend((0..nf as u32).chain(0..ne as u32).chain(0..nv as u32));
            // corners: [F-faces (fh order) | E-faces, 4 per edge | V-faces]; the V-face sides are
            // the E-faces' sides 1 and 3, so they cross edges too
            let (ef, vf) = (nh, nh + 4 * ne);
            let vl = VertexLayout::new(m)?;
            let mut slot_he = vec![0u32; nh];
            for h in 0..nh {
                slot_he[vl.vidx[h] as usize] = h as u32;
            }
            edge_origins_by_corner(&mesh, &mut o, |c| {
                if c < ef {
                    (FACE, face[fl.fh[c] as usize])
                } else if c < vf {
                    let (e, k) = ((c - ef) / 4, (c - ef) % 4);
                    match k {
                        0 => (FACE, face[2 * e]),
                        2 => (FACE, face[2 * e + 1]),
                        _ => (EDGE, e as u32),
                    }
                } else {
                    // slot of x: its side pairs with the E-face of rotate(x)
                    let r = m.he_prev[slot_he[c - vf] as usize] ^ 1;
                    (EDGE, r >> 1)
                }
            })?;
            Some(o)
        } else {
            None
        };
        Ok(Level { mesh, stencils, origins, creases: None })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn weights_sum_to_one() {
        for n in 2..12 {
            let s: f64 = (0..n).map(|i| doo_sabin_weight(n, i)).sum();
            assert!((s - 1.0).abs() < 1e-14, "n = {n}");
        }
    }

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(doo_sabin, |_, (v, e, f)| (2 * e, 4 * e, f + e + v), |name, m, r| {
            let ps = n_point_spheres(m);
            let mut want = face_sizes(m);
            want.truncate(m.n_faces() - ps);
            want.extend(std::iter::repeat(4).take(m.n_edges()));
            want.extend(m.vertices().filter(|&x| m.point_sphere_face(x).is_none()).map(|x| m.valence(x)));
            want.sort();
            let mut got = face_sizes(r);
            got.truncate(r.n_faces() - ps);
            got.sort();
            assert_eq!(got, want, "{name} face sizes");
        });
    }

    #[test]
    fn level_equals_plain_on_corpus() {
        level_matches_plain_on_corpus(doo_sabin, doo_sabin_level, |name, m, lv| {
            let o = lv.origins.as_ref().unwrap();
            let fl = FaceLayout::new(m).unwrap();
            let (fv, ff, fe) = (
                origin_counts(&o.vertex_kind, &o.vertex, FACE, m.n_faces()),
                origin_counts(&o.face_kind, &o.face, FACE, m.n_faces()),
                origin_counts(&o.edge_kind, &o.edge, FACE, m.n_faces()),
            );
            for f in 0..m.n_faces() {
                let point = is_point_face(m, f);
                // n corner points and n F-face sides per n-gon; a point-sphere keeps its vertex
                assert_eq!((fv[f], ff[f], fe[f]), (fl.degree(f), 1, fl.degree(f)), "{name} face {f} {point}");
            }
            assert!(origin_counts(&o.face_kind, &o.face, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
            assert!(origin_counts(&o.edge_kind, &o.edge, EDGE, m.n_edges()).iter().all(|&c| c == 2), "{name}");
            let vf = origin_counts(&o.face_kind, &o.face, VERTEX, m.n_vertices());
            assert!(vf.iter().enumerate().all(|(v, &c)| c == usize::from(m.v_out[v] & crate::mesh::POINT == 0)), "{name}");
            let kinds = |k: &[u8], kind: u8| k.iter().filter(|&&x| x == kind).count();
            let ps = n_point_spheres(m);
            assert_eq!(kinds(&o.vertex_kind, FACE), m.n_halfedges(), "{name}");
            assert_eq!(kinds(&o.vertex_kind, VERTEX), ps, "{name}");
            assert_eq!((kinds(&o.face_kind, FACE), kinds(&o.face_kind, EDGE), kinds(&o.face_kind, VERTEX)), (m.n_faces(), m.n_edges(), m.n_vertices() - ps), "{name}");
        });
    }

    #[test]
    fn level_refuses_holes() {
        match doo_sabin_level(&cube_with_hole(), &Request::plain()) {
            Err(crate::error::MeshError::Precondition(msg)) => assert!(msg.starts_with("doo_sabin") && msg.contains("no boundary rules"), "{msg}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn matches_direct_weights() {
        let m = crate::primitives::dodecahedron();
        let r = doo_sabin(&m).unwrap();
        let fl = FaceLayout::new(&m).unwrap();
        for f in 0..m.n_faces() {
            let hs = fl.corners(f);
            let n = hs.len();
            for k in 0..n {
                let want: DVec3 = (0..n).map(|i| m.positions()[m.vertex(crate::HalfedgeId(hs[i])).idx()] * doo_sabin_weight(n, (i + n - k) % n)).sum();
                assert!((r.positions()[fl.off[f] as usize + k] - want).length() < 1e-13);
            }
        }
    }

    #[test]
    fn handle_self_loop_opens() {
        let m = cube_with_handle_loop();
        let r = doo_sabin(&m).unwrap();
        // no two corner points coincide
        let p = r.positions();
        for i in 0..p.len() {
            for j in 0..i {
                assert!((p[i] - p[j]).length() > 1e-6, "{i} {j}");
            }
        }
    }
}

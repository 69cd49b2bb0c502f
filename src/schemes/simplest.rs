//! The simplest subdivision scheme (J. Peters & U. Reif, "The simplest
//! subdivision scheme for smoothing polyhedra", ACM TOG 16(4), 1997), one
//! level: mid-edge subdivision.
//!
//! What is implemented, exactly: every new vertex is the midpoint of an old
//! edge (a self-loop's midpoint is its vertex); every new vertex is joined to
//! the midpoints of the four edges that follow and precede its edge in the two
//! faces beside it. Each old n-gon becomes the n-gon of its edge midpoints
//! (F-face) and each old valence-k vertex the k-gon of the midpoints around
//! it (V-face), which cuts every vertex off at the edge midpoints ("connect
//! every edge midpoint to its four neighbouring edge midpoints", the paper's
//! abstract). On a regular quad mesh two steps are one binary refinement of
//! the four-direction (Zwart–Powell) box spline. The paper's improved weights for the
//! extraordinary (non-4-sided) faces are *not* applied: every new point is a
//! plain midpoint, so one step is exactly the rectification (medial
//! polyhedron) of the input.
//!
//! Counts (H = 2E): V' = E, E' = H = 2E, F' = F + V; every new vertex is
//! 4-valent. Output vertex e is the midpoint of edge e; faces are
//! `[F-faces | V-faces]`.
//!
//! Stencils and correspondence ([`simplest_level`]): the scheme is linear,
//! a row is `½ a + ½ b`. Origins: the midpoint of e → (EDGE, e); the F-face
//! of f → (FACE, f), the V-face of v → (VERTEX, v); every output edge lies
//! inside one input face (it cuts a corner of it) → (FACE, that face).
//! Open meshes: the paper has no boundary rule, and the plain mid-edge rule
//! at a boundary would replace the boundary polygon by its midpoint polygon
//! at every level (the hole keeps its n sides and shrinks towards a point).
//! topomesh keeps the boundary polyline instead, the convention of Blender's
//! *keep boundaries* it also uses for [`super::dual`] (the mid-edge step is a
//! rectification, dual-like): a boundary vertex stays, as a corner of its
//! V-face, and boundary edges are split at their midpoints. With E_b
//! boundary edges, V_b boundary vertices and h holes: V' = E + V_b,
//! E' = 2E + E_b, F' = F + V (the holes stay holes, each of n sides now
//! 2n). The boundary is interpolated as a polyline (a crease), the interior
//! is smoothed as on closed meshes.

use super::hosts::{check_output_size, refuse_holes, with_point_spheres, FaceLayout, VertexLayout, MIN_LEN};
use super::corner_origins::edge_origins_by_corner;
use super::level::{with_point_spheres_level, Level, Origins, Request, EDGE, FACE, VERTEX};
use super::stencil::Stencils;
use crate::error::Result;
use crate::mesh::{Columns, Mesh};
use glam::DVec3;
use rayon::prelude::*;

/// One level of mid-edge ("simplest") subdivision. See the module docs.
pub fn simplest(m: &Mesh) -> Result<Mesh> {
    refuse_holes("simplest", m)?;
    with_point_spheres("simplest", m, step)
}

fn step(m: &Mesh) -> Result<Mesh> {
    check_output_size("simplest", 2 * m.n_halfedges(), m.n_edges())?;
    let fl = FaceLayout::new(m)?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;
    let pos: Vec<_> = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        // cancelled: zeros, the check below reports it
        if crate::cancel::requested() {
            DVec3::ZERO
        } else {
            (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5
        }
    }).collect();
    crate::cancel::check()?;
    // Connectivity straight into the columns (issue 19), numbered exactly as
    // `from_corner_twins` numbered the corners `[F-corners | V-slots]` it was
    // given (the `output_hashes` test holds it to that). Every F-corner c
    // (half-edge h = fh[c], side m(h) → m(next h)) precedes its twin, a
    // V-slot, so it is the first corner of edge c: it gets half-edge 2c and
    // its twin 2c + 1, the side m(x) → m(prev x) of the V-face of vert[x]
    // with x = next h (inside face[h], cutting its corner at vert[x]).
    // Walking on: the F-face goes to next h; the V-face rotates x to
    // prev[x] ^ 1 = h ^ 1, whose slot side starts the edge of prev(h ^ 1).
    // So each pair (2c, 2c + 1) is a lookup, written in order.
    let mut cols = Columns::new(pos, 2 * nh, nf + nv);
    let nfu = nf as u32;
    cols.he_next
        .par_chunks_exact_mut(2)
        .zip(cols.he_prev.par_chunks_exact_mut(2))
        .zip(cols.he_vert.par_chunks_exact_mut(2))
        .zip(cols.he_face.par_chunks_exact_mut(2))
        .with_min_len(MIN_LEN)
        .enumerate()
        .for_each(|(c, (((hn, hp), hv), hf))| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let h = fl.fh[c] as usize;
            let x = next[h] as usize;
            let ci = |k: u32| 2 * fl.cidx[k as usize];
            hn[0] = ci(x as u32);
            hp[0] = ci(prev[h]);
            hv[0] = (h >> 1) as u32;
            hf[0] = face[h];
            hn[1] = ci(prev[h ^ 1]) + 1;
            // the slot before x's in its rotation is next(x ^ 1)'s, whose side starts the edge of x ^ 1
            hp[1] = ci((x ^ 1) as u32) + 1;
            hv[1] = (x >> 1) as u32;
            hf[1] = nfu + vert[x];
        });
    crate::cancel::check()?;
    // a face starts at its first corner: F-face f at corner off[f], V-face v
    // at the slot of v_out[v] (the layout starts every rotation there)
    let (fs_f, fs_v) = cols.f_start.split_at_mut(nf);
    fs_f.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(f, s)| *s = 2 * fl.off[f]);
    fs_v.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(v, s)| *s = 2 * fl.cidx[prev[m.v_out[v] as usize] as usize] + 1);
    // midpoint e is first seen at the lower of its two F-corners (every
    // F-corner comes before every V-slot)
    cols.v_out.par_iter_mut().with_min_len(MIN_LEN).enumerate().for_each(|(e, o)| *o = 2 * fl.cidx[2 * e].min(fl.cidx[2 * e + 1]));
    Mesh::from_columns(cols)
}

/// The builder [`step`] replaced (corners and twins through
/// [`Mesh::from_corner_twins`]), kept as the reference it must equal.
#[cfg(test)]
fn step_via_twins(m: &Mesh) -> Result<Mesh> {
    check_output_size("simplest", 2 * m.n_halfedges(), m.n_edges())?;
    let fl = FaceLayout::new(m)?;
    let vl = VertexLayout::new(m)?;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    let (next, vert, _) = m.halfedge_columns();
    let prev = &m.he_prev;
    let p = &m.pos;
    let pos: Vec<_> = (0..ne).into_par_iter().with_min_len(MIN_LEN).map(|e| {
        // cancelled: zeros, the check below reports it
        if crate::cancel::requested() {
            DVec3::ZERO
        } else {
            (p[vert[2 * e] as usize] + p[vert[2 * e + 1] as usize]) * 0.5
        }
    }).collect();
    crate::cancel::check()?;
    let hu = nh as u32;
    let mut cv = vec![0u32; 2 * nh];
    let mut tw = vec![0u32; 2 * nh];
    {
        let (cf, cvf) = cv.split_at_mut(nh);
        let (tf, tvf) = tw.split_at_mut(nh);
        cf.par_iter_mut().zip(tf.par_iter_mut()).with_min_len(MIN_LEN).enumerate().for_each(|(c, (v, t))| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let h = fl.fh[c];
            *v = h >> 1;
            *t = hu + vl.vidx[next[h as usize] as usize];
        });
        let (pc, pt) = (super::hosts::SyncPtr(cvf.as_mut_ptr()), super::hosts::SyncPtr(tvf.as_mut_ptr()));
        (0..nh).into_par_iter().with_min_len(MIN_LEN).for_each(|x| {
            if crate::cancel::requested() {
                return; // the check after the loop reports it
            }
            let slot = vl.vidx[x] as usize;
            // SAFETY: vidx is a permutation of 0..nh.
            unsafe {
                *pc.get().add(slot) = (x >> 1) as u32;
                *pt.get().add(slot) = fl.cidx[prev[x] as usize];
            }
        });
    }
    crate::cancel::check()?;
    let mut sizes = Vec::with_capacity(nf + nv);
    sizes.extend((0..nf).map(|f| fl.degree(f) as u32));
    sizes.extend((0..nv).map(|v| vl.valence(v)));
    Mesh::from_corner_twins(pos, &sizes, &cv, &tw)
}

/// One level with what `req` asks for (see the module docs); without
/// requests it is [`simplest`]. Open meshes keep their boundary polyline
/// (module docs).
/// This scheme has no sharpness rules: `req.creases` is ignored and
/// `Level.creases` is `None` (creases are dropped).
pub fn simplest_level(m: &Mesh, req: &Request) -> Result<Level> {
    with_point_spheres_level(m, req, |m, req| {
        if m.n_holes() > 0 {
            return open_level(m, req);
        }
        let mesh = step(m)?;
        let (nv, ne, nf) = (m.n_vertices(), m.n_edges(), m.n_faces());
        let (_, vert, face) = m.halfedge_columns();
        let stencils = if req.stencils {
            Some(Stencils::build(ne, nv, |e, row| {
                row.add(vert[2 * e], 0.5);
                row.add(vert[2 * e + 1], 0.5);
            })?)
        } else {
            None
        };
        let origins = if req.origins {
            let fl = FaceLayout::new(m)?;
            let vl = VertexLayout::new(m)?;
            let mut o = Origins::with_capacity(ne, mesh.n_edges(), nf + nv);
            o.vertex_kind = vec![EDGE; ne];
            o.vertex.extend(0..ne as u32);
            o.face_kind.extend(std::iter::repeat(FACE).take(nf).chain(std::iter::repeat(VERTEX).take(nv)));
            o.face.extend((0..nf as u32).chain(0..nv as u32));
            // F-face corner c is half-edge fh[c]; V-face slot s is the outgoing half-edge whose slot it is
            let nh = m.n_halfedges();
            let mut slot_he = vec![0u32; nh];
            for h in 0..nh {
                slot_he[vl.vidx[h] as usize] = h as u32;
            }
            edge_origins_by_corner(&mesh, &mut o, |c| {
                let f = if c < nh { face[fl.fh[c] as usize] } else { face[slot_he[c - nh] as usize] };
                (FACE, f)
            })?;
            Some(o)
        } else {
            None
        };
        Ok(Level { mesh, stencils, origins, creases: None })
    })
}

/// One level on a mesh with hole faces (no point-spheres): boundary
/// vertices kept, boundary edges split (module docs). Faces are
/// `[F-faces of real faces | V-faces | holes]`.
fn open_level(m: &Mesh, req: &Request) -> Result<Level> {
    use crate::mesh::NONE;
    let (nv, ne, nf, nh) = (m.n_vertices(), m.n_edges(), m.n_faces(), m.n_halfedges());
    check_output_size("simplest", 2 * nh + nh, ne + nv)?;
    let (next, vert, face) = m.halfedge_columns();
    let prev = &m.he_prev;
    let hole = |h: u32| m.f_hole[face[h as usize] as usize];
    // boundary vertices, in vertex order, after the edge midpoints
    let mut bidx = vec![NONE; nv];
    let mut bverts = Vec::new();
    for h in 0..nh as u32 {
        let v = vert[h as usize] as usize;
        if hole(h) && bidx[v] == NONE {
            bidx[v] = bverts.len() as u32;
            bverts.push(v as u32);
        }
    }
    // corner numbering
    let (mut fc, mut vc, mut vx, mut ca) = (vec![NONE; nh], vec![NONE; nh], vec![NONE; nh], vec![NONE; nh]);
    let mut sizes = Vec::with_capacity(nf + nv);
    let mut holes = Vec::with_capacity(nf + nv);
    let mut c = 0u32;
    let cycle = |f: usize| {
        let s = m.f_start[f];
        let mut h = s;
        let mut out = Vec::new();
        loop {
            out.push(h);
            h = next[h as usize];
            if h == s {
                break out;
            }
        }
    };
    for f in 0..nf {
        crate::cancel::poll(f)?;
        if !m.f_hole[f] {
            let hs = cycle(f);
            for &h in &hs {
                fc[h as usize] = c;
                c += 1;
            }
            sizes.push(hs.len() as u32);
            holes.push(false);
        }
    }
    for v in 0..nv {
        crate::cancel::poll(v)?;
        let start = c;
        for x in super::creases::ring(m, m.v_out[v]) {
            vc[x as usize] = c;
            c += 1;
            if hole(x) {
                vx[x as usize] = c; // the kept boundary vertex, after m(x)
                c += 1;
            }
        }
        sizes.push(c - start);
        holes.push(false);
    }
    let mut hole_faces = Vec::new();
    for f in 0..nf {
        if m.f_hole[f] {
            let hs = cycle(f);
            for &k in &hs {
                ca[k as usize] = c; // [w, m(k)]: the two halves of side k
                c += 2;
            }
            sizes.push(2 * hs.len() as u32);
            holes.push(true);
            hole_faces.push(f as u32);
        }
    }
    let n = c as usize;
    let (mut cv, mut tw) = (vec![0u32; n], vec![0u32; n]);
    let mut co = vec![(0u8, 0u32); if req.origins { n } else { 0 }];
    let bv = |w: u32| (ne as u32) + bidx[w as usize];
    for h in 0..nh {
        crate::cancel::poll(h)?;
        let hu = h as u32;
        let mid = hu >> 1;
        if !hole(hu) {
            // F-face side m(h) → m(next h), cutting the corner at vert[next h]
            let i = fc[h] as usize;
            cv[i] = mid;
            tw[i] = vc[next[h] as usize];
            // V-face side m(h) → m(prev h) inside face[h]
            let j = vc[h] as usize;
            cv[j] = mid;
            tw[j] = fc[prev[h] as usize];
            if req.origins {
                co[i] = (FACE, face[h]);
                co[j] = (FACE, face[h]);
            }
        } else {
            // V-face of w = vert[h]: m(h) → w → m(prev h) along the boundary
            let (j, x) = (vc[h] as usize, vx[h] as usize);
            cv[j] = mid;
            tw[j] = ca[h];
            cv[x] = bv(vert[h]);
            tw[x] = ca[prev[h] as usize] + 1;
            // the hole: w → m(h) → (next corner)
            let a = ca[h] as usize;
            cv[a] = bv(vert[h]);
            tw[a] = vc[h];
            cv[a + 1] = mid;
            tw[a + 1] = vx[next[h] as usize];
            if req.origins {
                co[j] = (EDGE, mid);
                co[x] = (EDGE, prev[h] >> 1);
                co[a] = (EDGE, mid);
                co[a + 1] = (EDGE, mid);
            }
        }
    }
    let st = Stencils::build(ne + bverts.len(), nv, |i, row| {
        if i < ne {
            row.add(vert[2 * i], 0.5);
            row.add(vert[2 * i + 1], 0.5);
        } else {
            row.add(bverts[i - ne], 1.0);
        }
    })?;
    let pos = st.apply_points(&m.pos)?;
    let mesh = Mesh::from_corner_twins_with_holes(pos, &sizes, &cv, &tw, holes)?;
    let origins = if req.origins {
        let mut o = Origins::with_capacity(mesh.n_vertices(), mesh.n_edges(), mesh.n_faces());
        o.vertex_kind = std::iter::repeat(EDGE).take(ne).chain(std::iter::repeat(VERTEX).take(bverts.len())).collect();
        o.vertex = (0..ne as u32).chain(bverts.iter().copied()).collect();
        let real: Vec<u32> = (0..nf as u32).filter(|&f| !m.f_hole[f as usize]).collect();
        o.face_kind = std::iter::repeat(FACE).take(real.len()).chain(std::iter::repeat(VERTEX).take(nv)).chain(std::iter::repeat(FACE).take(hole_faces.len())).collect();
        o.face = real.iter().copied().chain(0..nv as u32).chain(hole_faces.iter().copied()).collect();
        edge_origins_by_corner(&mesh, &mut o, |c| co[c])?;
        Some(o)
    } else {
        None
    };
    Ok(Level { mesh, stencils: req.stencils.then_some(st), origins, creases: None })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schemes::hosts::test_meshes::*;

    #[test]
    fn counts_and_validity_on_corpus() {
        check_on_corpus(simplest, |_, (v, e, f)| (e, 2 * e, f + v), |name, _, r| {
            assert!(r.vertices().filter(|&x| r.point_sphere_face(x).is_none()).all(|x| r.valence(x) == 4), "{name} 4-valent");
        });
    }

    #[test]
    fn level_equals_plain_on_corpus() {
        level_matches_plain_on_corpus(simplest, simplest_level, |name, m, lv| {
            let o = lv.origins.as_ref().unwrap();
            let fl = FaceLayout::new(m).unwrap();
            assert!(origin_counts(&o.vertex_kind, &o.vertex, EDGE, m.n_edges()).iter().all(|&c| c == 1), "{name}");
            assert!(origin_counts(&o.face_kind, &o.face, VERTEX, m.n_vertices()).iter().enumerate().all(|(v, &c)| c == usize::from(m.v_out[v] & crate::mesh::POINT == 0)), "{name}");
            assert!(origin_counts(&o.face_kind, &o.face, FACE, m.n_faces()).iter().all(|&c| c == 1), "{name}");
            // each face is the origin of its n corner-cutting edges
            let fe = origin_counts(&o.edge_kind, &o.edge, FACE, m.n_faces());
            for f in 0..m.n_faces() {
                assert_eq!(fe[f], fl.degree(f), "{name} face {f}");
            }
        });
    }

    #[test]
    fn open_meshes_keep_their_boundary_polyline() {
        for (name, m) in open_meshes() {
            let (v, e, f) = counts(&m);
            let nb = (0..m.n_halfedges()).filter(|&h| m.f_hole[m.he_face[h] as usize]).count();
            let vb = (0..v).filter(|&x| crate::schemes::creases::ring(&m, m.v_out[x]).any(|h| m.f_hole[m.he_face[h as usize] as usize])).count();
            let lv = simplest_level(&m, &full_request()).unwrap();
            check_level(name, &m, &lv);
            let r = &lv.mesh;
            assert_eq!(counts(r), (e + vb, 2 * e + nb, f + v), "{name}");
            assert_eq!((open_euler(r), r.n_holes()), (open_euler(&m), m.n_holes()), "{name}");
            let rb = (0..r.n_halfedges()).filter(|&h| r.f_hole[r.he_face[h] as usize]).count();
            assert_eq!(rb, 2 * nb, "{name}: boundary edges split");
            // every boundary point of the output lies on the input's boundary polyline
            for h in 0..r.n_halfedges() {
                if r.f_hole[r.he_face[h] as usize] {
                    let p = r.pos[r.he_vert[h] as usize];
                    let on = (0..m.n_halfedges()).filter(|&k| m.f_hole[m.he_face[k] as usize]).any(|k| {
                        let (a, b) = (m.pos[m.he_vert[k] as usize], m.pos[m.he_vert[k ^ 1] as usize]);
                        (p - a).length() < 1e-12 || (p - b).length() < 1e-12 || (p - (a + b) * 0.5).length() < 1e-12
                    });
                    assert!(on, "{name}: boundary point {p} off the input boundary");
                }
            }
            // a second level works on the output (open input again)
            let two = simplest_level(r, &full_request()).unwrap();
            check_level(name, r, &two);
        }
    }

    #[test]
    fn direct_columns_equal_the_twin_builder() {
        for (name, m) in corpus() {
            let (mut a, mut b) = (m.clone(), m.clone());
            for level in 1..=2 {
                let (na, nb) = (with_point_spheres("simplest", &a, step).unwrap(), with_point_spheres("simplest", &b, step_via_twins).unwrap());
                assert_eq!(na, nb, "{name} level {level}");
                (a, b) = (na, nb);
            }
        }
    }

    #[test]
    fn cube_gives_cuboctahedron() {
        let r = simplest(&crate::primitives::cube()).unwrap();
        assert_eq!(r.face_size_histogram().get(&3), Some(&8));
        assert_eq!(r.face_size_histogram().get(&4), Some(&6));
    }
}

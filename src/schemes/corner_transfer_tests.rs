//! Tests of the corner transfer, with the first (matrix-building)
//! implementation kept as the reference the fast [`transfer`] must equal
//! bit for bit.

use super::*;
use crate::schemes::hosts::FaceLayout;

/// The corner transfer of one level (see the module docs): `input` and
/// `out` the level's meshes, `s` its stencils (rows: `out`'s vertices) and
/// `o` its origins (internal ids).
pub(super) fn reference(input: &Mesh, out: &Mesh, s: &Stencils, o: &Origins) -> Result<Stencils> {
    let ifl = FaceLayout::new(input)?;
    let ofl = FaceLayout::new(out)?;
    // exported corner index of every input half-edge of a real face
    let mut ec = vec![NONE; input.n_halfedges()];
    // per input face: its corners as (vertex, exported corner), sorted by vertex
    let mut by_vertex: Vec<(u32, u32)> = Vec::with_capacity(input.n_halfedges());
    let mut k = 0u32;
    for f in 0..input.n_faces() {
        crate::cancel::poll(f)?;
        let cs = ifl.corners(f);
        let start = by_vertex.len();
        for &h in cs {
            if !input.f_hole[f] {
                ec[h as usize] = k;
                by_vertex.push((input.he_vert[h as usize], k));
                k += 1;
            }
        }
        by_vertex[start..].sort_unstable();
    }
    // by_vertex[ifl.off[f]..ifl.off[f + 1]] when f is real (holes hold none)
    let mut voff = Vec::with_capacity(input.n_faces() + 1);
    voff.push(0usize);
    for f in 0..input.n_faces() {
        let d = if input.f_hole[f] { 0 } else { ifl.degree(f) };
        voff.push(voff[f] + d);
    }
    let real = |f: u32| f != NONE && (f as usize) < input.n_faces() && !input.f_hole[f as usize];
    let at = |f: u32, u: u32| -> &[(u32, u32)] {
        let sl = &by_vertex[voff[f as usize]..voff[f as usize + 1]];
        let a = sl.partition_point(|&(w, _)| w < u);
        let b = sl.partition_point(|&(w, _)| w <= u);
        &sl[a..b]
    };
    let holds = |f: u32, p: usize| -> bool {
        let (c, _) = s.row(p);
        c.iter().all(|&u| !at(f, u).is_empty())
    };
    // output corners in export order
    let ocorners: Vec<u32> = (0..out.n_faces()).filter(|&g| !out.f_hole[g]).flat_map(|g| ofl.corners(g).iter().copied()).collect();
    let face_of = |kind: u8, i: u32| -> u32 {
        if kind == FACE && real(i) {
            i
        } else {
            NONE
        }
    };
    // rules 1–3
    let direct = |hc: u32| -> u32 {
        let p = out.he_vert[hc as usize] as usize;
        let g = out.he_face[hc as usize] as usize;
        let e_out = (hc >> 1) as usize;
        let e_in = (out.he_prev[hc as usize] >> 1) as usize;
        [
            face_of(o.vertex_kind[p], o.vertex[p]),
            face_of(o.face_kind[g], o.face[g]),
            face_of(o.edge_kind[e_out], o.edge[e_out]),
            face_of(o.edge_kind[e_in], o.edge[e_in]),
        ]
        .into_iter()
        .find(|&f| f != NONE)
        .unwrap_or(NONE)
    };
    let around = |kind: u8, i: u32, push: &mut dyn FnMut(u32)| match kind {
        EDGE => {
            for h in [2 * i, 2 * i + 1] {
                push(input.he_face[h as usize]);
            }
        }
        VERTEX => {
            let vo = input.v_out[i as usize];
            if vo & POINT == 0 {
                for h in crate::schemes::creases::ring(input, vo) {
                    push(input.he_face[h as usize]);
                }
            }
        }
        _ => push(i),
    };
    let n_out = ocorners.len();
    Stencils::build(n_out, k as usize, |c, row| {
        let hc = ocorners[c];
        let p = out.he_vert[hc as usize] as usize;
        let g = out.he_face[hc as usize] as usize;
        let first = direct(hc);
        let mut home = NONE;
        if first != NONE && holds(first, p) {
            home = first;
        } else {
            let mut cands: Vec<u32> = Vec::new();
            let mut push = |f: u32| {
                if real(f) && !cands.contains(&f) {
                    cands.push(f);
                }
            };
            push(first);
            push(direct(out.he_prev[hc as usize]));
            push(direct(out.he_next[hc as usize]));
            around(o.vertex_kind[p], o.vertex[p], &mut push);
            around(o.face_kind[g], o.face[g], &mut push);
            if let Some(&f) = cands.iter().find(|&&f| holds(f, p)) {
                home = f;
            } else if let Some(&f) = cands.first() {
                // read linearly in the first candidate (see the module docs)
                let mut lin: Vec<u32> = Vec::new();
                match o.vertex_kind[p] {
                    VERTEX => lin.push(o.vertex[p]),
                    EDGE => {
                        let e = o.vertex[p] as usize;
                        lin.extend([input.he_vert[2 * e], input.he_vert[2 * e + 1]]);
                    }
                    _ => {}
                }
                let lin: Vec<u32> = lin.into_iter().filter(|&u| !at(f, u).is_empty()).collect();
                if lin.is_empty() {
                    // a face point: its face's mean
                    let sl = &by_vertex[voff[f as usize]..voff[f as usize + 1]];
                    for &(_, ci) in sl {
                        row.add(ci, 1.0 / sl.len() as f64);
                    }
                } else {
                    for &u in &lin {
                        let cs = at(f, u);
                        for &(_, ci) in cs {
                            row.add(ci, 1.0 / (lin.len() * cs.len()) as f64);
                        }
                    }
                }
                return;
            }
        }
        if home == NONE {
            // no real input face anywhere near: cannot happen for a level's
            // real face; leave the row empty (value 0) rather than panic
            return;
        }
        let (cols, ws) = s.row(p);
        for (&u, &w) in cols.iter().zip(ws) {
            let cs = at(home, u);
            for &(_, ci) in cs {
                row.add(ci, w / cs.len() as f64);
            }
        }
    })
    .and_then(|t| {
        if t.off.windows(2).any(|w| w[0] == w[1]) {
            return Err(MeshError::Precondition("corner attributes: an output corner has no input face to take its value from".into()));
        }
        Ok(t)
    })
}

use crate::schemes::level::Request;

fn req() -> Request<'static> {
    Request { stencils: true, origins: true, ..Request::default() }
}

/// Corner values of the cube: every corner its own value (every edge a
/// seam), as (value per corner) = f(face, vertex).
fn seams(m: &Mesh) -> Vec<f64> {
    let p = m.to_polygons();
    let mut out = Vec::new();
    let mut k = 0;
    for (f, &n) in p.sizes.iter().enumerate() {
        for j in 0..n as usize {
            let v = p.indices[k + j] as f64;
            out.push(100.0 * f as f64 + v);
        }
        k += n as usize;
    }
    out
}

fn honeycomb(m: &Mesh, r: &Request) -> Result<super::super::level::Level> {
    super::super::honeycomb::honeycomb_level(m, 0.5, None, r)
}
fn truncation(m: &Mesh, r: &Request) -> Result<super::super::level::Level> {
    super::super::vertex_truncation::vertex_truncation_level(m, super::super::vertex_truncation::Truncation::Polyhedral { ratio: 0.5 }, r)
}
fn menger(m: &Mesh, r: &Request) -> Result<super::super::level::Level> {
    super::super::menger_level::menger_level(m, &Default::default(), r).map(|(l, _)| l)
}

fn schemes() -> Vec<(&'static str, fn(&Mesh, &Request) -> Result<super::super::level::Level>)> {
    vec![
        ("honeycomb", honeycomb),
        ("vertex_truncation", truncation),
        ("menger", menger),
        ("doo_sabin", super::super::doo_sabin::doo_sabin_level),
        ("midpoint", super::super::midpoint::midpoint_level),
        ("dual", super::super::dual::dual_level),
        ("simplest", super::super::simplest::simplest_level),
        ("sqrt3", super::super::sqrt3::sqrt3_level),
        ("sierpinski", super::super::sierpinski::sierpinski_level),
    ]
}

#[test]
fn seamless_data_is_s_at_a_and_seams_do_not_mix() {
    let m = crate::primitives::cube();
    let p = m.to_polygons();
    let a: Vec<f64> = (0..8).map(|v| (v * v) as f64).collect();
    let per_corner: Vec<f64> = p.indices.iter().map(|&v| a[v as usize]).collect();
    let sv = seams(&m);
    for (name, lv) in schemes() {
        let l = lv(&m, &req()).unwrap();
        let (s, o) = (l.stencils.as_ref().unwrap(), l.origins.as_ref().unwrap());
        let t = corner_stencils(&m, &l.mesh, s, o).unwrap();
        assert_eq!(t.n_rows(), l.mesh.n_halfedges(), "{name}: one row per output corner (closed output)");
        let got = t.apply(&per_corner, 1).unwrap();
        let sa = s.apply(&a, 1).unwrap();
        let op = l.mesh.to_polygons();
        for (c, &v) in op.indices.iter().enumerate() {
            if name == "sqrt3" && o.vertex_kind[v as usize] == VERTEX {
                continue; // smoothed over the one-ring: read linearly
            }
            assert!((got[c] - sa[v as usize]).abs() < 1e-12, "{name} corner {c}: {} vs {}", got[c], sa[v as usize]);
        }
        // every row mixes the corners of one input face only
        let mut face_of_corner = Vec::new();
        for (f, &n) in p.sizes.iter().enumerate() {
            face_of_corner.extend(std::iter::repeat(f).take(n as usize));
        }
        for r in 0..t.n_rows() {
            let (cols, w) = t.row(r);
            assert!(!cols.is_empty());
            assert!(cols.iter().all(|&c| face_of_corner[c as usize] == face_of_corner[cols[0] as usize]), "{name} row {r}");
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        }
        let _ = t.apply(&sv, 1).unwrap();
    }
}

/// The fast transfer equals the first implementation's matrix applied to
/// the data, bit for bit, for every scheme on closed and open meshes (with
/// a big face, a self-loop and a two-gon among them), two levels deep, with
/// seams everywhere and several arrays at once.
#[test]
fn transfer_equals_the_reference_bit_for_bit() {
    use crate::schemes::hosts::test_meshes::*;
    let mut meshes = vec![
        ("cube", crate::primitives::cube()),
        ("dodecahedron", crate::primitives::dodecahedron()),
        ("torus", crate::primitives::torus(6, 4, 1.0, 0.4).unwrap()),
        ("self_loop", cube_with_self_loop()),
        ("two_gon", cube_with_two_gon()),
        ("prism", prism(&(0..12).map(|i| { let t = i as f64 * std::f64::consts::TAU / 12.0; [t.cos(), t.sin()] }).collect::<Vec<_>>(), 1.0)),
    ];
    meshes.extend(open_meshes());
    for (mname, m0) in meshes {
        for (name, lv) in schemes() {
            let mut m = m0.clone();
            let n_in = m.to_polygons().indices.len();
            // two arrays: seams everywhere (k = 2), and a scalar
            let a2: Vec<f64> = (0..2 * n_in).map(|i| ((i * 7919) % 1009) as f64 * 0.37 - 3.0).collect();
            let a1: Vec<f64> = (0..n_in).map(|i| (i as f64).sqrt()).collect();
            let mut arrays = vec![(a2, 2), (a1, 1)];
            for level in 0..2 {
                let r = Request { level, ..req() };
                let Ok(l) = lv(&m, &r) else { break }; // refusals (open Sierpinski/Menger) are tested elsewhere
                let (s, o) = (l.stencils.as_ref().unwrap(), l.origins.as_ref().unwrap());
                let want = reference(&m, &l.mesh, s, o);
                let t = corner_stencils(&m, &l.mesh, s, o);
                assert_eq!(want.is_ok(), t.is_ok(), "{mname} {name} level {level}");
                let mut got = arrays.clone();
                let res = transfer(&m, &l.mesh, s, o, &mut got);
                let Ok(want) = want else {
                    assert!(res.is_err());
                    break;
                };
                assert_eq!(t.unwrap(), want, "{mname} {name} level {level}: the matrix");
                res.unwrap();
                for ((a, k), (g, gk)) in arrays.iter().zip(&got) {
                    assert_eq!(k, gk);
                    let w = want.apply(a, *k).unwrap();
                    assert_eq!(w.len(), g.len());
                    assert!(w.iter().zip(g).all(|(x, y)| x.to_bits() == y.to_bits()), "{mname} {name} level {level}: values");
                }
                arrays = got;
                m = l.mesh;
            }
        }
    }
}

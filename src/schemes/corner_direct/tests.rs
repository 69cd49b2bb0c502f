//! The direct paths against the generic transfer they replace.

use super::*;
use crate::schemes::corner_transfer::transfer;
use crate::schemes::hosts::test_meshes as tm;
use crate::schemes::level::{Level, Request};
use crate::schemes::vertex_truncation::Truncation;

type LevelFn = Box<dyn Fn(&Mesh, &Request) -> Result<Level>>;
type DirectFn = Box<dyn Fn(&Mesh, &Mesh, &[f64], usize) -> Result<Option<Vec<f64>>>>;

fn schemes() -> Vec<(String, LevelFn, DirectFn)> {
    use crate::schemes::*;
    let mut v: Vec<(String, LevelFn, DirectFn)> = vec![
        ("doo_sabin".into(), Box::new(doo_sabin::doo_sabin_level), Box::new(super::doo_sabin)),
        ("dual".into(), Box::new(dual::dual_level), Box::new(super::dual)),
        ("simplest".into(), Box::new(simplest::simplest_level), Box::new(super::simplest)),
        ("sqrt3".into(), Box::new(sqrt3::sqrt3_level), Box::new(super::sqrt3)),
        ("sierpinski".into(), Box::new(sierpinski::sierpinski_level), Box::new(super::sierpinski)),
    ];
    for (t, a) in [(0.5, None), (0.3, Some(0.7)), (0.8, Some(0.0))] {
        v.push((
            format!("honeycomb t={t} a={a:?}"),
            Box::new(move |m, r| honeycomb::honeycomb_level(m, t, a, r)),
            Box::new(move |i, o, rows, k| super::honeycomb(i, o, t, a, rows, k)),
        ));
    }
    for r in [0.25, 1.0 / 3.0, 0.5] {
        v.push((
            format!("truncation r={r}"),
            Box::new(move |m, q| vertex_truncation::vertex_truncation_level(m, Truncation::Polyhedral { ratio: r }, q)),
            Box::new(move |i, o, rows, k| super::truncation(i, o, r, rows, k)),
        ));
    }
    v
}

/// `k` columns per exported corner, a function of (face, vertex, column):
/// every edge a seam, and a face passing a vertex twice gives it one value.
fn per_face_vertex(m: &Mesh, k: usize) -> Vec<f64> {
    let p = m.to_polygons();
    let mut out = Vec::new();
    let mut at = 0;
    for (f, &n) in p.sizes.iter().enumerate() {
        for &v in &p.indices[at..at + n as usize] {
            out.extend((0..k).map(|j| ((f * 7919 + v as usize * 104729 + j * 31) % 1009) as f64 * 0.013 - 3.0));
        }
        at += n as usize;
    }
    out
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + x.abs().max(y.abs())))
}

/// Two levels on every closed corpus mesh without point-spheres: the direct
/// path applies (Sierpinski: not on self-loops) and equals the transfer.
#[test]
fn equals_the_generic_transfer() {
    let k = 2;
    for (name, level, direct) in schemes() {
        for (mname, m0) in tm::corpus() {
            let mut m = m0;
            for depth in 0..2 {
                let lv = level(&m, &tm::full_request()).unwrap();
                let rows = per_face_vertex(&m, k);
                let mut want = vec![(rows.clone(), k)];
                let mut s = lv.stencils.clone().unwrap();
                if name == "sqrt3" {
                    // its documented corner rule reads an old vertex linearly (its home
                    // face's value there); the transfer does so only where no face
                    // holds the vertex's one-ring row, so give it that row
                    let nv = m.n_vertices();
                    s = crate::schemes::stencil::Stencils::build(s.n_rows(), s.n_cols, |i, r| {
                        if i < nv {
                            r.add(i as u32, 1.0);
                        } else {
                            let (c, w) = s.row(i);
                            c.iter().zip(w).for_each(|(&c, &w)| r.add(c, w));
                        }
                    })
                    .unwrap();
                }
                transfer(&m, &lv.mesh, &s, lv.origins.as_ref().unwrap(), &mut want).unwrap();
                let got = direct(&m, &lv.mesh, &rows, k).unwrap();
                let loops = (0..m.n_edges()).any(|e| m.he_vert[2 * e] == m.he_vert[2 * e + 1]);
                if !applies(&m) || (name == "sierpinski" && loops) {
                    assert!(got.is_none(), "{name} on {mname} level {depth}: no direct path");
                } else {
                    let got = got.unwrap_or_else(|| panic!("{name} on {mname} level {depth}: the direct path applies"));
                    assert!(close(&got, &want[0].0), "{name} on {mname} level {depth}");
                }
                m = lv.mesh;
            }
        }
    }
}

/// One-hot face indicators (column f is 1 at face f's corners): every output
/// corner reads exactly one input face, even on faces that pass a vertex
/// twice (Sierpinski's pyramids, a self-loop's face).
#[test]
fn every_corner_reads_one_face() {
    for (name, level, direct) in schemes() {
        for (mname, m) in tm::corpus() {
            if !applies(&m) {
                continue;
            }
            let p = m.to_polygons();
            let nf = p.sizes.len();
            let mut rows = Vec::new();
            for (f, &n) in p.sizes.iter().enumerate() {
                for _ in 0..n {
                    rows.extend((0..nf).map(|j| (j == f) as u8 as f64));
                }
            }
            let lv = level(&m, &Request::default()).unwrap();
            let Some(got) = direct(&m, &lv.mesh, &rows, nf).unwrap() else { continue };
            assert_eq!(got.len(), lv.mesh.to_polygons().indices.len() * nf, "{name} on {mname}");
            for (c, r) in got.chunks_exact(nf).enumerate() {
                let nonzero = r.iter().filter(|x| x.abs() > 1e-14).count();
                assert_eq!(nonzero, 1, "{name} on {mname}: corner {c} reads {nonzero} faces");
                assert!((r.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{name} on {mname}: corner {c}");
            }
        }
    }
}

/// Not the layout a kernel reads (another scheme's output, an open input,
/// rows of the wrong length): `None`, so the caller takes the transfer.
#[test]
fn other_layouts_are_refused() {
    let m = crate::primitives::cube();
    let rows = per_face_vertex(&m, 1);
    let ds = crate::schemes::doo_sabin::doo_sabin(&m).unwrap();
    let sq = crate::schemes::sqrt3::sqrt3(&m).unwrap();
    assert!(simplest(&m, &ds, &rows, 1).unwrap().is_none());
    assert!(truncation(&m, &ds, 0.25, &rows, 1).unwrap().is_none());
    assert!(sqrt3(&m, &ds, &rows, 1).unwrap().is_none());
    assert!(sierpinski(&m, &sq, &rows, 1).unwrap().is_none());
    assert!(doo_sabin(&m, &ds, &rows[1..], 1).unwrap().is_none());
    let open = tm::cube_with_hole();
    let lv = crate::schemes::doo_sabin::doo_sabin_level(&open, &Request::default()).unwrap();
    assert!(doo_sabin(&open, &lv.mesh, &per_face_vertex(&open, 1), 1).unwrap().is_none());
}

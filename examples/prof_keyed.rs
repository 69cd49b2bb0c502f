//! Time of the keyed-builder operators (Conway, TopMod) on a 100k-quad
//! torus, best of N, plus an FNV hash of every output (positions, faces,
//! corner twins) to compare builds before and after a builder change:
//! `RAYON_NUM_THREADS=1 cargo run --release --example prof_keyed [N]`.
mod common;

use common::hash;
use std::time::Instant;
use topomesh::schemes::{conway, topmod};
use topomesh::{primitives, Mesh, Result};

fn main() {
    let reps: usize = std::env::args().nth(1).map_or(5, |s| s.parse().unwrap());
    let t = primitives::torus(400, 250, 3.0, 1.0).unwrap();
    type Op = Box<dyn Fn(&Mesh) -> Result<Mesh>>;
    let mut ops: Vec<(String, Op)> = Vec::new();
    for l in ["d", "a", "t", "k", "j", "e", "o", "g", "s", "b", "m", "n", "z", "c", "u", "w", "v", "p", "q", "l", "r"] {
        ops.push((format!("conway {l}"), Box::new(move |m: &Mesh| conway::conway(l, Some(m)))));
    }
    ops.push(("stellate".into(), Box::new(|m: &Mesh| topmod::stellate::stellate(m, 0.0))));
    ops.push(("linear_vertex_insertion".into(), Box::new(topmod::linear::linear_vertex_insertion)));
    ops.push(("corner_cutting".into(), Box::new(|m: &Mesh| topmod::corner_cutting::corner_cutting(m, 0.5625))));
    ops.push(("loop_style".into(), Box::new(|m: &Mesh| topmod::loop_style::loop_style(m, 1.0))));
    ops.push(("root4".into(), Box::new(|m: &Mesh| topmod::loop_style::root4(m, 0.0, 0.0))));
    ops.push(("fractal".into(), Box::new(|m: &Mesh| topmod::loop_style::fractal(m, 1.0))));
    ops.push(("pentagonalize".into(), Box::new(|m: &Mesh| topmod::pentagonal::pentagonalize(m, 0.0))));
    ops.push(("pentagon_preserving".into(), Box::new(|m: &Mesh| topmod::pentagonal::pentagon_preserving(m, 0.75))));
    ops.push(("dual_12_6_4".into(), Box::new(|m: &Mesh| topmod::twelve_six_four::dual_12_6_4(m, 0.7))));
    ops.push(("checkerboard".into(), Box::new(|m: &Mesh| topmod::checkerboard::checkerboard(m, 0.33))));
    ops.push(("doo_sabin_bc_new".into(), Box::new(|m: &Mesh| topmod::doo_sabin_bc_new::doo_sabin_bc_new(m, 1.0, 1.0))));
    ops.push(("double_stellate_misc".into(), Box::new(|m: &Mesh| topmod::stellate::double_stellate_misc(m, 0.0, 0.0))));
    ops.push(("stellate_edge_removal".into(), Box::new(|m: &Mesh| topmod::stellate::stellate_edge_removal(m, 0.0))));
    // TopMod's compositions (dual + X + dual) and their parts
    ops.push(("dual".into(), Box::new(topomesh::schemes::dual::dual)));
    ops.push(("loop".into(), Box::new(topomesh::schemes::loop_subdivision::loop_subdivision)));
    ops.push(("root3".into(), Box::new(topmod::compose::root3)));
    ops.push(("dual_loop".into(), Box::new(topmod::compose::dual_loop)));
    ops.push(("cubic_pentagonalize".into(), Box::new(|m: &Mesh| topmod::compose::cubic_pentagonalize(m, 0.0))));
    ops.push(("dual_pentagonalize".into(), Box::new(|m: &Mesh| topmod::compose::dual_pentagonalize(m, 0.0))));
    ops.push(("dual_pentagonalize (composed)".into(), Box::new(|m: &Mesh| topomesh::schemes::dual::dual(&topmod::pentagonal::pentagonalize(&topomesh::schemes::dual::dual(m)?, 0.0)?))));
    ops.push(("dual_pentagon_preserving".into(), Box::new(|m: &Mesh| topmod::compose::dual_pentagon_preserving(m, 0.75))));
    ops.push(("remesh_12_6_4".into(), Box::new(|m: &Mesh| topmod::compose::remesh_12_6_4(m, 0.7))));
    ops.push(("dual_checkerboard".into(), Box::new(|m: &Mesh| topmod::compose::dual_checkerboard(m, 0.33))));
    ops.push(("dual_hexagon_preserving".into(), Box::new(|m: &Mesh| topmod::compose::dual_hexagon_preserving(m, 0.0, 0.0))));
    let filter: Option<String> = std::env::args().nth(2);
    for (name, op) in &ops {
        if filter.as_ref().is_some_and(|f| !name.contains(f.as_str())) {
            continue;
        }
        let mut best = f64::INFINITY;
        let mut out = op(&t).unwrap();
        for _ in 0..reps {
            let t0 = Instant::now();
            out = op(&t).unwrap();
            best = best.min(t0.elapsed().as_secs_f64());
        }
        let nf = out.n_faces();
        println!("{name:26} {:8.2} ms {nf:>9} faces {:6.2} M/s  hash {:016x}", best * 1e3, nf as f64 / best / 1e6, hash(&out));
    }
}

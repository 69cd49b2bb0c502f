//! Stage times of TopMod's "dual + X + dual" compositions on a 100k-quad
//! torus (best of N each): the first dual, X, and the last dual, to see
//! what a composition spends in its duals:
//! `RAYON_NUM_THREADS=1 cargo run --release --example prof_compose [N]`.
use std::time::Instant;
use topomesh::schemes::{dual::dual, loop_subdivision::loop_subdivision, topmod as tm};
use topomesh::{primitives, Mesh, Result};

fn best<T>(reps: usize, f: impl Fn() -> T) -> (f64, T) {
    let mut out = f();
    let mut b = f64::INFINITY;
    for _ in 0..reps {
        let t = Instant::now();
        out = f();
        b = b.min(t.elapsed().as_secs_f64());
    }
    (b * 1e3, out)
}

fn main() {
    let reps: usize = std::env::args().nth(1).map_or(5, |s| s.parse().unwrap());
    let t = primitives::torus(400, 250, 3.0, 1.0).unwrap();
    type Op = Box<dyn Fn(&Mesh) -> Result<Mesh>>;
    let ops: Vec<(&str, bool, Op)> = vec![
        ("root3 (honeycomb)", true, Box::new(|m: &Mesh| topomesh::schemes::honeycomb::honeycomb(m, 0.5, None))),
        ("dual_loop (loop)", true, Box::new(loop_subdivision)),
        ("cubic_pentagonalize", false, Box::new(|m: &Mesh| tm::pentagonal::pentagonalize(m, 0.0))),
        ("dual_pentagon_preserving", true, Box::new(|m: &Mesh| tm::pentagonal::pentagon_preserving(m, 0.75))),
        ("remesh_12_6_4", true, Box::new(|m: &Mesh| tm::twelve_six_four::dual_12_6_4(m, 0.7))),
        ("dual_checkerboard", true, Box::new(|m: &Mesh| tm::checkerboard::checkerboard(m, 0.33))),
        ("dual_hexagon_preserving", true, Box::new(|m: &Mesh| tm::loop_style::root4(m, 0.0, 0.0))),
    ];
    for (name, dual_first, op) in &ops {
        let (t0, d) = if *dual_first { best(reps, || dual(&t).unwrap()) } else { (0.0, t.clone()) };
        let (t1, x) = best(reps, || op(&d).unwrap());
        // cubic pentagonalization: X, dual, dual
        let (t2, y) = best(reps, || dual(&x).unwrap());
        let t3 = if *dual_first { 0.0 } else { best(reps, || dual(&y).unwrap()).0 };
        println!("{name:26} dual {t0:6.2}  X {t1:7.2}  dual {t2:7.2} {t3:7.2} ms  ({} -> {} faces)", x.n_faces(), y.n_vertices());
    }
}

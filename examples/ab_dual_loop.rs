//! Dual Loop on the 100k-quad torus, the composition (dual, Loop, dual)
//! against the one-pass build, alternating in one process (issue 16):
//! `RAYON_NUM_THREADS=1 cargo run --release --example ab_dual_loop [N]`
//! prints the best and median of N calls each (ms, M output faces/s).
use std::time::Instant;
use topomesh::schemes::{dual::dual, loop_subdivision::loop_subdivision, topmod::compose};
use topomesh::{primitives, Mesh, Result};

fn main() {
    let reps: usize = std::env::args().nth(1).map_or(7, |s| s.parse().unwrap());
    let t = primitives::torus(400, 250, 3.0, 1.0).unwrap();
    type Op = fn(&Mesh) -> Result<Mesh>;
    let ops: [(&str, Op); 2] = [("composition", |m| dual(&loop_subdivision(&dual(m)?)?)), ("one pass", compose::dual_loop)];
    let (a, b) = (ops[0].1(&t).unwrap(), ops[1].1(&t).unwrap());
    assert!(a == b, "the builds differ");
    let faces = a.n_faces() as f64;
    drop((a, b));
    let mut times = vec![Vec::new(); ops.len()];
    for _ in 0..reps {
        for (i, (_, op)) in ops.iter().enumerate() {
            let s = Instant::now();
            let r = op(&t).unwrap();
            times[i].push(s.elapsed().as_secs_f64() * 1e3);
            drop(r);
        }
    }
    for ((name, _), ts) in ops.iter().zip(&mut times) {
        ts.sort_by(f64::total_cmp);
        let (best, med) = (ts[0], ts[ts.len() / 2]);
        println!("{name:12} best {best:7.2} ms  median {med:7.2} ms  ({:.2} / {:.2} M faces/s, {faces} faces)", faces / best / 1e3, faces / med / 1e3);
    }
}

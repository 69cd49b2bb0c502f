//! Ctrl-C latency inside one long level: each scheme runs once to time it,
//! then 12 times with cancellation requested at 1/13 … 12/13 of that time;
//! prints the worst time from the request to the call's return.
//! `cargo run --release --example cancel_latency [scheme ...]`
use topomesh::{primitives as pr, schemes::*, cancel};
fn main() {
    let which: Vec<String> = std::env::args().skip(1).collect();
    let tor = |a, b| pr::torus(a, b, 2.0, 0.5).unwrap();
    let mut ico = pr::icosahedron();
    for _ in 0..8 { ico = loop_subdivision::loop_subdivision(&ico).unwrap(); }
    let run = |name: &str, f: &dyn Fn() -> topomesh::Result<topomesh::Mesh>| {
        if !which.is_empty() && !which.iter().any(|w| w == name) { return; }
        let t = std::time::Instant::now();
        let r = f().unwrap();
        let total = t.elapsed().as_secs_f64();
        let nf = r.n_faces();
        drop(r);
        let mut worst = (0.0f64, 0.0f64);
        for k in 1..=12 {
            let at = total * k as f64 / 13.0;
            let t = std::time::Instant::now();
            let h = std::thread::spawn(move || { std::thread::sleep(std::time::Duration::from_secs_f64(at)); cancel::request(); });
            let r = f();
            let el = t.elapsed().as_secs_f64();
            h.join().unwrap();
            // SAFETY: the cancelled call has returned and no other runs
            unsafe { cancel::reset() };
            let lat = el - at; let _ = r.is_err();
            if !(lat <= worst.0) { worst = (lat, at); }
        }
        eprintln!("{name:18} {:7.0} ms, F {nf:9}: worst latency {:6.1} ms (request at {:.0} ms)", total * 1e3, worst.0 * 1e3, worst.1 * 1e3);
    };
    let t2 = tor(1000, 1000); let t14 = tor(700, 700);
    run("catmull_clark", &|| catmull_clark::catmull_clark(&t2));
    run("doo_sabin", &|| doo_sabin::doo_sabin(&t14));
    run("loop", &|| loop_subdivision::loop_subdivision(&ico));
    run("sqrt3", &|| sqrt3::sqrt3(&ico));
    run("simplest", &|| simplest::simplest(&t14));
    run("midpoint", &|| midpoint::midpoint(&ico));
    run("dual", &|| dual::dual(&t2));
    run("honeycomb", &|| honeycomb::honeycomb(&t14, 0.5, None));
    run("vertex_truncation", &|| vertex_truncation::vertex_truncation(&t14, vertex_truncation::Truncation::Chaikin));
    run("sierpinski", &|| sierpinski::sierpinski(&t14));
    run("menger", &|| menger::menger(&tor(150, 150), &menger::MengerOptions::default()));
    run("menger_sponge", &|| menger_sponge::menger_sponge(4));
    run("triangulate", &|| { let _ = t2.triangulate(); cancel::check()?; Ok(pr::cube()) });
    let sc = { let mut m = pr::cube(); for _ in 0..6 { m = sierpinski::sierpinski(&m).unwrap(); } catmull_clark::catmull_clark(&m).unwrap() };
    run("triangulate_sierp", &|| { let _ = sc.triangulate(); cancel::check()?; Ok(pr::cube()) });
}

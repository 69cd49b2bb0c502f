//! `osd-petite REQUEST RESPONSE`: uniform OpenSubdiv refinement for tests/osd/petite.py.
//! `osd-petite --time RUNS REQUEST RESPONSE`: the same refinements timed instead
//! (benches/bench_osd.py: OpenSubdiv's own library called directly).
//!
//! Both files are whitespace-separated text, one batch per file:
//! request  `n` then per mesh: `scheme levels boundary creasing V F K M`, V lines `x y z`,
//!          F lines `size i0 i1 ...`, K lines `a b sharpness` (edge creases), M lines `v sharpness`;
//! response per mesh: `V F` then V lines `x y z` (f32, shortest round-trip) and F lines
//!          `size i0 i1 ...`, or `error MESSAGE` on one line; with `--time`, per mesh one line
//!          `topology_ms primvar_ms faces`: the medians over RUNS runs (after one untimed run) of
//!          building the topology refiner and refining it uniformly, and of interpolating the
//!          positions through every level, and the last level's face count.
use opensubdiv_petite::far;
use std::error::Error;
use std::time::Instant;

type Res<T> = Result<T, Box<dyn Error>>;

struct Tokens<'a>(std::str::SplitWhitespace<'a>);

impl Tokens<'_> {
    fn word(&mut self) -> Res<&str> {
        self.0.next().ok_or_else(|| "request ends early".into())
    }
    fn num<T: std::str::FromStr>(&mut self) -> Res<T>
    where
        T::Err: Error + 'static,
    {
        Ok(self.word()?.parse::<T>()?)
    }
}

/// One mesh of a request.
struct Request {
    options: far::TopologyRefinerOptions,
    levels: usize,
    nv: usize,
    pos: Vec<f32>,
    sizes: Vec<u32>,
    idx: Vec<u32>,
    crease_v: Vec<u32>,
    crease_s: Vec<f32>,
    corner_v: Vec<u32>,
    corner_s: Vec<f32>,
}

fn parse(t: &mut Tokens) -> Res<Request> {
    let scheme = match t.word()? {
        "loop" => far::Scheme::Loop,
        "catmull_clark" => far::Scheme::CatmullClark,
        "bilinear" => far::Scheme::Bilinear,
        s => return Err(format!("unknown scheme {s}").into()),
    };
    let levels: usize = t.num()?;
    let boundary = match t.word()? {
        "edge_only" => far::BoundaryInterpolation::EdgeOnly,
        "edge_and_corner" => far::BoundaryInterpolation::EdgeAndCorner,
        s => return Err(format!("unknown boundary {s}").into()),
    };
    let creasing = match t.word()? {
        "uniform" => far::CreasingMethod::Uniform,
        "chaikin" => far::CreasingMethod::Chaikin,
        s => return Err(format!("unknown creasing method {s}").into()),
    };
    let (nv, nf, nk, nm): (usize, usize, usize, usize) = (t.num()?, t.num()?, t.num()?, t.num()?);
    let mut pos = Vec::with_capacity(3 * nv);
    for _ in 0..3 * nv {
        pos.push(t.num::<f32>()?);
    }
    let (mut sizes, mut idx) = (Vec::with_capacity(nf), Vec::new());
    for _ in 0..nf {
        let n: u32 = t.num()?;
        sizes.push(n);
        for _ in 0..n {
            idx.push(t.num::<u32>()?);
        }
    }
    let (mut crease_v, mut crease_s) = (Vec::new(), Vec::new());
    for _ in 0..nk {
        crease_v.push(t.num::<u32>()?);
        crease_v.push(t.num::<u32>()?);
        crease_s.push(t.num::<f32>()?);
    }
    let (mut corner_v, mut corner_s) = (Vec::new(), Vec::new());
    for _ in 0..nm {
        corner_v.push(t.num::<u32>()?);
        corner_s.push(t.num::<f32>()?);
    }
    let options = far::TopologyRefinerOptions { scheme, boundary_interpolation: Some(boundary), creasing_method: creasing, ..Default::default() };
    Ok(Request { options, levels, nv, pos, sizes, idx, crease_v, crease_s, corner_v, corner_s })
}

/// The uniformly refined topology of `r`.
fn refiner(r: &Request) -> Res<far::TopologyRefiner> {
    let mut desc = far::TopologyDescriptor::new(r.nv, &r.sizes, &r.idx)?;
    if !r.crease_s.is_empty() {
        desc.creases(&r.crease_v, &r.crease_s);
    }
    if !r.corner_s.is_empty() {
        desc.corners(&r.corner_v, &r.corner_s);
    }
    let mut refiner = far::TopologyRefiner::new(desc, r.options)?;
    refiner.refine_uniform(far::topology_refiner::UniformRefinementOptions { refinement_level: r.levels, ..Default::default() });
    Ok(refiner)
}

/// The positions of `r` through every level of `refiner`.
fn positions(r: &Request, refiner: &far::TopologyRefiner) -> Res<Vec<f32>> {
    let primvar = far::PrimvarRefiner::new(refiner)?;
    let mut pos = r.pos.clone();
    for level in 1..=r.levels {
        pos = primvar.interpolate(level, 3, &pos).ok_or("interpolation failed")?;
    }
    Ok(pos)
}

fn refine_one(t: &mut Tokens, out: &mut String) -> Res<()> {
    let r = parse(t)?;
    let refiner = refiner(&r)?;
    let pos = positions(&r, &refiner)?;
    let last = refiner.level(r.levels).ok_or("no refined level")?;
    use std::fmt::Write;
    writeln!(out, "{} {}", pos.len() / 3, last.face_count())?;
    for p in pos.chunks(3) {
        writeln!(out, "{} {} {}", p[0], p[1], p[2])?;
    }
    for face in last.face_vertices_iter() {
        write!(out, "{}", face.len())?;
        for v in face {
            write!(out, " {}", v.0)?;
        }
        out.push('\n');
    }
    Ok(())
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time_one(t: &mut Tokens, runs: usize, out: &mut String) -> Res<()> {
    let r = parse(t)?;
    let (mut topo, mut prim) = (Vec::with_capacity(runs), Vec::with_capacity(runs));
    let mut faces = 0;
    for run in 0..=runs {
        let t0 = Instant::now();
        let refiner = refiner(&r)?;
        let t1 = Instant::now();
        let pos = positions(&r, &refiner)?;
        let t2 = Instant::now();
        faces = refiner.level(r.levels).ok_or("no refined level")?.face_count();
        std::hint::black_box(&pos);
        if run > 0 {
            topo.push((t1 - t0).as_secs_f64() * 1e3);
            prim.push((t2 - t1).as_secs_f64() * 1e3);
        }
    }
    use std::fmt::Write;
    writeln!(out, "{} {} {}", median(topo), median(prim), faces)?;
    Ok(())
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().collect();
    let (runs, files) = match args.get(1).map(String::as_str) {
        Some("--time") if args.len() == 5 => (Some(args[2].parse::<usize>()?.max(1)), &args[3..]),
        _ if args.len() == 3 => (None, &args[1..]),
        _ => return Err("usage: osd-petite [--time RUNS] REQUEST RESPONSE".into()),
    };
    let text = std::fs::read_to_string(&files[0])?;
    let mut t = Tokens(text.split_whitespace());
    let n: usize = t.num()?;
    let mut out = String::new();
    for _ in 0..n {
        let mut one = String::new();
        // a bad request ends the batch: its tokens cannot be skipped reliably
        let done = match runs {
            Some(k) => time_one(&mut t, k, &mut one),
            None => refine_one(&mut t, &mut one),
        };
        match done {
            Ok(()) => out.push_str(&one),
            Err(e) => {
                out.push_str(&format!("error {}\n", e.to_string().replace('\n', " ")));
                break;
            }
        }
    }
    std::fs::write(&files[1], out)?;
    Ok(())
}

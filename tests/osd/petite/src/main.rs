//! `osd-petite REQUEST RESPONSE`: uniform OpenSubdiv refinement for tests/osd/petite.py.
//!
//! Both files are whitespace-separated text, one batch per file:
//! request  `n` then per mesh: `scheme levels boundary creasing V F K M`, V lines `x y z`,
//!          F lines `size i0 i1 ...`, K lines `a b sharpness` (edge creases), M lines `v sharpness`;
//! response per mesh: `V F` then V lines `x y z` (f32, shortest round-trip) and F lines
//!          `size i0 i1 ...`, or `error MESSAGE` on one line.
use opensubdiv_petite::far;
use std::error::Error;

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

fn refine_one(t: &mut Tokens, out: &mut String) -> Res<()> {
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

    let mut desc = far::TopologyDescriptor::new(nv, &sizes, &idx)?;
    if nk > 0 {
        desc.creases(&crease_v, &crease_s);
    }
    if nm > 0 {
        desc.corners(&corner_v, &corner_s);
    }
    let options = far::TopologyRefinerOptions {
        scheme,
        boundary_interpolation: Some(boundary),
        creasing_method: creasing,
        ..Default::default()
    };
    let mut refiner = far::TopologyRefiner::new(desc, options)?;
    refiner.refine_uniform(far::topology_refiner::UniformRefinementOptions {
        refinement_level: levels,
        ..Default::default()
    });
    let primvar = far::PrimvarRefiner::new(&refiner)?;
    for level in 1..=levels {
        pos = primvar.interpolate(level, 3, &pos).ok_or("interpolation failed")?;
    }
    let last = refiner.level(levels).ok_or("no refined level")?;
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

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 3 {
        return Err("usage: osd-petite REQUEST RESPONSE".into());
    }
    let text = std::fs::read_to_string(&args[1])?;
    let mut t = Tokens(text.split_whitespace());
    let n: usize = t.num()?;
    let mut out = String::new();
    for _ in 0..n {
        let mut one = String::new();
        // a bad request ends the batch: its tokens cannot be skipped reliably
        match refine_one(&mut t, &mut one) {
            Ok(()) => out.push_str(&one),
            Err(e) => {
                out.push_str(&format!("error {}\n", e.to_string().replace('\n', " ")));
                break;
            }
        }
    }
    std::fs::write(&args[2], out)?;
    Ok(())
}

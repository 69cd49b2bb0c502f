//! Peak heap bytes of `iterations = L` in the core, per output face and as a
//! multiple of the exported arrays (issue 19's `× export`: float64 vertices,
//! int64 face sizes and indices): `cargo run --release --example peak_levels
//! -- catmull_clark|loop|midpoint|doo_sabin|sqrt3|simplest|dual|honeycomb|vertex_truncation [LEVELS]` (`TOPOMESH_PROF_INPUT=torus`:
//! the 100k-quad torus, else the 82k-triangle sphere). Counts what Rust
//! allocates (a counting global allocator), not the RSS.
//!
//! `TOPOMESH_PROF_OPEN=1` removes every 997th face (schemes `catmull_clark_level`, `loop_level`,
//! `midpoint_level`, `doo_sabin_level`, `sqrt3_level`, `simplest_level`, `dual_level`: the level
//! path open meshes take); `TOPOMESH_PROF_SMALL=1` takes inputs 16–25× smaller; `TOPOMESH_PEAK_MAX=2` makes it a check (`.ci/run` runs it): it exits
//! with status 1 when a level's peak exceeds that multiple of the export.
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use topomesh::schemes::{catmull_clark::catmull_clark, doo_sabin::doo_sabin, loop_subdivision::loop_subdivision, midpoint::midpoint};
use topomesh::schemes::catmull_clark::catmull_clark_level;
use topomesh::schemes::level::Request;
use topomesh::schemes::loop_subdivision::loop_level;
use topomesh::schemes::{dual::dual, honeycomb::honeycomb, simplest::simplest, sqrt3::sqrt3, vertex_truncation::{vertex_truncation, Truncation}};
use topomesh::{primitives, Mesh};

struct Counting;
static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
/// TOPOMESH_PROF_LOG: print every block of 1 MB or more as it comes and goes.
static LOG: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
fn log(what: &str, size: usize) {
    if size >= 1 << 20 && LOG.load(Relaxed) {
        // no allocation here: a fixed buffer written to stderr
        use std::io::Write;
        let mut b = [0u8; 96];
        let mut c = std::io::Cursor::new(&mut b[..]);
        let _ = writeln!(c, "{what} {:.2} MB (now {:.1} MB)", size as f64 / 1e6, NOW.load(Relaxed) as f64 / 1e6);
        let n = c.position() as usize;
        let _ = std::io::stderr().write_all(&b[..n]);
    }
}
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let n = NOW.fetch_add(l.size(), Relaxed) + l.size();
        PEAK.fetch_max(n, Relaxed);
        log("alloc", l.size());
        unsafe { System.alloc(l) }
    }
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        let n = NOW.fetch_add(l.size(), Relaxed) + l.size();
        PEAK.fetch_max(n, Relaxed);
        log("zeroed", l.size());
        unsafe { System.alloc_zeroed(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        NOW.fetch_sub(l.size(), Relaxed);
        log("free", l.size());
        unsafe { System.dealloc(p, l) }
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, new: usize) -> *mut u8 {
        log("realloc", new);
        if new > l.size() {
            let n = NOW.fetch_add(new - l.size(), Relaxed) + new - l.size();
            PEAK.fetch_max(n, Relaxed);
        } else {
            NOW.fetch_sub(l.size() - new, Relaxed);
        }
        unsafe { System.realloc(p, l, new) }
    }
}
#[global_allocator]
static A: Counting = Counting;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let scheme = a.get(1).map_or("catmull_clark", |s| s.as_str());
    let levels: usize = a.get(2).map_or(3, |s| s.parse().unwrap());
    let step: fn(&Mesh) -> topomesh::Result<Mesh> = match scheme {
        "catmull_clark_level" => |m| catmull_clark_level(m, &Request::plain()).map(|l| l.mesh),
        "loop_level" => |m| loop_level(m, &Request::plain()).map(|l| l.mesh),
        "midpoint_level" => |m| topomesh::schemes::midpoint::midpoint_level(m, &Request::plain()).map(|l| l.mesh),
        "doo_sabin_level" => |m| topomesh::schemes::doo_sabin::doo_sabin_level(m, &Request::plain()).map(|l| l.mesh),
        "sqrt3_level" => |m| topomesh::schemes::sqrt3::sqrt3_level(m, &Request::plain()).map(|l| l.mesh),
        "simplest_level" => |m| topomesh::schemes::simplest::simplest_level(m, &Request::plain()).map(|l| l.mesh),
        "dual_level" => |m| topomesh::schemes::dual::dual_level(m, &Request::plain()).map(|l| l.mesh),
        "loop" => loop_subdivision,
        "midpoint" => midpoint,
        "doo_sabin" => doo_sabin,
        "sqrt3" => sqrt3,
        "simplest" => simplest,
        "dual" => dual,
        "honeycomb" => |m| honeycomb(m, 0.5, None),
        "vertex_truncation" => |m| vertex_truncation(m, Truncation::Chaikin),
        _ => catmull_clark,
    };
    // the levels after the first of `iterations = L` on an input nobody else holds
    let owned: Option<fn(Mesh) -> topomesh::Result<Mesh>> = match scheme {
        "sqrt3" | "sqrt3_level" => Some(|m| topomesh::schemes::sqrt3::sqrt3_level_owned(m, &Request::plain()).map(|l| l.mesh)),
        "dual" | "dual_level" => Some(|m| topomesh::schemes::dual::dual_level_owned(m, &Request::plain()).map(|l| l.mesh)),
        "simplest" | "simplest_level" => Some(|m| topomesh::schemes::simplest::simplest_level_owned(m, &Request::plain()).map(|l| l.mesh)),
        "honeycomb" => Some(|m| topomesh::schemes::honeycomb::honeycomb_level_owned(m, 0.5, None, &Request::plain()).map(|l| l.mesh)),
        "vertex_truncation" => Some(|m| topomesh::schemes::vertex_truncation::vertex_truncation_level_owned(m, Truncation::Chaikin, &Request::plain()).map(|l| l.mesh)),
        _ => None,
    };
    // TOPOMESH_PROF_SMALL: inputs 16-25x smaller (CI runs the debug build)
    let small = std::env::var("TOPOMESH_PROF_SMALL").is_ok();
    let input = if std::env::var("TOPOMESH_PROF_INPUT").is_ok_and(|s| s == "torus") {
        if small { primitives::torus(80, 50, 3.0, 1.0) } else { primitives::torus(400, 250, 3.0, 1.0) }.unwrap()
    } else {
        let mut s = primitives::icosahedron();
        for _ in 0..if small { 4 } else { 6 } {
            s = loop_subdivision(&s).unwrap();
        }
        s
    };
    // TOPOMESH_PROF_OPEN: every 997th face removed (open levels; the plain
    // level request, as the extension makes it)
    let input = if std::env::var("TOPOMESH_PROF_OPEN").is_ok() {
        let p = input.to_polygons();
        let (mut sizes, mut idx, mut at) = (Vec::new(), Vec::new(), 0usize);
        for (f, &n) in p.sizes.iter().enumerate() {
            if f % 997 != 0 {
                sizes.push(n as i64);
                idx.extend(p.indices[at..at + n as usize].iter().map(|&i| i as i64));
            }
            at += n as usize;
        }
        let opts = topomesh::BuildOptions { close_boundaries: true, ..Default::default() };
        Mesh::from_polygons(input.positions().to_vec(), &sizes, &idx, opts).unwrap()
    } else {
        input
    };
    LOG.store(std::env::var("TOPOMESH_PROF_LOG").is_ok(), Relaxed);
    let max: Option<f64> = std::env::var("TOPOMESH_PEAK_MAX").ok().map(|s| s.parse().expect("TOPOMESH_PEAK_MAX: a number"));
    let mut over = false;
    for l in 1..=levels {
        let base = NOW.load(Relaxed);
        PEAK.store(base, Relaxed);
        let mut cur: Option<Mesh> = None;
        for _ in 0..l {
            // a previous level is given up where the scheme can use that, as the extension does
            let next = match (cur.take(), owned) {
                (Some(m), Some(f)) => f(m).unwrap(),
                (Some(m), None) => step(&m).unwrap(),
                (None, _) => step(&input).unwrap(),
            };
            cur = Some(next);
        }
        let m = cur.unwrap();
        let grow = (PEAK.load(Relaxed) - base) as f64;
        let held = (NOW.load(Relaxed) - base) as f64;
        let export = (24 * m.n_vertices() + 8 * m.n_faces() + 16 * m.n_edges()) as f64;
        let nf = m.n_faces() as f64;
        println!(
            "{scheme} L{l}: {} faces, peak {:.1} B/face ({:.2}x export), mesh {:.1} B/face ({:.2}x)",
            m.n_faces(),
            grow / nf,
            grow / export,
            held / nf,
            held / export
        );
        if max.is_some_and(|x| grow / export > x) {
            println!("{scheme} L{l}: peak {:.2}x the export is over TOPOMESH_PEAK_MAX = {}", grow / export, max.unwrap());
            over = true;
        }
    }
    if over {
        std::process::exit(1);
    }
}

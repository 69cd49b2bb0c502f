//! PyO3 bindings: the `topomesh._core` extension module. Thin: argument
//! conversion, GIL release around heavy work, error mapping. Each topic has
//! its own file; scheme files add methods to `Mesh` with their own
//! `#[pymethods] impl PyMesh` block (pyo3's `multiple-pymethods`).

use pyo3::prelude::*;

mod alloc;
mod boundary;
mod conway;
mod data;
mod levels;
mod display;
pub(crate) mod convert;
pub(crate) mod ifs;
mod io;
pub(crate) mod fractal;
pub(crate) mod mesh;
mod refine;
mod topmod;
mod repair;
mod ops;
mod tools;
mod perf;
mod primitives;
mod printing;
mod smooth;
mod pool;

pyo3::create_exception!(
    topomesh,
    MeshError,
    pyo3::exceptions::PyValueError,
    "Invalid mesh input or a broken operator precondition; the message names the face, vertex or edge."
);

pyo3::create_exception!(
    topomesh,
    GeometryWarning,
    pyo3::exceptions::PyUserWarning,
    "A result that is a valid manifold but geometrically flawed (for example self-intersecting); the message says where and how much."
);

/// Raises `msg` as a `topomesh.GeometryWarning` at the caller's line (an
/// error when warnings are errors).
pub(crate) fn warn_geometry(py: Python<'_>, msg: String) -> PyResult<()> {
    let msg = std::ffi::CString::new(msg).expect("no NUL in the message");
    PyErr::warn(py, &py.get_type::<GeometryWarning>(), &msg, 1)
}

/// Maps a core error to Python: `Interrupted` to `KeyboardInterrupt`, the
/// rest to `topomesh.MeshError` (a `ValueError`).
pub(crate) fn err(e: crate::MeshError) -> PyErr {
    match e {
        crate::MeshError::Interrupted => pyo3::exceptions::PyKeyboardInterrupt::new_err("interrupted"),
        e => MeshError::new_err(e.to_string()),
    }
}

pub(crate) fn arg_err(msg: impl Into<String>) -> PyErr {
    MeshError::new_err(msg.into())
}

/// An integer argument of any size (`#[pyo3(from_py_with = big_int)] x:
/// i128`): Python ints beyond `i128` saturate, so range checks ([`int_in`])
/// name the parameter instead of pyo3 raising a bare `OverflowError`.
pub(crate) fn big_int(obj: &Bound<'_, PyAny>) -> PyResult<i128> {
    match obj.extract::<i128>() {
        Ok(v) => Ok(v),
        Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(obj.py()) => {
            Ok(if obj.lt(0)? { i128::MIN } else { i128::MAX })
        }
        Err(e) => Err(e),
    }
}

/// An index argument (`#[pyo3(from_py_with = sat_i64)] x: i64`): ints beyond
/// `i64` saturate, so the callee's range check reports them as out of range
/// (a `MeshError`) instead of pyo3 raising `OverflowError`.
pub(crate) fn sat_i64(obj: &Bound<'_, PyAny>) -> PyResult<i64> {
    Ok(big_int(obj)?.clamp(i64::MIN as i128, i64::MAX as i128) as i64)
}

/// `v` when it lies in `lo..=hi`, else a `MeshError` naming `call`, the
/// parameter `name` and the range.
pub(crate) fn int_in(call: &str, name: &str, v: i128, lo: i64, hi: i64) -> PyResult<i64> {
    if (lo as i128..=hi as i128).contains(&v) {
        return Ok(v as i64);
    }
    let shown = match v {
        i128::MAX => "a huge value (>= 2**127)".to_string(),
        i128::MIN => "a huge negative value".to_string(),
        v => v.to_string(),
    };
    let allowed = if hi == i64::MAX { format!(">= {lo}") } else { format!("in [{lo}, {hi}]") };
    Err(arg_err(format!("{call}: {name} = {shown} must be {allowed} (an integer)")))
}

/// [`int_in`] as a `usize`.
pub(crate) fn usize_in(call: &str, name: &str, v: i128, lo: usize, hi: usize) -> PyResult<usize> {
    Ok(int_in(call, name, v, lo as i64, hi.min(i64::MAX as usize) as i64)? as usize)
}

/// A finite float argument in `[lo, hi]`, else a `MeshError` naming it.
/// `lo = f64::MIN_POSITIVE` means positive: `(0, hi]`, subnormals included,
/// as the message says.
pub(crate) fn finite_in(call: &str, name: &str, x: f64, lo: f64, hi: f64) -> PyResult<f64> {
    let above = if lo == f64::MIN_POSITIVE { x > 0.0 } else { x >= lo };
    if x.is_finite() && above && x <= hi {
        Ok(x)
    } else {
        Err(arg_err(format!("{call}: {name} = {} is out of range; it must be a finite number in {}", crate::error::num(x), crate::error::range(lo, hi))))
    }
}

/// `py.detach(f)` with `f` run in this process's thread pool ([`pool`]):
/// every parallel loop the extension starts must run there.
pub(crate) fn detach<T: Send>(py: Python<'_>, f: impl FnOnce() -> T + Send) -> T {
    py.detach(|| pool::run(f))
}

/// How often the calling thread takes the GIL back to look for Ctrl-C.
const POLL: std::time::Duration = std::time::Duration::from_millis(50);

/// Runs `work` on a worker thread while the calling thread, with the GIL
/// released except for a moment every 50 ms, checks for signals and calls
/// `on_poll` (progress bars). On `KeyboardInterrupt` (or any error a signal
/// handler raises) it sets the core's cancellation flag, waits for the worker
/// to stop at its next poll, clears the flag once no other call runs (they
/// stop too: `crate::cancel::reset_when_idle`) and returns that error; the
/// worker's partial results are dropped.
pub(crate) fn run_interruptible_with<T: Send>(
    py: Python<'_>,
    work: impl FnOnce() -> crate::Result<T> + Send,
    mut on_poll: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<T> {
    use std::sync::atomic::{AtomicBool, Ordering};
    let caller = std::thread::current();
    // set before the unpark: `is_finished` turns true only once the thread
    // has exited, after the unpark, so waiting on it lost the wake-up and
    // slept a whole poll interval on every short call
    let done = AtomicBool::new(false);
    std::thread::scope(|s| {
        // named, so that a stray thread it started would show (tests/test_threads.py)
        let worker = std::thread::Builder::new().name("topomesh-call".into()).spawn_scoped(s, || {
            // in topomesh's pool, never rayon's global one (`pool` module docs)
            let r = pool::run(work);
            done.store(true, Ordering::Release);
            caller.unpark();
            r
        });
        let Ok(worker) = worker else {
            return Err(err(crate::error::MeshError::Memory("could not start a worker thread".into())));
        };
        loop {
            // park_timeout may wake early (the unpark token, spuriously): only
            // the flag decides
            py.detach(|| {
                if !done.load(Ordering::Acquire) {
                    std::thread::park_timeout(POLL);
                }
            });
            if done.load(Ordering::Acquire) {
                break;
            }
            let polled = py.check_signals().and_then(|()| on_poll(py));
            if let Err(e) = polled {
                crate::cancel::request();
                let _ = py.detach(|| worker.join());
                // other calls may still be running: cleared once none is
                crate::cancel::reset_when_idle();
                return Err(e);
            }
        }
        match worker.join() {
            Ok(r) => r.map_err(err),
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}

/// [`run_interruptible_with`] with nothing to do between polls.
pub(crate) fn run_interruptible<T: Send>(py: Python<'_>, work: impl FnOnce() -> crate::Result<T> + Send) -> PyResult<T> {
    run_interruptible_with(py, work, |_| Ok(()))
}

/// Runs one level of a scheme `iterations` times, interruptibly with the GIL
/// released, one tqdm update per level when `progress` is true.
///
/// Memory: every level is checked up front against the budget with the
/// lower bounds of `predict` (the scheme's count formulas), then each level
/// again from the real counts of its input with the upper bound, and a
/// refusal is a `MeshError` naming the call, level, bytes and budget.
/// `iterations` outside `0..` is a `MeshError` naming the scheme; 0 returns
/// an equal mesh.
///
/// For the remeshing schemes built through the keyed builder: the output
/// inherits `data`'s face attributes through the face parents composed
/// over the levels (`crate::schemes::face_parents`), and the rest of the
/// data is dropped with a warning ([`data::inherited`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn iterate_traced(
    py: Python<'_>,
    mesh: &crate::Mesh,
    data: &data::MeshData,
    iterations: i128,
    progress: bool,
    name: &str,
    predict: crate::budget::Predictor,
    step: impl Fn(&crate::Mesh) -> crate::Result<crate::Mesh> + Sync,
) -> PyResult<mesh::PyMesh> {
    use crate::schemes::face_parents::{compose_parents, traced};
    // TopMod's remeshing entries have no boundary rule: an open mesh is
    // refused under the entry's own name (a composition's inner step, e.g.
    // root3's dual, would otherwise name itself)
    if iterations > 0 {
        crate::schemes::hosts::refuse_holes(name, mesh).map_err(err)?;
    }
    // None: not wanted (no face attributes) or a level recorded nothing
    let start = (!data.face.is_empty()).then(|| (0..mesh.n_faces() as u32).collect::<Vec<u32>>());
    let (out, parents) = iterate_with(py, mesh, iterations, progress, name, predict, start, |src, st| {
        let m: &crate::Mesh = &src;
        if st.is_none() {
            return step(m);
        }
        let (out, p) = traced(m, || step(m))?;
        *st = match (st.take(), p) {
            (Some(a), Some(b)) => Some(compose_parents(&a, &b)),
            _ => None,
        };
        Ok(out)
    })?;
    data::inherited(py, data, name, mesh, out.unwrap_or_else(|| mesh.clone()), parents)
}

/// A level's input in [`iterate_with`]: the caller's mesh, or the previous
/// level's, which the step may consume.
pub(crate) enum Src<'a> {
    Input(&'a crate::Mesh),
    Level(crate::Mesh),
}

impl std::ops::Deref for Src<'_> {
    type Target = crate::Mesh;
    fn deref(&self) -> &crate::Mesh {
        match self {
            Src::Input(m) => m,
            Src::Level(m) => m,
        }
    }
}

/// [`iterate_traced`] with a state carried from level to level (attributes,
/// stencils, origins); returns the last level's mesh (None for 0 levels)
/// and the state. The step owns the previous level (issue 19: an input
/// freed as soon as it is no longer needed); it is dropped when the step
/// returns if the step did not consume it.
#[allow(clippy::too_many_arguments)]
pub(crate) fn iterate_with<S: Send>(
    py: Python<'_>,
    mesh: &crate::Mesh,
    iterations: i128,
    progress: bool,
    name: &str,
    predict: crate::budget::Predictor,
    mut state: S,
    step: impl Fn(Src<'_>, &mut S) -> crate::Result<crate::Mesh> + Sync,
) -> PyResult<(Option<crate::Mesh>, S)> {
    use crate::budget::{self, Counts};
    use std::sync::atomic::{AtomicU64, Ordering};
    let n = int_in(name, "iterations", iterations, 0, i64::MAX)? as u64;
    let start = Counts::of(mesh);
    detach(py, || budget::check_levels(name, &start, n, predict)).map_err(err)?;
    let bar = if progress {
        let kw = pyo3::types::PyDict::new(py);
        kw.set_item("total", n)?;
        kw.set_item("desc", name)?;
        Some(py.import("tqdm")?.getattr("tqdm")?.call((), Some(&kw))?)
    } else {
        None
    };
    let done = AtomicU64::new(0);
    let mut shown = 0u64;
    let mut update = |py: Python<'_>| -> PyResult<()> {
        if let Some(b) = &bar {
            let d = done.load(Ordering::Relaxed);
            if d > shown {
                b.call_method1("update", (d - shown,))?;
                shown = d;
            }
        }
        let _ = py;
        Ok(())
    };
    let out = run_interruptible_with(
        py,
        || {
            let mut cur: Option<crate::Mesh> = None;
            for k in 1..=n {
                crate::cancel::check()?;
                let src = cur.take().map_or(Src::Input(mesh), Src::Level);
                budget::check_level(name, k, n, &Counts::of(&src), predict)?;
                // the earlier levels' freed temporaries, returned to the
                // system before the largest level (issue 19's peak target)
                if k == n && k > 1 && src.n_halfedges() >= alloc::TRIM_MIN_HALFEDGES {
                    alloc::release_free_heap();
                }
                cur = Some(step(src, &mut state)?);
                done.store(k, Ordering::Relaxed);
            }
            Ok((cur, state))
        },
        &mut update,
    );
    if out.is_ok() {
        update(py)?;
    }
    if let Some(b) = &bar {
        b.call_method0("close")?;
    }
    if let Ok((Some(m), _)) = &out {
        data::finite_output(name, mesh, m)?;
    }
    out
}

/// Sets the memory budget of every topomesh call, in bytes.
///
/// Parameters
/// ----------
/// nbytes : int or None
///     The budget (>= 0); ``None`` returns to the default: the environment
///     variable ``TOPOMESH_MEMORY_BUDGET`` (bytes, or with a K/M/G/T suffix)
///     if set, else the machine's available memory (``MemAvailable``, lowered
///     to the room under an address-space limit), recomputed at each call.
///
/// Raises
/// ------
/// MeshError
///     ``nbytes`` negative.
#[pyfunction]
#[pyo3(signature = (nbytes))]
fn set_memory_budget(nbytes: &Bound<'_, PyAny>) -> PyResult<()> {
    let b = if nbytes.is_none() {
        None
    } else {
        let v = big_int(nbytes).map_err(|_| arg_err(format!("set_memory_budget: nbytes = {nbytes} must be an integer >= 0 or None")))?;
        Some(int_in("set_memory_budget", "nbytes", v, 0, i64::MAX)? as u64)
    };
    crate::budget::set(b);
    Ok(())
}

/// The memory budget in force, in bytes (see :func:`set_memory_budget`).
///
/// Returns
/// -------
/// int
///     Calls whose predicted peak exceeds it raise ``MeshError`` before
///     allocating.
#[pyfunction]
fn memory_budget() -> PyResult<u64> {
    crate::budget::get().map_err(err)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("MeshError", m.py().get_type::<MeshError>())?;
    m.add("GeometryWarning", m.py().get_type::<GeometryWarning>())?;
    mesh::register(m)?;
    ops::register(m)?;
    tools::register(m)?;
    ifs::register(m)?;
    fractal::register(m)?;
    io::register(m)?;
    conway::register(m)?;
    perf::register(m)?;
    m.add_function(wrap_pyfunction!(set_memory_budget, m)?)?;
    m.add_function(wrap_pyfunction!(memory_budget, m)?)?;
    // rust-numpy imports NumPy's C API (and checks its version, in Python)
    // on the first array it makes; done here, a Ctrl-C can never land in
    // that import (it panicked there when the first array of a process was
    // an interrupted call's result)
    let _ = numpy::PyArray1::<f64>::zeros(m.py(), 0, false);
    Ok(())
}

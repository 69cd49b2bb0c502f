//! The rayon thread pool of this process, never rayon's global one.
//!
//! A forked child has none of its parent's threads. Had the parent used
//! rayon's global pool, every parallel loop in the child would queue its
//! work for threads that no longer exist and wait forever: after
//! `os.fork()` (the default `multiprocessing` start method on Linux before
//! Python 3.14) a child's `topomesh.torus(60, 40)` hung. rayon cannot
//! restart its global pool, so the extension runs its parallel work in a
//! pool of its own, made on first use in each process (again in a forked
//! child) with rayon's own defaults (`RAYON_NUM_THREADS`, else one thread
//! per core): the worker of every interruptible call, every `detach`, and
//! the few calls that hold the GIL (the Platonic solids, the output check,
//! `spherize`, `add_handle`'s corner choice).
//! `tests/test_threads.py` checks that a broad workload leaves no thread of
//! rayon's global pool and runs it again in a forked child.

use rayon::{ThreadPool, ThreadPoolBuilder};
use std::sync::{Arc, Mutex};

static POOL: Mutex<Option<(u32, Arc<ThreadPool>)>> = Mutex::new(None);

/// This process's pool (None when no thread could be started).
fn pool() -> Option<Arc<ThreadPool>> {
    let pid = std::process::id();
    let mut p = POOL.lock().unwrap_or_else(|e| e.into_inner());
    match p.as_ref() {
        Some((owner, pool)) if *owner == pid => Some(pool.clone()),
        _ => {
            // a parent's pool (after fork): its threads do not exist here,
            // so it is forgotten rather than asked to shut them down
            if let Some(old) = p.take() {
                std::mem::forget(old);
            }
            let pool = Arc::new(ThreadPoolBuilder::new().thread_name(|i| format!("topomesh-{i}")).build().ok()?);
            *p = Some((pid, pool.clone()));
            Some(pool)
        }
    }
}

/// Runs `f` in this process's pool (inline when already on one of its
/// threads, or when the pool could not start).
pub(crate) fn run<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    // registered: the cancellation flag is never cleared while it runs
    // (`crate::cancel::registered`)
    crate::cancel::registered(|| match pool() {
        Some(p) => p.install(f),
        None => f(),
    })
}

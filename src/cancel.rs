//! Cooperative cancellation: one process-wide flag that long loops poll.
//!
//! The Python binding sets it when Ctrl-C arrives while a call runs on its
//! worker thread, waits for the worker to return [`MeshError::Interrupted`],
//! and clears it once no other call runs ([`reset_when_idle`]): a call must
//! never see the flag cleared between a loop body that skipped its work and
//! its next check, or it would take the skipped work as done. Loops poll [`check`] once per chunk or phase (a relaxed
//! atomic load, about a nanosecond), never per element. A cancelled call
//! returns an error and drops everything it built, so no partial state is
//! left.

use crate::error::{MeshError, Result};
use std::sync::atomic::{AtomicBool, Ordering};

static CANCELLED: AtomicBool = AtomicBool::new(false);

/// `Err(MeshError::Interrupted)` once cancellation was requested.
#[inline]
pub fn check() -> Result<()> {
    check_flag(&CANCELLED)
}

#[inline]
fn check_flag(flag: &AtomicBool) -> Result<()> {
    if flag.load(Ordering::Relaxed) {
        Err(MeshError::Interrupted)
    } else {
        Ok(())
    }
}

/// [`check`] on every 64 Ki-th index of a sequential loop (`i % 65536 == 0`).
#[inline]
pub fn poll(i: usize) -> Result<()> {
    if i & 0xffff == 0 {
        check()
    } else {
        Ok(())
    }
}

/// Whether cancellation was requested (for loops that cannot return an error,
/// e.g. rayon `for_each` bodies: they skip their work and the caller's next
/// [`check`] reports it).
#[inline]
pub fn requested() -> bool {
    CANCELLED.load(Ordering::Relaxed)
}

/// Asks every running call to stop at its next poll.
pub fn request() {
    CANCELLED.store(true, Ordering::Relaxed);
}

/// Clears the flag.
///
/// # Safety
/// No call that polls the flag may be running, in any thread, unless it
/// runs inside [`registered`] (whose calls [`reset_when_idle`] waits for).
/// A call whose loop bodies skipped their work on seeing the flag reports
/// it at its next [`check`]; cleared in between, that check passes, and the
/// fills that write into memory never initialized
/// ([`crate::mesh::Columns::unfilled`], [`crate::mesh::unfilled_points`])
/// would then declare entries written that no body wrote.
pub unsafe fn reset() {
    CANCELLED.store(false, Ordering::Relaxed);
}

/// Calls running inside [`registered`], and whether the flag is to be
/// cleared once there are none (per process: a forked child starts over).
struct Registry {
    pid: u32,
    running: usize,
    clear_pending: bool,
}

static CALLS: std::sync::Mutex<Registry> = std::sync::Mutex::new(Registry { pid: 0, running: 0, clear_pending: false });

fn calls() -> std::sync::MutexGuard<'static, Registry> {
    let mut c = CALLS.lock().unwrap_or_else(|e| e.into_inner());
    let pid = std::process::id();
    if c.pid != pid {
        // a parent's calls (after fork) do not run here
        *c = Registry { pid, running: 0, clear_pending: false };
    }
    c
}

/// Runs `f` as a call that [`reset_when_idle`] waits for: the flag, once
/// set, stays set until every registered call has returned, so a call never
/// sees it cleared between a skipped loop body and its next check. The
/// Python extension runs all its work through here.
pub fn registered<T>(f: impl FnOnce() -> T) -> T {
    struct Leave;
    impl Drop for Leave {
        fn drop(&mut self) {
            let mut c = calls();
            c.running -= 1;
            if c.running == 0 && c.clear_pending {
                c.clear_pending = false;
                CANCELLED.store(false, Ordering::Relaxed);
            }
        }
    }
    calls().running += 1;
    let _leave = Leave;
    f()
}

/// Clears the flag now if no [`registered`] call runs, else when the last
/// one returns (they all see it set until then, and stop at their next poll).
pub fn reset_when_idle() {
    let mut c = calls();
    if c.running == 0 {
        CANCELLED.store(false, Ordering::Relaxed);
    } else {
        c.clear_pending = true;
    }
}

/// Elements per task of [`par_collect`].
const COLLECT_CHUNK: usize = 1 << 12;

/// `(0..n).map(f)` collected in parallel, chunk by chunk, stopping at the
/// first chunk after cancellation. A rayon `collect` whose bodies return
/// early still writes every element, and writing a large output onto memory
/// the machine has not touched yet page-faults at ~2.5 s/GB on these VMs:
/// that pass was 0.7-1.5 s of Ctrl-C latency in a Doo-Sabin level. Here an
/// unwritten chunk's pages are never touched.
pub fn par_collect<T: Copy + Send + Sync>(n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Result<Vec<T>> {
    par_collect_flag(&CANCELLED, n, f)
}

/// `n` copies of `value`, written as [`par_collect`] writes (in parallel,
/// stopping once cancelled) rather than by `vec![value; n]`'s sequential
/// pass, which no poll can interrupt.
pub fn par_filled<T: Copy + Send + Sync>(n: usize, value: T) -> Result<Vec<T>> {
    par_collect(n, |_| value)
}

fn par_collect_flag<T: Copy + Send + Sync>(flag: &AtomicBool, n: usize, f: impl Fn(usize) -> T + Sync + Send) -> Result<Vec<T>> {
    use rayon::prelude::*;
    use std::sync::atomic::AtomicUsize;
    let mut v: Vec<T> = Vec::with_capacity(n);
    // every element is written: the pages mapped in one call per chunk
    crate::mesh::populate(&mut v, n);
    let done = AtomicUsize::new(0);
    v.spare_capacity_mut()[..n].par_chunks_mut(COLLECT_CHUNK).enumerate().for_each(|(k, ch)| {
        if flag.load(Ordering::Relaxed) {
            return;
        }
        for (j, slot) in ch.iter_mut().enumerate() {
            slot.write(f(k * COLLECT_CHUNK + j));
        }
        done.fetch_add(ch.len(), Ordering::Relaxed);
    });
    check_flag(flag)?;
    if done.load(Ordering::Relaxed) != n {
        return Err(MeshError::Interrupted);
    }
    // SAFETY: the chunks cover 0..n and every one was written in full (their
    // lengths sum to n); T is Copy, so nothing needs dropping either way.
    unsafe { v.set_len(n) };
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// While a registered call runs, a reset waits for it; the last call
    /// out clears. (The flag itself is left alone: the schemes' tests run
    /// in parallel in this process and would stop; the core's tests make no
    /// other registered call.)
    #[test]
    fn reset_waits_for_registered_calls() {
        registered(|| {
            reset_when_idle();
            let c = calls();
            assert!(c.clear_pending && c.running == 1);
        });
        let c = calls();
        assert!(!c.clear_pending && c.running == 0);
    }


    /// On a local flag: setting the process-wide one here would make the
    /// schemes tested in parallel skip work (a rayon body sees `requested()`)
    /// and, once reset, build from the skipped (zeroed) buffers.
    #[test]
    fn flag_round_trip() {
        let flag = AtomicBool::new(false);
        assert!(check_flag(&flag).is_ok());
        flag.store(true, Ordering::Relaxed);
        assert_eq!(check_flag(&flag), Err(MeshError::Interrupted));
        flag.store(false, Ordering::Relaxed);
        assert!(check_flag(&flag).is_ok());
        assert!(check().is_ok() && !requested());
    }

    #[test]
    fn par_collect_is_map_collect_and_stops_when_cancelled() {
        let flag = AtomicBool::new(false);
        for n in [0, 1, COLLECT_CHUNK - 1, COLLECT_CHUNK, 5 * COLLECT_CHUNK + 7] {
            let v = par_collect_flag(&flag, n, |i| (i as u64) * 3 + 1).unwrap();
            assert_eq!(v, (0..n as u64).map(|i| i * 3 + 1).collect::<Vec<_>>());
        }
        // set from inside the bodies: later chunks stop and the call errs
        let v = par_collect_flag(&flag, 64 * COLLECT_CHUNK, |i| {
            if i == 3 {
                flag.store(true, Ordering::Relaxed);
            }
            i
        });
        assert_eq!(v, Err(MeshError::Interrupted));
    }
}

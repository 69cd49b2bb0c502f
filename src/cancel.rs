//! Cooperative cancellation: one process-wide flag that long loops poll.
//!
//! The Python binding sets it when Ctrl-C arrives while a call runs on its
//! worker thread, waits for the worker to return [`MeshError::Interrupted`],
//! and clears it. Loops poll [`check`] once per chunk or phase (a relaxed
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

/// Clears the flag (after the cancelled call has returned).
pub fn reset() {
    CANCELLED.store(false, Ordering::Relaxed);
}

#[cfg(test)]
mod tests {
    use super::*;

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
}

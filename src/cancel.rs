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
    if CANCELLED.load(Ordering::Relaxed) {
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

    #[test]
    fn flag_round_trip() {
        assert!(check().is_ok());
        request();
        assert_eq!(check(), Err(MeshError::Interrupted));
        reset();
        assert!(check().is_ok());
    }
}

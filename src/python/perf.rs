//! Performance knobs (issue 19): the allocator's block cache.

use super::{arg_err, big_int, int_in};
use pyo3::prelude::*;

/// Sets how many bytes of large freed blocks topomesh's allocator may keep
/// for reuse (the block cache; off by default).
///
/// The cache only helps calls that repeat the same sizes (warm benchmarks,
/// iterations over one mesh): it saves zeroing fresh pages, at the price of
/// keeping up to ``nbytes`` resident between calls. The environment variable
/// ``TOPOMESH_BLOCK_CACHE`` (bytes or a size such as ``"256M"``) sets it
/// when the module loads.
///
/// Parameters
/// ----------
/// nbytes : int
///     Limit in bytes, 0 to 2**30; 0 turns the cache off and frees what it
///     holds.
///
/// Returns
/// -------
/// int
///     The previous limit.
#[pyfunction]
fn set_block_cache(nbytes: &Bound<'_, PyAny>) -> PyResult<usize> {
    let v = big_int(nbytes).map_err(|_| arg_err(format!("set_block_cache: nbytes = {nbytes} must be an integer")))?;
    let b = int_in("set_block_cache", "nbytes", v, 0, super::alloc::MAX_CACHED as i64)? as usize;
    Ok(super::alloc::set_block_cache(b))
}

/// The block cache's limit and the bytes it holds now (see
/// :func:`set_block_cache`).
///
/// Returns
/// -------
/// tuple of (int, int)
///     ``(limit, held)`` in bytes.
#[pyfunction]
fn block_cache() -> (usize, usize) {
    super::alloc::block_cache()
}

/// Whether output buffers are populated before their fill
/// (`TOPOMESH_POPULATE`, `src/mesh/populate.rs`; tests).
#[pyfunction]
fn _populate() -> bool {
    crate::mesh::populate_on()
}

/// Whether the allocator's zeroed blocks of these sizes read zero after
/// dirty blocks of the same sizes were freed (tests; `src/python/alloc.rs`).
#[pyfunction]
fn _zeroed_blocks_are_zero(sizes: Vec<usize>) -> PyResult<bool> {
    if let Some(&n) = sizes.iter().find(|&&n| n > 1 << 30) {
        return Err(arg_err(format!("_zeroed_blocks_are_zero: size {n} is above 1 GiB")));
    }
    Ok(super::alloc::zeroed_blocks_are_zero(&sizes))
}

/// The allocator's huge-page advice as the environment set it at import:
/// ``(on, largest advised block in bytes)`` (tests; `src/python/alloc.rs`).
#[pyfunction]
fn _huge_page_advice() -> (bool, usize) {
    super::alloc::huge_pages()
}

/// An on/off switch read from the environment at import: None when unset,
/// `empty` for an empty value; a value it cannot read is an error naming the
/// variable and what it `must_be`.
fn env_switch(var: &str, empty: bool, must_be: &str) -> PyResult<Option<bool>> {
    let Ok(v) = std::env::var(var) else { return Ok(None) };
    match v.trim().to_ascii_lowercase().as_str() {
        "" => Ok(Some(empty)),
        "1" | "true" | "yes" | "on" => Ok(Some(true)),
        "0" | "false" | "no" | "off" => Ok(Some(false)),
        _ => Err(arg_err(format!("{var} = {v:?} must be {must_be}"))),
    }
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // opt-in (src/python/alloc.rs); "0" was the spelling for off when the
    // advice was on by default, and still is
    if let Some(on) = env_switch("TOPOMESH_HUGE_PAGES", false, "1 (advise huge pages) or 0 (the default)")? {
        super::alloc::set_huge_pages(on);
    }
    // on by default (src/python/alloc.rs, zero_block)
    if let Some(on) = env_switch("TOPOMESH_ZERO_DROP", true, "1 (zeroed blocks drop absent pages, the default) or 0")? {
        super::alloc::set_zero_drop(on);
    }
    // on by default (src/mesh/populate.rs)
    if let Some(on) = env_switch("TOPOMESH_POPULATE", true, "1 (map output pages in one call, the default) or 0")? {
        crate::mesh::set_populate(on);
    }
    if let Ok(s) = std::env::var("TOPOMESH_HUGE_PAGES_MAX") {
        let b = crate::budget::parse_size(&s).ok_or_else(|| {
            arg_err(format!("TOPOMESH_HUGE_PAGES_MAX = {s:?} must be a size in bytes, such as 67108864 or 64M"))
        })?;
        super::alloc::set_huge_pages_max(usize::try_from(b).unwrap_or(usize::MAX));
    }
    if let Ok(s) = std::env::var("TOPOMESH_BLOCK_CACHE") {
        let b = crate::budget::parse_size(&s).ok_or_else(|| {
            arg_err(format!("TOPOMESH_BLOCK_CACHE = {s:?} must be a size in bytes, such as 268435456 or 256M"))
        })?;
        super::alloc::set_block_cache(b.min(super::alloc::MAX_CACHED as u64) as usize);
    }
    m.add_function(wrap_pyfunction!(set_block_cache, m)?)?;
    m.add_function(wrap_pyfunction!(block_cache, m)?)?;
    m.add_function(wrap_pyfunction!(_huge_page_advice, m)?)?;
    m.add_function(wrap_pyfunction!(_zeroed_blocks_are_zero, m)?)?;
    m.add_function(wrap_pyfunction!(_populate, m)?)?;
    Ok(())
}

//! The extension module's global allocator: the system allocator plus a
//! small cache of large freed blocks.
//!
//! Every scheme and every construction allocates its output columns and
//! temporaries fresh. glibc serves blocks above its mmap threshold with a
//! new `mmap` and returns them with `munmap` on free, so every call pays a
//! page fault per 4 KiB page it touches: half the time of a Loop step on an
//! 82k-triangle sphere, measured. Keeping a few large freed blocks for the
//! next request of a similar size removes those faults when operations
//! repeat (iterations, pipelines, benchmarks).
//!
//! Bounds: blocks of at least [`MIN_BLOCK`] bytes, at most [`SLOTS`] of them
//! and [`MAX_CACHED`] bytes in total; a cached block is reused only for a
//! request of at least half its size, and a large request that no cached
//! block fits empties the cache (see [`BlockCache::take`]). Only topomesh's own (Rust)
//! allocations go through here; Python's and NumPy's are untouched.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::Mutex;

const MIN_BLOCK: usize = 1 << 20;
const SLOTS: usize = 32;
const MAX_CACHED: usize = 256 << 20;
/// Blocks with a larger alignment bypass the cache (the system allocator
/// serves them differently).
const MAX_ALIGN: usize = 16;

struct Cache {
    /// (address, size) of cached blocks; size 0 marks a free slot.
    blocks: [(usize, usize); SLOTS],
    total: usize,
}

pub(crate) struct BlockCache {
    cache: Mutex<Cache>,
}

#[global_allocator]
static GLOBAL: BlockCache = BlockCache { cache: Mutex::new(Cache { blocks: [(0, 0); SLOTS], total: 0 }) };

impl BlockCache {
    #[inline]
    fn cacheable(layout: &Layout) -> bool {
        layout.size() >= MIN_BLOCK && layout.align() <= MAX_ALIGN
    }

    /// A cached block of `size..=2 * size` bytes (the smallest), removed
    /// from the cache. The lock never allocates (a futex), so allocating
    /// under it cannot recurse.
    ///
    /// On a miss the whole cache is given back to the system first, so a
    /// workload that does not repeat itself peaks no higher than without the
    /// cache (its freed blocks are reused by malloc as before).
    fn take(&self, size: usize) -> Option<*mut u8> {
        let mut c = self.cache.lock().ok()?;
        let mut best: Option<usize> = None;
        for (i, &(_, s)) in c.blocks.iter().enumerate() {
            if s >= size && s / 2 <= size && best.map_or(true, |b| s < c.blocks[b].1) {
                best = Some(i);
            }
        }
        let Some(i) = best else {
            for b in c.blocks.iter_mut().filter(|b| b.1 != 0) {
                // SAFETY: a cached block was allocated by System and is owned
                // by the cache alone; System's free ignores the layout size.
                unsafe { System.dealloc(b.0 as *mut u8, Layout::from_size_align_unchecked(b.1, 1)) };
                *b = (0, 0);
            }
            c.total = 0;
            return None;
        };
        let (p, s) = c.blocks[i];
        c.blocks[i] = (0, 0);
        c.total -= s;
        Some(p as *mut u8)
    }
}

// SAFETY: every block handed out is either fresh from `System` or a block
// that `System` allocated with size >= the request and alignment <= 16 and
// that was freed to the cache (no longer in use by anyone); the cache
// remembers at most the size it was last requested with, which never
// exceeds the block's real size. Blocks leave the cache under the lock, so
// one block is never handed out twice. `System` (malloc/free/realloc) does
// not use the layout's size to free or resize a block, so a block obtained
// for a smaller layout can be freed or resized with that layout.
unsafe impl GlobalAlloc for BlockCache {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if Self::cacheable(&layout) {
            if let Some(p) = self.take(layout.size()) {
                return p;
            }
        }
        // SAFETY: forwarded with the caller's layout.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if Self::cacheable(&layout) {
            if let Some(p) = self.take(layout.size()) {
                // SAFETY: the block holds at least layout.size() bytes.
                unsafe { std::ptr::write_bytes(p, 0, layout.size()) };
                return p;
            }
        }
        // SAFETY: forwarded with the caller's layout.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if Self::cacheable(&layout) {
            if let Ok(mut c) = self.cache.lock() {
                if c.total + layout.size() <= MAX_CACHED {
                    if let Some(i) = c.blocks.iter().position(|&(_, s)| s == 0) {
                        c.blocks[i] = (ptr as usize, layout.size());
                        c.total += layout.size();
                        return;
                    }
                }
            }
        }
        // SAFETY: ptr was allocated by System (directly or via the cache).
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: ptr was allocated by System (directly or via the cache),
        // whose realloc does not depend on the old layout's size.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

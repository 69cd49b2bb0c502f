//! The extension module's global allocator: the system allocator, with an
//! opt-in huge-page advice on large blocks and an opt-in cache of large
//! freed blocks.
//!
//! Every scheme and every construction allocates its output columns and
//! temporaries fresh. glibc serves blocks above its mmap threshold with a
//! new `mmap` and returns them with `munmap` on free, so every call pays a
//! page fault per 4 KiB page it touches: half the time of a Loop step on an
//! 82k-triangle sphere, measured.
//!
//! * **Huge pages** (off by default): with `TOPOMESH_HUGE_PAGES=1` in the
//!   environment, blocks of [`HUGE_MIN`] to [`HUGE_MAX`] bytes are advised
//!   `MADV_HUGEPAGE`, so the kernel (where transparent huge pages are in
//!   `madvise` or `always` mode) maps their 2 MiB-aligned interior with 2
//!   MiB pages: one fault instead of 512, and nothing kept resident after a
//!   call. It is off because on the VMs measured (issue 19,
//!   `benches/README.md`, "The advice off by default") the advice made the
//!   first large call in a process 2–5× slower (midpoint, Loop and
//!   Catmull-Clark level 3 on the 82k-triangle sphere: 0.8–3.6 s against
//!   0.6–1.0 s), the kernel stalling to find 2 MiB pages, while warm level-1
//!   and level-2 calls showed no gain beyond the noise; a repeated large
//!   call gains up to 1.5×. Advising every block above 64 MiB too had
//!   been worse still (first calls up to 6.4 s). `TOPOMESH_HUGE_PAGES_MAX`
//!   (bytes, or a size such as `1G`) moves the upper bound.
//! * **Block cache** (off by default): keeps up to a set number of bytes of
//!   large freed blocks for the next request of a similar size, which also
//!   saves the zeroing of fresh pages when operations repeat (iterations,
//!   pipelines, warm benchmarks). Turned on by `topomesh.set_block_cache(bytes)`
//!   or the environment variable `TOPOMESH_BLOCK_CACHE` (bytes, or a size such
//!   as `256M`) read when the module loads; at most [`MAX_CACHED`] bytes.
//!   Bounds: blocks of at least [`MIN_BLOCK`] bytes, at most [`SLOTS`] of
//!   them; a cached block is reused only for a request of at least half its
//!   size, and a large request that no cached block fits empties the cache
//!   (see [`BlockCache::take`]). Setting the limit to 0 frees what it holds.
//!
//! * **Zeroed blocks** of at least 1 MiB ([`zero_block`], on by default,
//!   `TOPOMESH_ZERO_DROP=0` turns it off): the pages glibc had given back
//!   are dropped rather than written, resident ones written.
//! * **The heap's free pages** are given back once before the last level
//!   of a large multi-level call ([`release_free_heap`]).
//!
//! Only topomesh's own (Rust) allocations go through here; Python's and
//! NumPy's are untouched.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Multi-level calls release the heap's free pages before their last level
/// when the level before it has at least this many half-edges
/// ([`release_free_heap`]); below it the release costs more than it frees.
pub(crate) const TRIM_MIN_HALFEDGES: usize = 1 << 17;

/// Returns the free pages glibc keeps inside its heaps to the system
/// (`malloc_trim`). glibc serves blocks up to its dynamic mmap threshold
/// (up to 32 MiB) from its heaps and keeps them resident once freed, so
/// the temporaries of a level stay in the process's memory while the next,
/// larger level allocates fresh pages beside them: on the 82k-triangle
/// sphere, Loop and midpoint level 3 peaked at 2.01× their exported arrays
/// (first call), 1.95× with this release before the last level, which costs
/// 0.2–3.6 ms (`benches/README.md`, "The heap's free pages released before
/// the last level"). Elsewhere (not glibc) it does nothing.
pub(crate) fn release_free_heap() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only returns free memory of the allocator's own
    // heaps; no live block is touched.
    unsafe {
        libc::malloc_trim(0);
    }
}

const MIN_BLOCK: usize = 1 << 20;
const SLOTS: usize = 32;
/// Largest block cache limit accepted.
pub(crate) const MAX_CACHED: usize = 1 << 30;
/// Blocks with a larger alignment bypass the cache (the system allocator
/// serves them differently).
const MAX_ALIGN: usize = 16;
/// Smallest block advised to use huge pages: below it the 2 MiB-aligned
/// interior is at most half the block.
const HUGE_MIN: usize = 4 << 20;
const HUGE_PAGE: usize = 2 << 20;

struct Cache {
    /// (address, size) of cached blocks; size 0 marks a free slot.
    blocks: [(usize, usize); SLOTS],
    total: usize,
}

pub(crate) struct BlockCache {
    cache: Mutex<Cache>,
    /// Bytes the cache may hold (0: off).
    limit: AtomicUsize,
}

#[global_allocator]
static GLOBAL: BlockCache =
    BlockCache { cache: Mutex::new(Cache { blocks: [(0, 0); SLOTS], total: 0 }), limit: AtomicUsize::new(0) };

/// Whether large blocks get the huge-page advice (`TOPOMESH_HUGE_PAGES=1`
/// turns it on; module docs).
static HUGE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Largest block advised when the advice is on (module docs).
const HUGE_MAX: usize = 64 << 20;

/// Largest block advised now (`TOPOMESH_HUGE_PAGES_MAX`, bytes).
static HUGE_MAX_NOW: AtomicUsize = AtomicUsize::new(HUGE_MAX);

pub(crate) fn set_huge_pages_max(bytes: usize) {
    HUGE_MAX_NOW.store(bytes, Ordering::Relaxed);
}

pub(crate) fn set_huge_pages(on: bool) {
    HUGE.store(on, Ordering::Relaxed);
}

/// Whether the advice is on, and the largest block it covers.
pub(crate) fn huge_pages() -> (bool, usize) {
    (HUGE.load(Ordering::Relaxed), HUGE_MAX_NOW.load(Ordering::Relaxed))
}

/// Sets the block cache limit in bytes (0 turns it off and frees what it
/// holds); returns the previous limit.
pub(crate) fn set_block_cache(bytes: usize) -> usize {
    let old = GLOBAL.limit.swap(bytes.min(MAX_CACHED), Ordering::Relaxed);
    GLOBAL.trim(bytes);
    old
}

/// The block cache limit in bytes and the bytes it holds now.
pub(crate) fn block_cache() -> (usize, usize) {
    let held = GLOBAL.cache.lock().map(|c| c.total).unwrap_or(0);
    (GLOBAL.limit.load(Ordering::Relaxed), held)
}

/// Advises the kernel to back the 2 MiB-aligned interior of a fresh block
/// with huge pages. Advice only: a refusal changes nothing.
fn advise_huge(p: *mut u8, size: usize) {
    if p.is_null() || size < HUGE_MIN || size > HUGE_MAX_NOW.load(Ordering::Relaxed) || !HUGE.load(Ordering::Relaxed) {
        return;
    }
    let start = (p as usize).next_multiple_of(HUGE_PAGE);
    let end = (p as usize + size) & !(HUGE_PAGE - 1);
    if end > start {
        // SAFETY: the range lies inside a block this allocator just got
        // from the system; madvise(MADV_HUGEPAGE) changes no contents.
        unsafe { libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE) };
    }
}

/// Zeroed blocks of at least this size are cleared by [`zero_block`].
const ZERO_BLOCK_MIN: usize = 1 << 20;
/// Whether [`zero_block`] may drop pages (`TOPOMESH_ZERO_DROP=0` at import
/// turns it off: glibc's `calloc` then clears every zeroed block).
static ZERO_DROP: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(true);

pub(crate) fn set_zero_drop(on: bool) {
    ZERO_DROP.store(on, Ordering::Relaxed);
}

/// Clears `size` bytes at `p` for `alloc_zeroed`. glibc's `calloc` writes
/// zeros over a block it reuses from its heaps, page by page on one thread,
/// faulting in the pages it had given back to the system (its heaps' tops
/// are trimmed on free). Here each 16 MiB span of whole pages is probed
/// (`mincore`): mostly absent, it is dropped (`MADV_DONTNEED`: private
/// anonymous memory then reads as zero pages, faulted in by whoever writes
/// them first, the fill's threads in parallel); mostly resident, it is
/// written, which is cheaper than faulting resident pages again. The
/// partial pages at both ends are written. `menger_sponge(4)` on two
/// threads, warm calls: 25–37 ms → 15–18 ms (`benches/README.md`).
///
/// # Safety
/// `p..p + size` lies inside one live block this allocator got from
/// `System`, private anonymous memory (glibc's heaps and maps).
unsafe fn zero_block(p: *mut u8, size: usize) {
    const PAGE: usize = 4096;
    const SPAN: usize = 4096 * PAGE;
    let (a, b) = (p as usize, p as usize + size);
    let (start, end) = (a.next_multiple_of(PAGE), b & !(PAGE - 1));
    if end <= start {
        // SAFETY: the caller's block
        unsafe { std::ptr::write_bytes(p, 0, size) };
        return;
    }
    // SAFETY: the partial pages at both ends, inside the block
    unsafe {
        std::ptr::write_bytes(p, 0, start - a);
        std::ptr::write_bytes(end as *mut u8, 0, b - end);
    }
    // one byte per page of a span, on the stack: no allocation in here
    let mut probe = [0u8; SPAN / PAGE];
    let mut s = start;
    while s < end {
        let len = SPAN.min(end - s);
        let pages = len / PAGE;
        // SAFETY: page-aligned whole pages inside the block; `probe` has a
        // byte for each of them. Neither call changes live data of anyone
        // else: the pages are the caller's and about to be zero anyway.
        let dropped = unsafe {
            let resident = if libc::mincore(s as *mut libc::c_void, len, probe.as_mut_ptr()) == 0 {
                probe[..pages].iter().filter(|&&x| x & 1 != 0).count()
            } else {
                pages
            };
            2 * resident < pages && libc::madvise(s as *mut libc::c_void, len, libc::MADV_DONTNEED) == 0
        };
        if !dropped {
            // SAFETY: as above
            unsafe { std::ptr::write_bytes(s as *mut u8, 0, len) };
        }
        s += len;
    }
}

/// Test hook: zeroed blocks of these sizes, each allocated right after a
/// block of the same size had only its first MiB written with ones (so
/// glibc may hand back the same memory, mostly absent: the dropping path)
/// and freed, and again after a block written whole (resident: the writing
/// path): whether every byte read zero.
pub(crate) fn zeroed_blocks_are_zero(sizes: &[usize]) -> bool {
    sizes.iter().all(|&n| {
        let fresh = vec![0u8; n];
        let mut ok = fresh.iter().all(|&x| x == 0);
        drop(fresh);
        // the partly written one first, while the memory past its first
        // MiB has never been touched
        for written in [n.min(ZERO_BLOCK_MIN), n] {
            let mut dirty = vec![0u8; n];
            dirty[..written].fill(1);
            std::hint::black_box(&dirty);
            drop(dirty);
            let z = vec![0u8; n];
            ok &= z.iter().all(|&x| x == 0);
        }
        ok
    })
}

impl BlockCache {
    #[inline]
    fn cacheable(&self, layout: &Layout) -> bool {
        layout.size() >= MIN_BLOCK && layout.align() <= MAX_ALIGN && self.limit.load(Ordering::Relaxed) != 0
    }

    /// Frees cached blocks until at most `limit` bytes are held.
    fn trim(&self, limit: usize) {
        if let Ok(mut c) = self.cache.lock() {
            for i in 0..SLOTS {
                if c.total <= limit {
                    break;
                }
                let (p, s) = c.blocks[i];
                if s != 0 {
                    // SAFETY: a cached block was allocated by System and is
                    // owned by the cache alone; System's free ignores the size.
                    unsafe { System.dealloc(p as *mut u8, Layout::from_size_align_unchecked(s, 1)) };
                    c.blocks[i] = (0, 0);
                    c.total -= s;
                }
            }
        }
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
        if self.cacheable(&layout) {
            if let Some(p) = self.take(layout.size()) {
                return p;
            }
        }
        // SAFETY: forwarded with the caller's layout.
        let p = unsafe { System.alloc(layout) };
        advise_huge(p, layout.size());
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if self.cacheable(&layout) {
            if let Some(p) = self.take(layout.size()) {
                // SAFETY: the block holds at least layout.size() bytes.
                unsafe { std::ptr::write_bytes(p, 0, layout.size()) };
                return p;
            }
        }
        if layout.size() >= ZERO_BLOCK_MIN && layout.align() <= MAX_ALIGN && cfg!(target_os = "linux") && ZERO_DROP.load(Ordering::Relaxed) {
            // SAFETY: forwarded with the caller's layout; cleared below.
            let p = unsafe { System.alloc(layout) };
            if !p.is_null() {
                // SAFETY: p holds layout.size() bytes of a block from System.
                unsafe { zero_block(p, layout.size()) };
                advise_huge(p, layout.size());
            }
            return p;
        }
        // SAFETY: forwarded with the caller's layout.
        let p = unsafe { System.alloc_zeroed(layout) };
        advise_huge(p, layout.size());
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if self.cacheable(&layout) {
            if let Ok(mut c) = self.cache.lock() {
                if c.total + layout.size() <= self.limit.load(Ordering::Relaxed) {
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
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if new_size > layout.size() {
            advise_huge(p, new_size);
        }
        p
    }
}

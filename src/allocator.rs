//! The binary's global allocator: mimalloc, called the way its C interface is fastest.
//!
//! Every Rust allocation states its alignment, and the `mimalloc` crate passes every one to
//! `mi_malloc_aligned`, whose checks of the alignment cost about as much again as the allocation
//! itself (a sheet allocates some 20 000 small nodes and strings). A block of `mi_malloc` is always
//! aligned to a machine word, like every block of mimalloc (their sizes are multiples of a word,
//! and so are their pages' starts), so a request aligned to at most a word (an `Expr` node, a
//! `Vec` of them, a `String`: nearly all) takes plain `mi_malloc`, `mi_zalloc` and `mi_realloc`;
//! a larger alignment keeps the aligned entry points. Freeing is `mi_free` for both.
//!
//! One of the crate's two places of `unsafe` code (the other is `parallel::pool`, which lends
//! borrowed work to kept threads and sets their cores): the `GlobalAlloc` contract, passed
//! straight to mimalloc, and [`exit`], which ends the process without mimalloc's clean-up.

use libmimalloc_sys as mi;
use std::alloc::{GlobalAlloc, Layout};
use std::ffi::c_void;

/// The alignment of every block `mi_malloc` returns: a machine word.
const WORD: usize = std::mem::size_of::<usize>();

/// mimalloc as a [`GlobalAlloc`] (see the module's doc).
pub struct Mimalloc;

// SAFETY: each method passes the request to the mimalloc function with the same contract (a block
// of at least `size` bytes aligned as asked, or null; `mi_free` and `mi_realloc*` take any block of
// mimalloc), choosing the unaligned one only when its word alignment meets `layout.align()`.
unsafe impl GlobalAlloc for Mimalloc {
    #[inline]
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if layout.align() <= WORD {
            mi::mi_malloc(layout.size()) as *mut u8
        } else {
            mi::mi_malloc_aligned(layout.size(), layout.align()) as *mut u8
        }
    }

    #[inline]
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if layout.align() <= WORD {
            mi::mi_zalloc(layout.size()) as *mut u8
        } else {
            mi::mi_zalloc_aligned(layout.size(), layout.align()) as *mut u8
        }
    }

    #[inline]
    unsafe fn dealloc(&self, ptr: *mut u8, _layout: Layout) {
        mi::mi_free(ptr as *mut c_void);
    }

    #[inline]
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if layout.align() <= WORD {
            mi::mi_realloc(ptr as *mut c_void, new_size) as *mut u8
        } else {
            mi::mi_realloc_aligned(ptr as *mut c_void, new_size, layout.align()) as *mut u8
        }
    }
}

/// Ends the process with `code` at once, without the clean-up of `exit(3)`: mimalloc, linked
/// statically, frees every page it holds when the process ends (`mi_process_done`), which the
/// kernel does anyway as the process goes (interleaved, 30 runs: the Franka Panda's JSON 24.1 →
/// 22.0 ms, the SCARA arm's `check` 4.9 → 4.0 ms). For the binary's last step only, once
/// everything is written and flushed.
pub fn exit(code: u8) -> ! {
    // Whatever Rust's line-buffered stdout still holds (a prompt without its line end).
    let _ = std::io::Write::flush(&mut std::io::stdout());
    // SAFETY: `_exit` ends the process; it takes any status and has no other precondition.
    unsafe { libc::_exit(i32::from(code)) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every size up to 2 KiB and some large ones, at every alignment from 1 to 4 KiB: the block is
    /// aligned as asked, holds its bytes (written, grown by `realloc` with the prefix kept, read
    /// back), and zeroed when asked.
    #[test]
    fn blocks_are_aligned_hold_their_bytes_and_grow() {
        let a = Mimalloc;
        let sizes = (1..=2048).chain([4095, 4096, 65_536, 1 << 20]);
        for size in sizes {
            for align in [1, 2, 4, 8, 16, 32, 64, 4096] {
                let layout = Layout::from_size_align(size, align).unwrap();
                // SAFETY: a non-zero size; each block is used within its size and freed once.
                unsafe {
                    let p = a.alloc(layout);
                    assert!(!p.is_null());
                    assert_eq!(p as usize % align, 0, "size {size}, align {align}");
                    p.write_bytes(0xA5, size);
                    let q = a.realloc(p, layout, size * 2);
                    assert_eq!(q as usize % align, 0, "realloc: size {size}, align {align}");
                    assert!((0..size).all(|i| *q.add(i) == 0xA5));
                    a.dealloc(q, Layout::from_size_align(size * 2, align).unwrap());
                    let z = a.alloc_zeroed(layout);
                    assert_eq!(z as usize % align, 0, "zeroed: size {size}, align {align}");
                    assert!((0..size).all(|i| *z.add(i) == 0));
                    a.dealloc(z, layout);
                }
            }
        }
    }
}

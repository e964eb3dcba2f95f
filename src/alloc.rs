//! The process's global allocator: mimalloc for small blocks, the system allocator for large ones.
//!
//! Terms, substitutions and answers are many small short-lived blocks, which mimalloc serves
//! with far fewer instructions than glibc's malloc. Large blocks (an engine heap grown by a
//! runaway query, a big `findall` bag) stay with the system allocator: its `realloc` of a large
//! block remaps pages instead of copying them, so growing a heap of N bytes to 2N peaks at 2N
//! resident, where mimalloc's copying `realloc` peaks at 3N (the old block is still resident
//! while the new one fills). Which allocator owns a block follows from its size alone, so `dealloc`
//! and `realloc` always reach the allocator that made the block.
//!
//! Small blocks are asked of mimalloc with its plain `mi_malloc` when their alignment is at most
//! a word's (nearly every block): every mimalloc block is word-aligned, and the aligned entry
//! point the `mimalloc` crate calls for every block takes a slow path whenever its size class's
//! free list is empty, one that for a size that is not a power of two allocates a larger block
//! from another size class (so the first class's free list is never refilled, and that size
//! takes the slow path from then on).

use libmimalloc_sys as mi;
use std::alloc::{GlobalAlloc, Layout, System};
use std::ffi::c_void;

/// Blocks of this many bytes or more come from the system allocator.
pub const LARGE: usize = 256 * 1024;

/// mimalloc below [`LARGE`] bytes, the system allocator from there on.
pub struct Hybrid;

fn large(size: usize) -> bool {
    size >= LARGE
}

/// True when any mimalloc block meets `align`: every block is aligned to a word.
fn word_aligned(align: usize) -> bool {
    align <= std::mem::size_of::<usize>()
}

unsafe impl GlobalAlloc for Hybrid {
    #[inline]
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if large(layout.size()) {
            System.alloc(layout)
        } else if word_aligned(layout.align()) {
            mi::mi_malloc(layout.size()) as *mut u8
        } else {
            mimalloc::MiMalloc.alloc(layout)
        }
    }

    #[inline]
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if large(layout.size()) {
            System.alloc_zeroed(layout)
        } else if word_aligned(layout.align()) {
            mi::mi_zalloc(layout.size()) as *mut u8
        } else {
            mimalloc::MiMalloc.alloc_zeroed(layout)
        }
    }

    #[inline]
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if large(layout.size()) {
            System.dealloc(ptr, layout)
        } else {
            mimalloc::MiMalloc.dealloc(ptr, layout)
        }
    }

    #[inline]
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        match (large(layout.size()), large(new_size)) {
            (false, false) if word_aligned(layout.align()) => {
                mi::mi_realloc(ptr as *mut c_void, new_size) as *mut u8
            }
            (false, false) => mimalloc::MiMalloc.realloc(ptr, layout, new_size),
            (true, true) => System.realloc(ptr, layout, new_size),
            // Crossing the line: the block changes owner, so move it by hand.
            _ => {
                let new_layout = Layout::from_size_align_unchecked(new_size, layout.align());
                let new = self.alloc(new_layout);
                if !new.is_null() {
                    std::ptr::copy_nonoverlapping(ptr, new, layout.size().min(new_size));
                    self.dealloc(ptr, layout);
                }
                new
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::alloc::{GlobalAlloc, Layout};

    #[test]
    fn small_blocks_meet_every_alignment_and_keep_their_contents() {
        // Word-aligned blocks come from `mi_malloc`, larger alignments from the aligned entry
        // point: each block must meet its alignment, also after a `realloc`.
        let a = super::Hybrid;
        for align in [1, 2, 4, 8, 16, 32, 64, 4096] {
            for size in [1, 7, 8, 24, 40, 48, 100, 1000, 5000] {
                let layout = Layout::from_size_align(size, align).expect("layout");
                unsafe {
                    let p = a.alloc(layout);
                    assert!(!p.is_null() && p as usize % align == 0, "{size} {align}");
                    std::ptr::write_bytes(p, 0xa5, size);
                    let q = a.realloc(p, layout, size * 3);
                    assert!(!q.is_null() && q as usize % align == 0, "{size} {align}");
                    assert!((0..size).all(|i| *q.add(i) == 0xa5));
                    a.dealloc(q, Layout::from_size_align(size * 3, align).expect("layout"));
                    let z = a.alloc_zeroed(layout);
                    assert!(z as usize % align == 0 && (0..size).all(|i| *z.add(i) == 0));
                    a.dealloc(z, layout);
                }
            }
        }
    }

    #[test]
    fn blocks_move_between_the_allocators_intact() {
        // Grow one vector from small to large and back: each crossing moves the contents.
        let mut v: Vec<u64> = Vec::new();
        for i in 0..(super::LARGE as u64 / 4) {
            v.push(i);
        }
        assert!(v.capacity() * 8 >= super::LARGE);
        v.truncate(10);
        v.shrink_to_fit();
        assert_eq!(v, (0..10).collect::<Vec<u64>>());
        let big = vec![7u8; super::LARGE * 2];
        assert!(big.iter().all(|&b| b == 7));
    }
}

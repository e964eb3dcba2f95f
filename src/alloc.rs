//! The process's global allocator: mimalloc for small blocks, the system allocator for large ones.
//!
//! Terms, substitutions and answers are many small short-lived blocks, which mimalloc serves
//! with far fewer instructions than glibc's malloc. Large blocks (an engine heap grown by a
//! runaway query, a big `findall` bag) stay with the system allocator: its `realloc` of a large
//! block remaps pages instead of copying them, so growing a heap of N bytes to 2N peaks at 2N
//! resident, where mimalloc's copying `realloc` peaks at 3N (the old block is still resident
//! while the new one fills). Which allocator owns a block follows from its size alone, so `dealloc`
//! and `realloc` always reach the allocator that made the block.

use std::alloc::{GlobalAlloc, Layout, System};

/// Blocks of this many bytes or more come from the system allocator.
pub const LARGE: usize = 256 * 1024;

/// mimalloc below [`LARGE`] bytes, the system allocator from there on.
pub struct Hybrid;

fn large(size: usize) -> bool {
    size >= LARGE
}

/// True when mimalloc's plain entry points give `layout` its alignment: every mimalloc block
/// is word-aligned (its size classes are whole words), so an alignment of a word or less
/// needs no aligned entry point. The aligned ones (which `mimalloc::MiMalloc` always calls)
/// cost more: when a size class's free list is empty and the class is not a power of two
/// (24, 40, 48 bytes, ...), `mi_malloc_aligned` over-allocates from the next class instead of
/// refilling the list, so such a class stays on that slow path for good (about 160
/// instructions a block instead of about 20).
fn word_aligned(layout: Layout) -> bool {
    layout.align() <= std::mem::size_of::<usize>()
}

unsafe impl GlobalAlloc for Hybrid {
    #[inline]
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if large(layout.size()) {
            System.alloc(layout)
        } else if word_aligned(layout) {
            libmimalloc_sys::mi_malloc(layout.size()) as *mut u8
        } else {
            mimalloc::MiMalloc.alloc(layout)
        }
    }

    #[inline]
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if large(layout.size()) {
            System.alloc_zeroed(layout)
        } else if word_aligned(layout) {
            libmimalloc_sys::mi_zalloc(layout.size()) as *mut u8
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
            (false, false) if word_aligned(layout) => {
                libmimalloc_sys::mi_realloc(ptr.cast(), new_size) as *mut u8
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
    use super::Hybrid;
    use std::alloc::{GlobalAlloc, Layout};

    #[test]
    fn every_block_has_its_alignment_and_keeps_its_bytes() {
        // The plain entry points serve alignments up to a word, the aligned ones the rest:
        // each block must be aligned, zeroed when asked, and keep its bytes when it grows.
        for align in [1, 2, 4, 8, 16, 32, 64, 4096] {
            for size in (1..=200).chain([1000, 5000]) {
                let layout = Layout::from_size_align(size, align).expect("layout");
                unsafe {
                    let p = Hybrid.alloc(layout);
                    assert!(!p.is_null() && p as usize % align == 0, "{size}/{align}");
                    std::ptr::write_bytes(p, 0xab, size);
                    let q = Hybrid.realloc(p, layout, size * 3);
                    assert!(
                        !q.is_null() && q as usize % align == 0,
                        "{size}/{align} grown"
                    );
                    assert!((0..size).all(|i| *q.add(i) == 0xab), "{size}/{align} kept");
                    Hybrid.dealloc(q, Layout::from_size_align(size * 3, align).expect("l"));
                    let z = Hybrid.alloc_zeroed(layout);
                    assert!(
                        !z.is_null() && z as usize % align == 0,
                        "{size}/{align} zeroed"
                    );
                    assert!((0..size).all(|i| *z.add(i) == 0), "{size}/{align} zeroes");
                    Hybrid.dealloc(z, layout);
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

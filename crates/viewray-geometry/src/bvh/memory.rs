//! Two hints that change no result: the processor is asked to start loading the nodes
//! and leaves a ray will visit, and Linux to back a mesh's large buffers with huge pages.
//! Both need `unsafe` (an intrinsic and a system call); each block says why it is sound.

/// Asks the CPU to start loading the bytes at `offsets` from the start of
/// `items[index]` into the cache, so that the loads of the children a ray will visit
/// overlap. The offsets are constants, so this is straight-line code: a loop here cost
/// coherent rays, whose data is already cached, a tenth of their time.
#[inline(always)]
pub(crate) fn prefetch<T, const N: usize>(items: &[T], index: usize, offsets: [usize; N]) {
    #[cfg(target_arch = "x86_64")]
    if let Some(item) = items.get(index) {
        let start = std::ptr::from_ref(item).cast::<i8>();
        for offset in offsets {
            #[allow(unsafe_code)]
            // SAFETY: `_mm_prefetch` is only a hint: it reads nothing the program can
            // observe and never faults, whatever the address. It is an SSE instruction,
            // and SSE is part of the x86_64 baseline.
            unsafe {
                use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
                _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset));
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (items, index, offsets);
}

/// Asks the kernel to back `buffer`'s unused capacity with 2 MiB pages (Linux's
/// transparent huge pages, where the system leaves them to `madvise`), before the
/// buffer is filled: a mesh's build items, nodes and triangle packets are tens of
/// megabytes each. One fault then maps 2 MiB instead of 4 KiB (a seventh of a build had
/// gone to the kernel's page faults), and a ray's random walk through the hierarchy
/// misses the TLB far less often. Only a hint: nothing changes where the system
/// declines, or on other systems.
pub(crate) fn advise_huge_pages<T>(buffer: &mut Vec<T>) {
    #[cfg(target_os = "linux")]
    {
        const HUGE_PAGE: usize = 2 << 20;
        let spare = buffer.spare_capacity_mut();
        let start = spare.as_mut_ptr() as usize;
        let end = start + std::mem::size_of_val(spare);
        // The whole huge pages inside the unused capacity.
        let (first, last) = (
            start.next_multiple_of(HUGE_PAGE),
            end / HUGE_PAGE * HUGE_PAGE,
        );
        if last > first {
            #[allow(unsafe_code)]
            // SAFETY: the range lies inside `buffer`'s allocation, which this function
            // borrows mutably; `MADV_HUGEPAGE` only changes how the kernel backs those
            // pages, never their contents or whether they may be read and written. An
            // error (for example no huge page support) leaves everything as it was.
            unsafe {
                libc::madvise(
                    first as *mut libc::c_void,
                    last - first,
                    libc::MADV_HUGEPAGE,
                );
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = buffer;
}

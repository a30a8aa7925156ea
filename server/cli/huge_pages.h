// Asks glibc's allocator for transparent huge pages, which glibc reads only from the environment
// when a process starts (the tunable glibc.malloc.hugetlb=1): glint re-executes itself once with
// it added.
//
// Why: most kernels hand out huge pages only where a program asks (THP "madvise"), and glibc does
// not ask by default. Loading a mesh of a million triangles then touches some 300 MB in 4 KiB
// pages: on the virtual machines measured, one page fault each (187,000 faults, a second of
// system time) and a TLB miss on most accesses of the BVH build, so that OBJ parse and build
// took 2.7 s instead of 0.65 s (bench/BENCHMARKS.md, time to first pixel). Renders of smaller
// scenes gain a few per cent.
//
// A GLIBC_TUNABLES the user set, even empty, is left alone: `GLIBC_TUNABLES= glint ...` runs
// without the re-execution (for valgrind, whose tools follow no exec by default).
#pragma once

namespace glint {

// Re-executes this program with GLIBC_TUNABLES=glibc.malloc.hugetlb=1 if GLIBC_TUNABLES is unset;
// returns (and glint runs on as it is) if it is set or the executable cannot be run again.
void request_huge_pages(char** argv);

}  // namespace glint

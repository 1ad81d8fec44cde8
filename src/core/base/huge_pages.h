#pragma once
// Transparent huge pages for large, freshly allocated buffers (kernel matrices): the kernel then
// faults 2 MB at a time instead of 4 kB, which is most of a cold process's fit time at N ≥ 500
// (docs/performance.md, Fit speed as users meet it). This machine's kernels enable them only for
// ranges advised with MADV_HUGEPAGE ("madvise" mode).

#include <cstddef>

namespace hermite {

// Advises the whole 2 MB pages inside [data, data + bytes) before they are first written.
// Buffers under 4 MB are left alone; failures are ignored (only speed is at stake).
void adviseHugePages(void* data, std::size_t bytes);

}  // namespace hermite

#pragma once
// Large dense matrices (the n × n kernel block: 128 MB at n = 4000) are first touched during
// assembly. With 4 KiB pages that is ~32 000 page faults plus TLB misses in the factorisation;
// asking for transparent huge pages before the first touch removes most of both.

#include <cstddef>

namespace hermite {

// Advises the kernel to back [data, data + bytes) with transparent huge pages (Linux
// madvise(MADV_HUGEPAGE) on the 2 MiB-aligned interior). A no-op where unsupported.
void adviseHugePages(void* data, std::size_t bytes);

}  // namespace hermite

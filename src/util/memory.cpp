#include "util/memory.h"

#include <cstdlib>
#include <fstream>

#include <unistd.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace streak {

std::uint64_t residentBytes() {
    std::ifstream statm("/proc/self/statm");
    std::uint64_t totalPages = 0, residentPages = 0;
    if (!(statm >> totalPages >> residentPages)) return 0;
    const long pageSize = sysconf(_SC_PAGESIZE);
    return pageSize > 0 ? residentPages * std::uint64_t(pageSize) : 0;
}

void* allocateLarge(std::size_t bytes) {
    if (bytes < kHugePageWorthyBytes) return ::operator new(bytes);
    if (bytes > std::size_t(-1) - (kLargeBlockBytes - 1)) throw std::bad_alloc();
    // aligned_alloc wants a multiple of the alignment; the slack is under one huge page.
    const std::size_t rounded = (bytes + kLargeBlockBytes - 1) / kLargeBlockBytes * kLargeBlockBytes;
    void* block = std::aligned_alloc(kLargeBlockBytes, rounded);
    if (!block) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Advice only: where the system has no transparent huge pages it is refused, and the block
    // is faulted in 4 KiB pages as before.
    madvise(block, rounded, MADV_HUGEPAGE);
#endif
    return block;
}

void freeLarge(void* block, std::size_t bytes) noexcept {
    if (bytes < kHugePageWorthyBytes) ::operator delete(block);
    else std::free(block);
}

}  // namespace streak

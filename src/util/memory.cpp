#include "util/memory.h"

#include <fstream>

#include <unistd.h>

namespace streak {

std::uint64_t residentBytes() {
    std::ifstream statm("/proc/self/statm");
    std::uint64_t totalPages = 0, residentPages = 0;
    if (!(statm >> totalPages >> residentPages)) return 0;
    const long pageSize = sysconf(_SC_PAGESIZE);
    return pageSize > 0 ? residentPages * std::uint64_t(pageSize) : 0;
}

}  // namespace streak

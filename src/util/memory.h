#pragma once

#include <cstdint>

namespace streak {

// The bytes of this process resident in memory now (Linux: /proc/self/statm), or 0 where the
// system does not say. What a memory budget is measured against: the pages the scene, its
// geometry and everything else touched so far actually hold, not what streak thinks it allocated.
std::uint64_t residentBytes();

}  // namespace streak

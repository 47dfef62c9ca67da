#include "util/memory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>

namespace streak {
namespace {

// The system's transparent huge page mode ("always", "madvise" or "never"), or "" where it
// does not say.
std::string hugePageMode() {
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(in, line);
    const auto open = line.find('['), close = line.find(']');
    return open != std::string::npos && close > open ? line.substr(open + 1, close - open - 1) : "";
}

// Kilobytes of this process's memory mapping that holds `address` backed by huge pages
// (/proc/self/smaps), or -1 where the mapping is not listed.
long hugeKilobytesAt(const void* address) {
    std::ifstream smaps("/proc/self/smaps");
    const auto at = reinterpret_cast<std::uintptr_t>(address);
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        std::uintptr_t lo = 0, hi = 0;
        char dash = 0;
        std::istringstream header(line);
        if (header >> std::hex >> lo >> dash >> hi && dash == '-') {
            inside = lo <= at && at < hi;
            continue;
        }
        if (inside && line.rfind("AnonHugePages:", 0) == 0) return std::stol(line.substr(14));
    }
    return -1;
}

TEST(LargeVector, HoldsWhatIsWrittenInBlocksSmallAndLarge) {
    for (const std::size_t count : {std::size_t(10), kLargeBlockBytes / sizeof(std::uint32_t) * 3 + 7}) {
        LargeVector<std::uint32_t> values(count);
        std::iota(values.begin(), values.end(), 1u);
        values.push_back(0u);  // a reallocation keeps what was there
        ASSERT_EQ(values.size(), count + 1);
        for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(values[i], std::uint32_t(i + 1));
        if (count * sizeof(std::uint32_t) >= kLargeBlockBytes)
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(values.data()) % kLargeBlockBytes, 0u) << "a large block is aligned to a huge page";
    }
}

// The point of LargeVector: a large block faults in huge pages where the system lends them on
// advice, so a dense scene's arrays do not pay a fault every 4 KiB.
TEST(LargeVector, ALargeBlockIsBackedByHugePagesWhereTheSystemLendsThem) {
    const std::string mode = hugePageMode();
    if (mode != "madvise" && mode != "always") GTEST_SKIP() << "no transparent huge pages here (mode '" << mode << "')";
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer's allocator maps the blocks, not the system's";
#endif
    LargeVector<float> values(4 * kLargeBlockBytes / sizeof(float), 1.0f);
    const long huge = hugeKilobytesAt(values.data());
    ASSERT_GE(huge, 0) << "the block's mapping is not in /proc/self/smaps";
    // The kernel may find no free huge page at the moment (fragmented memory); it then falls
    // back to small pages, which is not what this checks. One of four is the least it takes.
    EXPECT_GE(huge, long(kLargeBlockBytes / 1024)) << "none of the block's 8 MiB is in huge pages";
}

}  // namespace
}  // namespace streak

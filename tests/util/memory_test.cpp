#include "util/memory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
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

// The line of /proc/self/status that starts with `key` (e.g. "THP_enabled:"), or "".
std::string statusLine(const std::string& key) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind(key, 0) == 0) return line;
    return "";
}

// What /proc/self/smaps says of the memory mapping that holds `address`: the kilobytes of it
// backed by huge pages and its VmFlags ("hg": advised MADV_HUGEPAGE); found = false where the
// mapping is not listed.
struct MappingOf {
    bool found = false;
    long hugeKilobytes = 0;
    std::string flags;
};
MappingOf mappingOf(const void* address) {
    std::ifstream smaps("/proc/self/smaps");
    const auto at = reinterpret_cast<std::uintptr_t>(address);
    std::string line;
    bool inside = false;
    MappingOf out;
    while (std::getline(smaps, line)) {
        std::uintptr_t lo = 0, hi = 0;
        char dash = 0;
        std::istringstream header(line);
        if (header >> std::hex >> lo >> dash >> hi && dash == '-') {
            if (out.found) break;  // past the mapping
            inside = lo <= at && at < hi;
            out.found = out.found || inside;
            continue;
        }
        if (!inside) continue;
        if (line.rfind("AnonHugePages:", 0) == 0) out.hugeKilobytes = std::stol(line.substr(14));
        if (line.rfind("VmFlags:", 0) == 0) out.flags = line.substr(8);
    }
    return out;
}

TEST(LargeVector, HoldsWhatIsWrittenInBlocksSmallAndLarge) {
    for (const std::size_t count : {std::size_t(10), kHugePageWorthyBytes / sizeof(std::uint32_t) - 1, kHugePageWorthyBytes / sizeof(std::uint32_t) + 1,
                                    kLargeBlockBytes / sizeof(std::uint32_t) * 3 + 7}) {
        LargeVector<std::uint32_t> values(count);
        std::iota(values.begin(), values.end(), 1u);
        values.push_back(0u);  // a reallocation keeps what was there
        ASSERT_EQ(values.size(), count + 1);
        for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(values[i], std::uint32_t(i + 1));
        if (values.capacity() * sizeof(std::uint32_t) >= kHugePageWorthyBytes) {
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(values.data()) % kLargeBlockBytes, 0u) << "a large block is aligned to a huge page";
        }
    }
}

// LargeBuffer: resize() makes nothing (its allocator's default construction leaves the bytes as
// they are), and constructAt makes an element as LargeVector's resize would, value-initialized
// whatever the bytes under it held; copies copy.
TEST(LargeBuffer, ResizeMakesNothingAndConstructAtValueInitializes) {
    struct Item {
        int a = 7;
        float b = 2.5f;
        std::uint32_t c = 0;
    };
    using Traits = std::allocator_traits<LargeBufferAllocator<Item>>;
    LargeBufferAllocator<Item> allocator;
    Item* raw = Traits::allocate(allocator, 4);
    std::memset(static_cast<void*>(raw), 0xAB, 4 * sizeof(Item));
    Traits::construct(allocator, raw);
    const unsigned char* bytes = reinterpret_cast<const unsigned char*>(raw);
    for (std::size_t i = 0; i < sizeof(Item); ++i) ASSERT_EQ(bytes[i], 0xAB) << "default construction wrote byte " << i;
    Traits::deallocate(allocator, raw, 4);

    LargeBuffer<Item> items;
    items.resize(kLargeBlockBytes / sizeof(Item) * 2 + 3);  // a large block, in huge pages where lent
    std::memset(static_cast<void*>(items.data()), 0xAB, items.size() * sizeof(Item));  // a reused block's bytes
    for (std::size_t i = 0; i < items.size(); ++i) {
        Item& item = constructAt(items, i);
        ASSERT_EQ(&item, &items[i]);
        ASSERT_EQ(item.a, 7);
        ASSERT_EQ(item.b, 2.5f);
        ASSERT_EQ(item.c, 0u);
        item.c = std::uint32_t(i);
    }
    const LargeBuffer<Item> copy = items;
    ASSERT_EQ(copy.size(), items.size());
    for (std::size_t i = 0; i < copy.size(); ++i) ASSERT_EQ(copy[i].c, std::uint32_t(i));
}

// The point of LargeVector: a large block is advised into huge pages, and faults in them where
// the system lends them, so a dense scene's arrays do not pay a fault every 4 KiB.
TEST(LargeVector, ALargeBlockIsAdvisedIntoHugePages) {
    const std::string mode = hugePageMode();
    if (mode != "madvise" && mode != "always") GTEST_SKIP() << "no transparent huge pages here (mode '" << mode << "')";
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer's allocator maps the blocks, not the system's";
#endif
    // A process may have them turned off for itself (prctl PR_SET_THP_DISABLE, inherited: some
    // containers and service managers do), and the advice is then refused.
    if (statusLine("THP_enabled:").find('0') != std::string::npos) GTEST_SKIP() << "huge pages are turned off for this process";
    LargeVector<float> values(4 * kLargeBlockBytes / sizeof(float), 1.0f);
    const MappingOf mapping = mappingOf(values.data());
    ASSERT_TRUE(mapping.found) << "the block's mapping is not in /proc/self/smaps";
    EXPECT_NE(mapping.flags.find(" hg"), std::string::npos) << "the block was not advised MADV_HUGEPAGE: VmFlags" << mapping.flags;
    // Whether the kernel had a free huge page at that moment is the machine's (fragmented memory
    // falls back to small pages); where it had, the block holds at least one.
    if (mapping.hugeKilobytes == 0) GTEST_SKIP() << "advised, but the kernel lent no huge page just now";
    EXPECT_GE(mapping.hugeKilobytes, long(kLargeBlockBytes / 1024));
}

}  // namespace
}  // namespace streak

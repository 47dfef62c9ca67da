#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace streak {

// The bytes of this process resident in memory now (Linux: /proc/self/statm), or 0 where the
// system does not say. What a memory budget is measured against: the pages the scene, its
// geometry and everything else touched so far actually hold, not what streak thinks it allocated.
std::uint64_t residentBytes();

// Memory for a frame's large arrays (a dense scene's segments, bounds and poses: hundreds of MB
// written once per frame). Each fresh page is a fault, and on a virtual machine a 4 KiB fault
// costs microseconds: 128 MB of segments took 350 ms to fault in against 35 ms to fill. A
// block of at least kLargeBlockBytes is aligned to it and asked for as huge pages where the
// system has them (Linux transparent huge pages in "madvise" mode, the default of many
// distributions): one fault per 2 MiB. Smaller blocks are plain operator new.
inline constexpr std::size_t kLargeBlockBytes = std::size_t(2) << 20;
void* allocateLarge(std::size_t bytes);
void freeLarge(void* block, std::size_t bytes) noexcept;

template <class T>
struct LargeAllocator {
    using value_type = T;
    LargeAllocator() = default;
    template <class U>
    LargeAllocator(const LargeAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocateLarge(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept { freeLarge(p, n * sizeof(T)); }
    template <class U>
    bool operator==(const LargeAllocator<U>&) const noexcept { return true; }
};

// A vector of a frame's large per-triangle or per-vertex data.
template <class T>
using LargeVector = std::vector<T, LargeAllocator<T>>;

}  // namespace streak

#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace streak {

// The bytes of this process resident in memory now (Linux: /proc/self/statm), or 0 where the
// system does not say. What a memory budget is measured against: the pages the scene, its
// geometry and everything else touched so far actually hold, not what streak thinks it allocated.
std::uint64_t residentBytes();

// Memory for a frame's large arrays (a dense scene's segments, bounds and poses: hundreds of MB
// written once per frame). Each fresh page is a fault, and on a virtual machine a 4 KiB fault
// costs microseconds: 128 MB of segments took 350 ms to fault in against 35 ms to fill. A
// block of at least kHugePageWorthyBytes is rounded up to whole huge pages (kLargeBlockBytes),
// aligned to them and asked for as huge pages where the system has them (Linux transparent huge
// pages in "madvise" mode, the default of many distributions): one fault per 2 MiB. Smaller
// blocks are plain operator new.
inline constexpr std::size_t kLargeBlockBytes = std::size_t(2) << 20;
// At about 10 us a 4 KiB fault on such a machine, an eighth of a huge page in small pages (64
// faults) costs more than zeroing a whole huge page, and a frame's temporaries of a few hundred
// KB (the closed-surface search's lists, ClosedSurfaces) were mostly their faults.
inline constexpr std::size_t kHugePageWorthyBytes = kLargeBlockBytes / 8;
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

// LargeAllocator whose default construction does nothing: resize() leaves the new elements
// unconstructed, and their owner constructs each in place (constructAt) where it
// fills them, in parallel. A fresh page is zeroed by the kernel when it is first touched, and
// resize() touched every page of a dense frame's segments on one thread (a 128 MB block: most of
// the spheres' setup); filled in parallel, each thread faults in the pages it writes.
template <class T>
struct LargeBufferAllocator : LargeAllocator<T> {
    LargeBufferAllocator() = default;
    template <class U>
    LargeBufferAllocator(const LargeBufferAllocator<U>&) noexcept {}
    template <class U>
    void construct(U*) noexcept {}
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

// A LargeVector whose elements are constructed by their owner: after resize(n), element i is
// usable once constructAt(buffer, i) has made it (value-initialized, as LargeVector's resize
// makes it), typically in the parallel loop that fills it.
template <class T>
using LargeBuffer = std::vector<T, LargeBufferAllocator<T>>;

template <class T>
T& constructAt(LargeBuffer<T>& buffer, std::size_t i) {
    static_assert(std::is_trivially_destructible_v<T>, "a LargeBuffer's elements are never destroyed one by one");
    return *::new (static_cast<void*>(buffer.data() + i)) T();
}

}  // namespace streak

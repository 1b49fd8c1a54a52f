#pragma once
#include <cstddef>

namespace dp {

/// Memory for a large table that is read at random. Blocks of 2 MiB or more are 2 MiB-aligned
/// and, on Linux, marked for transparent huge pages, so that a lookup does not also miss the
/// TLB (4 KiB pages let the TLB cover only a few MiB). Smaller blocks come from operator new.
/// Throws std::bad_alloc on failure.
void* huge_page_allocate(size_t bytes, size_t alignment);
/// Frees a block of huge_page_allocate with the same size and alignment.
void huge_page_free(void* p, size_t bytes, size_t alignment) noexcept;

/// Standard allocator over huge_page_allocate, for std::vector.
template <class T>
struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) {}
    T* allocate(size_t n) { return static_cast<T*>(huge_page_allocate(n * sizeof(T), alignof(T))); }
    void deallocate(T* p, size_t n) noexcept { huge_page_free(p, n * sizeof(T), alignof(T)); }
    template <class U>
    bool operator==(const HugePageAllocator<U>&) const { return true; }
};

}  // namespace dp

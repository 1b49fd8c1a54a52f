#include "probe/huge_pages.h"

#include <cstdlib>
#include <limits>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dp {

namespace {
constexpr size_t kHugePage = size_t(2) << 20;
}  // namespace

void* huge_page_allocate(size_t bytes, size_t alignment) {
    if (bytes < kHugePage || alignment > kHugePage)
        return ::operator new(bytes, std::align_val_t(alignment));
    if (bytes > std::numeric_limits<size_t>::max() - kHugePage) throw std::bad_alloc();
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Only a hint: where the kernel declines, the block still works with small pages.
    madvise(p, rounded, MADV_HUGEPAGE);
#endif
    return p;
}

void huge_page_free(void* p, size_t bytes, size_t alignment) noexcept {
    if (bytes < kHugePage || alignment > kHugePage)
        ::operator delete(p, std::align_val_t(alignment));
    else
        std::free(p);
}

}  // namespace dp

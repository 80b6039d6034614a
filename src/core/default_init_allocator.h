#pragma once
// An allocator whose resize leaves trivially constructible elements uninitialized: for the big arrays
// the BVH builders fill in parallel right after sizing them, where zeroing first would cost a
// single-threaded pass over memory (and its page faults). Large ones go to huge pages.
#include <memory>
#include <vector>

#include "core/huge_pages.h"

namespace wideray {

template <class T>
class DefaultInitAllocator : public std::allocator<T> {
public:
    template <class U>
    struct rebind {
        using other = DefaultInitAllocator<U>;
    };
    using std::allocator<T>::allocator;

    T* allocate(size_t n) {
        if (n * sizeof(T) < kHugePageMinBytes) return std::allocator<T>::allocate(n);
        return static_cast<T*>(allocateHugePages(n * sizeof(T)));
    }
    void deallocate(T* p, size_t n) noexcept {
        if (n * sizeof(T) < kHugePageMinBytes) std::allocator<T>::deallocate(p, n);
        else freeHugePages(p);
    }

    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        std::allocator_traits<std::allocator<T>>::construct(static_cast<std::allocator<T>&>(*this), p,
                                                            std::forward<Args>(args)...);
    }
};

/// A vector whose resize default-initializes (leaves trivial elements as they are).
template <class T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;

} // namespace wideray

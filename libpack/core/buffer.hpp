// Internal: a vector whose elements are left unset when no value is given, for the large working arrays
// that are written in full next, on all threads. A value-initialising vector zeroes them first on one
// thread: at 4096^2 each such array costs a serial memset plus the page faults of its first touch, which
// the parallel writer would otherwise take on every core.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace heightpack::detail {

template <class T>
struct UnsetAllocator : std::allocator<T> {
    static_assert(std::is_trivially_default_constructible_v<T>, "only values that need no constructor are left unset");
    using value_type = T;
    template <class U>
    struct rebind {
        using other = UnsetAllocator<U>;
    };
    UnsetAllocator() = default;
    template <class U>
    UnsetAllocator(const UnsetAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;  // default-initialised: left as the allocator gave it
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

// Buffer<T>(n) holds n unset values; Buffer<T>(n, value) and every other way of filling it work as for
// std::vector.
template <class T>
using Buffer = std::vector<T, UnsetAllocator<T>>;

}  // namespace heightpack::detail

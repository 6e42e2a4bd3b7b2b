// Counting replacements of the allocation functions, for tests that prove a path allocates
// nothing. Include it in exactly one source file of a test binary (it defines the global
// allocation functions), then compare allocationCount() before and after the path.
//
// Counted: every operator new, and (outside AddressSanitizer builds, whose runtime owns
// malloc) every malloc, which is how Eigen allocates dynamic-size matrices.
#pragma once

#include <atomic>

#include "nocdyn/detail/sanitizer.hpp"
#include <cstdlib>
#include <new>

namespace nocdyn::test {
inline std::atomic<long> allocation_count{0};
/// Number of allocations so far in this process (see above for what counts).
inline long allocationCount() { return allocation_count.load(); }
/// Whether malloc itself is counted in this build.
#if NOCDYN_ASAN()
inline constexpr bool kCountsMalloc = false;
#else
inline constexpr bool kCountsMalloc = true;
#endif
}  // namespace nocdyn::test

#if !NOCDYN_ASAN()
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) {
    ++nocdyn::test::allocation_count;
    return __libc_malloc(size);
}
#endif

// Not inlined: GCC would otherwise see free() on the result of operator new and warn
// (-Wmismatched-new-delete), although this pair is consistent by construction.
[[gnu::noinline]] void* operator new(std::size_t size) {
    ++nocdyn::test::allocation_count;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
[[gnu::noinline]] void* operator new[](std::size_t size) { return operator new(size); }
[[gnu::noinline]] void operator delete(void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
// The nothrow forms (std::stable_sort's temporary buffer uses them): from malloc as well, so that
// the operator delete above frees what they return (AddressSanitizer checks the pair).
[[gnu::noinline]] void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    ++nocdyn::test::allocation_count;
    return std::malloc(size ? size : 1);
}
[[gnu::noinline]] void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
    return operator new(size, tag);
}
[[gnu::noinline]] void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
[[gnu::noinline]] void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

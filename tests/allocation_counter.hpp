// A counting replacement of the global operator new, for tests that prove a path allocates
// nothing. Include it in exactly one source file of a test binary (it defines the global
// allocation functions), then compare allocationCount() before and after the path.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace nocdyn::test {
inline std::atomic<long> allocation_count{0};
/// Number of calls to operator new (any form) so far in this process.
inline long allocationCount() { return allocation_count.load(); }
}  // namespace nocdyn::test

void* operator new(std::size_t size) {
    ++nocdyn::test::allocation_count;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

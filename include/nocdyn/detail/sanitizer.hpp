#pragma once
/// \file
/// NOCDYN_ASAN(): 1 in a build instrumented by AddressSanitizer, else 0. GCC says so with
/// __SANITIZE_ADDRESS__, clang (before 18) only through __has_feature(address_sanitizer); the
/// library's and the tests' guards read this one macro, whichever compiler built them. It is
/// function-like so that `#if NOCDYN_ASAN()` without this header is an error, not a silent 0.

#if defined(__SANITIZE_ADDRESS__)
#define NOCDYN_ASAN_ON 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define NOCDYN_ASAN_ON 1
#endif
#endif
#ifdef NOCDYN_ASAN_ON
#define NOCDYN_ASAN() 1
#else
#define NOCDYN_ASAN() 0
#endif

// Compiler hints that change code generation but never results.
#pragma once

#include <cstddef>
#include <cstdint>

/// Keeps a function out of its callers: for a rare path (a fallback) whose
/// size would otherwise stop the compiler from inlining the common path
/// around it.
#if defined(_MSC_VER)
#define FCSOLVE_NOINLINE __declspec(noinline)
#elif defined(__GNUC__) || defined(__clang__)
#define FCSOLVE_NOINLINE __attribute__((noinline))
#else
#define FCSOLVE_NOINLINE
#endif

/// Puts a small function into every caller even where the compiler's
/// inlining budget for a large translation unit is spent (GCC's
/// inline-unit-growth): for a hot function whose out-of-line call costs
/// more than its body, e.g. a struct returned through the stack.
#if defined(_MSC_VER)
#define FCSOLVE_ALWAYS_INLINE __forceinline
#elif defined(__GNUC__) || defined(__clang__)
#define FCSOLVE_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define FCSOLVE_ALWAYS_INLINE inline
#endif

/// Asks for the cache line holding an address ahead of its use (a read);
/// a hint only: never faults, changes no result.
#if defined(__GNUC__) || defined(__clang__)
#define FCSOLVE_PREFETCH(address) __builtin_prefetch((address), 0, 3)
#else
#define FCSOLVE_PREFETCH(address) ((void)(address))
#endif

namespace fcsolve {

inline constexpr std::uintptr_t kCacheLine = 64;  // x86-64 and most AArch64 cores

/// The cache lines an object of `bytes` can touch wherever it starts: the
/// count to ask prefetch_lines for to cover it.
constexpr int cache_lines_spanned(std::size_t bytes) { return int((bytes + kCacheLine - 1) / kCacheLine) + 1; }

/// Asks for the Lines cache lines from the one holding `begin`, for
/// reading soon. A fixed count, unrolled: a loop to a data-dependent end
/// costs a mispredicted branch where it stops (the 10^4 sphere pile's
/// sweep, in the cache, went from 0.7 to 0.9-1.2 ms with one; fixed, it
/// did not move: docs/results.md). Past an array's end it only fetches
/// unused lines: a prefetch never faults.
template <int Lines>
FCSOLVE_ALWAYS_INLINE void prefetch_lines(const void* begin) {
  const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(begin) & ~(kCacheLine - 1);
  for (int i = 0; i < Lines; ++i) FCSOLVE_PREFETCH(reinterpret_cast<const void*>(first + i * kCacheLine));
}

}  // namespace fcsolve

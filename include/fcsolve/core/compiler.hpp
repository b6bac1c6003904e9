// Compiler hints that change code generation but never results.
#pragma once

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

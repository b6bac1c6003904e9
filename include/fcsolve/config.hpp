// fcsolve: configuration, version and the argument-checking macros.
#pragma once

#define FCSOLVE_VERSION_MAJOR 0
#define FCSOLVE_VERSION_MINOR 1
#define FCSOLVE_VERSION_PATCH 0
#define FCSOLVE_VERSION_STRING "0.1.0"

#include <cassert>

// Inner-loop invariants: compiled out in release builds, like eigen_assert.
#ifndef FCSOLVE_ASSERT
#define FCSOLVE_ASSERT(cond) assert(cond)
#endif

// Eigen's malloc guard: a test build defines EIGEN_RUNTIME_NO_MALLOC and the
// solvers bracket their hot loops with these, so an allocation there aborts.
#ifdef EIGEN_RUNTIME_NO_MALLOC
#define FCSOLVE_NO_MALLOC_BEGIN() Eigen::internal::set_is_malloc_allowed(false)
#define FCSOLVE_NO_MALLOC_END() Eigen::internal::set_is_malloc_allowed(true)
#else
#define FCSOLVE_NO_MALLOC_BEGIN() ((void)0)
#define FCSOLVE_NO_MALLOC_END() ((void)0)
#endif

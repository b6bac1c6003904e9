// Included first by the programs built with EIGEN_RUNTIME_NO_MALLOC: an
// eigen_assert that throws, so an Eigen heap allocation between
// FCSOLVE_NO_MALLOC_BEGIN/END fails the test in release builds too (Eigen's
// own assert is compiled out there).
#pragma once

#include <stdexcept>

#define eigen_assert(x) \
  do {                  \
    if (!(x)) throw std::logic_error("eigen_assert failed: " #x); \
  } while (false)

// The linear-algebra policy fcsolve uses when none is named: SuiteSparse when
// the program links fcsolve::cholmod (FCSOLVE_WITH_CHOLMOD), else Eigen's own.
#pragma once

#include <fcsolve/linalg/eigen_backend.hpp>

#ifdef FCSOLVE_WITH_CHOLMOD
#include <fcsolve/linalg/suitesparse_backend.hpp>
namespace fcsolve {
using DefaultBackend = SuiteSparseBackend;
}
#else
namespace fcsolve {
using DefaultBackend = EigenBackend;
}
#endif

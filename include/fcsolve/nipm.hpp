// fcsolve: interior-point methods for frictional contact.
//   ipm::SocqpIpm    the convex SOCQP with the friction term frozen (s given)
//   ipm::AclmSolver  the ACLM fixed-point / Newton loops on s = ||u_T(s)||
//   ipm::NonsmoothIpm  the nonsmooth IPM on the full FC/I, with recovery
//   ipm::check_existence  Slater's assumption (the SOC program of Acary &
//                         Cadoux 2013); ipm::diagnose  rank, cond(W), ratio
// Each solver works on the global form (M, H: GlobalSocqpIpm, GlobalAclm,
// GlobalNipm) or the reduced form (W: LocalSocqpIpm, LocalAclm, LocalNipm),
// templated on the cone (Coulomb3D or Coulomb2D; a contact with mu = 0 keeps
// only its normal complementarity, ipm/form_common.hpp), and follows the
// solver contract (docs/architecture.md):
//   fcsolve::ipm::GlobalNipm<fcsolve::Coulomb3D> nipm;
//   nipm.compute(problem);
//   Vector r = Vector::Zero(problem.size()), v(problem.num_dofs());  // r: warm start
//   const fcsolve::SolverInfo& info = nipm.solve(r, v); Linear algebra: ipm::SparseKktFactorization
// <Backend> (CHOLMOD / UMFPACK when linked, Eigen otherwise) or
// ipm::DenseKktFactorization for small scenes.
#pragma once

#include <fcsolve/ipm/aclm.hpp>
#include <fcsolve/ipm/diagnostics.hpp>
#include <fcsolve/ipm/existence_check.hpp>
#include <fcsolve/ipm/nonsmooth_ipm.hpp>
#include <fcsolve/ipm/socqp_ipm.hpp>

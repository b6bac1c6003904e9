// The names a class templated on a cone policy declares for one contact: the
// cone, the contact dimension, its vector and its d x d matrix; a one-contact
// policy (local solver, formulation) adds the name it is listed under.
//
// A macro, as Eigen's EIGEN_DENSE_PUBLIC_INTERFACE: a class template does not
// see the names of a dependent base class, so a base that declared them would
// still need every one re-declared in each local solver and formulation.
#pragma once

#include <fcsolve/core/types.hpp>

#define FCSOLVE_CONE_TYPES(ConeType)                 \
  using Cone = ConeType;                             \
  static constexpr int dim = ConeType::dim;          \
  using Vec = typename ConeType::Vec;                \
  using Mat = SmallMatrix<ConeType::dim, typename ConeType::Scalar>

#define FCSOLVE_ONE_CONTACT_POLICY(ConeType, policy_name) \
  FCSOLVE_CONE_TYPES(ConeType);                           \
  static constexpr const char* name = policy_name

// Frictionless contact: one normal component per contact, K = K* = R_+.
// FC/II then is the LCP  0 <= u = W r + q  _|_  r >= 0; mu is ignored.
#pragma once

#include <fcsolve/core/types.hpp>

#include <algorithm>

namespace fcsolve {

template <class Scalar_>
struct FrictionlessTpl {
  using Scalar = Scalar_;
  static constexpr int dim = 1;
  using Vec = SmallVector<1, Scalar>;

  static Scalar tangential_norm(const Vec&) { return Scalar(0); }
  static Vec project(const Vec& z, Scalar /*mu*/) { return Vec(std::max(z[0], Scalar(0))); }
  static Vec project_dual(const Vec& z, Scalar mu) { return project(z, mu); }
  static Vec de_saxce_shift(const Vec&, Scalar) { return Vec::Zero(); }
  static Vec modified_velocity(const Vec& u, Scalar) { return u; }
  static bool contains(const Vec& r, Scalar, Scalar tol = 0) { return r[0] >= -tol; }
  static bool contains_dual(const Vec& u, Scalar, Scalar tol = 0) { return u[0] >= -tol; }
};

using Frictionless = FrictionlessTpl<double>;

}  // namespace fcsolve

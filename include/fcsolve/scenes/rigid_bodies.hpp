// A set of rigid bodies for Moreau-Jean time stepping (Acary & Brogliato
// 2008, "Numerical Methods for Nonsmooth Dynamical Systems", ch. 10; Jean
// 1999, "The non-smooth contact dynamics method", CMAME 177): the generalised
// velocity, the diagonal mass matrix, and H's columns for a contact.
//
// Body i has the generalised velocity (v_i, omega_i) in R^6 and the mass
// matrix diag(m_i I3, J_i), J_i the principal inertia. The scenes' bodies
// keep their orientation (spheres: isotropic, orientation never enters the
// geometry; boxes: axis-aligned, small-rotation approximation), so J_i is
// diagonal in world axes, M is diagonal and the gyroscopic term vanishes.
//
// Contact a between body A and body B (or a fixed obstacle) has the normal n
// pointing from B into A, tangents t1, t2, frame R = [n t1 t2] and point p;
// its local velocity is
//   u_a = R^T ((v_A + omega_A x (p - x_A)) - (v_B + omega_B x (p - x_B)))
// so H's 6 x 3 block for A is [R ; [p - x_A]_x R] and minus that for B
// (Acary & Brogliato 2008, sec. 10.1.2). Positions move by
//   x+ = x + h (theta v+ + (1 - theta) v).
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/scenes/geometry.hpp>

#include <Eigen/Geometry>  // cross()
#include <Eigen/SparseCore>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fcsolve::scenes {

using Triplet = Eigen::Triplet<double, int>;

/// One contact between body a and body b (b < 0: fixed obstacle -1 - b).
struct RigidContact {
  int a = 0;
  int b = 0;
  Mat3 frame;   ///< [n t1 t2], n from b into a
  Vec3 point;
  double gap = 0;
  std::uint64_t key = 0;  ///< identity across steps (warm start)
};

/// A contact's identity: the body pair (an obstacle as `bodies + k`) and
/// the corner of a face contact. Bodies up to 2^29.
inline std::uint64_t contact_key(int a, std::uint64_t b_code, unsigned corner = 0) {
  return (std::uint64_t(a) << 35) | (b_code << 3) | corner;
}

class RigidBodies {
 public:
  /// Adds a body at x with mass m, principal inertia J (world axes) and
  /// velocity v; returns its index.
  int add(const Vec3& x, double m, const Vec3& J, const Vec3& v = Vec3::Zero()) {
    x_.push_back(x);
    mass_.push_back(m);
    const Vec3 Jinv = J.cwiseInverse();
    minv_.insert(minv_.end(), {1.0 / m, 1.0 / m, 1.0 / m, Jinv.x(), Jinv.y(), Jinv.z()});
    V_.insert(V_.end(), {v.x(), v.y(), v.z(), 0.0, 0.0, 0.0});
    return int(x_.size() - 1);
  }

  int count() const { return int(x_.size()); }
  Index dofs() const { return Index(V_.size()); }
  const Vec3& position(int i) const { return x_[std::size_t(i)]; }
  double mass(int i) const { return mass_[std::size_t(i)]; }
  VectorMap inverse_mass() const { return VectorMap(minv_.data(), dofs()); }  ///< diagonal of M^-1
  VectorMap velocity() const { return VectorMap(V_.data(), dofs()); }

  /// R^T (relative velocity at the contact point) for the generalised
  /// velocity V: the contact's rows of H^T V.
  Vec3 local_velocity(const RigidContact& c, const Vector& V) const {
    Vec3 rel = V.segment<3>(6 * c.a) + V.segment<3>(6 * c.a + 3).cross(c.point - x_[c.a]);
    if (c.b >= 0) rel -= V.segment<3>(6 * c.b) + V.segment<3>(6 * c.b + 3).cross(c.point - x_[c.b]);
    return c.frame.transpose() * rel;
  }

  /// Appends contact number `col`'s 6 x 3 blocks of H (file comment).
  void add_columns(const RigidContact& c, int col, std::vector<Triplet>& t) const {
    const auto block = [&](int body, double sign) {
      const Mat3 top = sign * c.frame;
      const Mat3 bottom = sign * cross_matrix(c.point - x_[body]) * c.frame;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
          t.emplace_back(6 * body + i, 3 * col + j, top(i, j));
          t.emplace_back(6 * body + 3 + i, 3 * col + j, bottom(i, j));
        }
    };
    block(c.a, 1.0);
    if (c.b >= 0) block(c.b, -1.0);
  }

  /// x+ = x + h (theta v+ + (1 - theta) v), then v = v+.
  void advance(const Vector& V_next, double h, double theta) {
    for (std::size_t i = 0; i < x_.size(); ++i)
      x_[i] += h * (theta * V_next.segment<3>(6 * Index(i)) + (1 - theta) * velocity().segment<3>(6 * Index(i)));
    Eigen::Map<Vector>(V_.data(), dofs()) = V_next;
  }

  /// Gravity's impulse over a step, h f_ext (gravity along -z).
  Vector gravity_impulse(double h, double g) const {
    Vector f = Vector::Zero(dofs());
    for (std::size_t i = 0; i < x_.size(); ++i) f[6 * Index(i) + 2] = -h * mass_[i] * g;
    return f;
  }

  double max_speed() const {
    double s = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) s = std::max(s, velocity().segment<3>(6 * Index(i)).norm());
    return s;
  }

 private:
  std::vector<Vec3> x_;
  std::vector<double> mass_;
  std::vector<double> V_;     ///< (v_i, omega_i) per body (std::vector: bodies are added one by one)
  std::vector<double> minv_;  ///< the diagonal of M^-1
};

}  // namespace fcsolve::scenes

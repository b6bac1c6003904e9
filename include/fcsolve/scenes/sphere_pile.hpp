// A pile of spheres falling into an open box (floor z = 0, walls x = 0,
// x = L, y = 0, y = L): the layout and the contact detection. Spheres start
// on a jittered lattice, side ~ 1.5 n^(1/3) per layer, with small random
// velocities; radii 0.8..1.2 R0. Every sphere touches several others once
// the pile settles, so d nc exceeds the 6 dofs per sphere and W = H^T M^-1 H
// is rank-deficient.
#pragma once

#include <fcsolve/scenes/rigid_bodies.hpp>
#include <fcsolve/scenes/shape_contacts.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fcsolve::scenes {

struct SpherePileLayout {
  long spheres = 200;
  long seed = 1;
  double radius = 0.05;    ///< R0 (m)
  double density = 1000;   ///< kg/m^3
  double mass_ratio = 1;   ///< every 7th sphere is this much denser
};

/// Where the open-box piles start (this file, mixed_shapes.hpp): layers of
/// side x side cells of 2.6 R0 (wider than a body, 2.4 R0 at most), side ~
/// 1.5 n^(1/3); body i's centre jittered by 0.1 R0 across and up to 0.4 R0
/// up, with a small random velocity, falling.
struct PileLattice {
  PileLattice(long bodies, double size)
      : R0(size), side(std::max<long>(2, long(std::ceil(1.5 * std::cbrt(double(bodies)))))), cell(2.6 * size) {}
  double box() const { return double(side) * cell; }
  Vec3 position(long i, Uniform& uni) const {
    const long layer = i / (side * side), col = (i / side) % side, row = i % side;
    const double dz = uni(0.0, 0.4);  // last coordinate first (geometry.hpp, Uniform)
    const double dy = uni(-0.1, 0.1);
    const double dx = uni(-0.1, 0.1);
    return Vec3((double(row) + 0.5) * cell + dx * R0, (double(col) + 0.5) * cell + dy * R0,
                1.2 * R0 + double(layer) * cell + dz * R0);
  }
  static Vec3 velocity(Uniform& uni) {
    const double vz = uni(-0.5, 0.0);  // last coordinate first (geometry.hpp, Uniform)
    const double vy = uni(-0.2, 0.2);
    const double vx = uni(-0.2, 0.2);
    return Vec3(vx, vy, vz);
  }

  double R0;
  long side;
  double cell;
};

/// A solid sphere of density rho and radius R: its mass, and its inertia
/// 2/5 m R^2 about any axis.
inline double sphere_mass(double rho, double R) {
  constexpr double kPi = 3.14159265358979323846;
  return rho * 4.0 / 3.0 * kPi * R * R * R;
}
inline Vec3 sphere_inertia(double m, double R) { return Vec3::Constant(0.4 * m * R * R); }

class SpherePile {
 public:
  explicit SpherePile(const SpherePileLayout& p) : R0_(p.radius) {
    const long n = p.spheres;
    const PileLattice lattice(n, R0_);
    box_ = lattice.box();
    Uniform uni(std::uint32_t(p.seed));
    for (long i = 0; i < n; ++i) {
      const double R = R0_ * uni(0.8, 1.2);
      const double m = sphere_mass(p.density * (i % 7 == 6 ? p.mass_ratio : 1.0), R);
      const Vec3 x = lattice.position(i, uni);
      const Vec3 v = PileLattice::velocity(uni);
      radius_.push_back(R);
      bodies_.add(x, m, sphere_inertia(m, R), v);
    }
  }

  RigidBodies& bodies() { return bodies_; }
  const RigidBodies& bodies() const { return bodies_; }
  double box() const { return box_; }
  /// The length scale of the contact search (rigid_stepper.hpp).
  double size() const { return R0_; }

  /// Contacts whose gap is below `margin`, in a deterministic order (by key):
  /// sphere pairs found by a sweep along x, then walls.
  std::vector<RigidContact> candidates(double margin) const {
    const int n = bodies_.count();
    const auto x = [&](int i) -> const Vec3& { return bodies_.position(i); };
    std::vector<int> order(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](int i, int j) { return x(i).x() - radius_[i] < x(j).x() - radius_[j]; });
    std::vector<RigidContact> out;
    for (int s = 0; s < n; ++s) {
      const int i = order[s];
      const double reach = x(i).x() + radius_[i] + margin;
      for (int t = s + 1; t < n && x(order[t]).x() - radius_[order[t]] <= reach; ++t) {
        const int a = std::min(i, order[t]), b = std::max(i, order[t]);
        sphere_sphere_contact(bodies_, a, radius_[a], b, radius_[b], margin, out);
      }
    }
    const std::vector<AxisPlane> walls = open_box_planes(box_);
    for (int i = 0; i < n; ++i)
      for (const AxisPlane& wall : walls) sphere_plane_contact(bodies_, i, radius_[i], wall, margin, out);
    std::sort(out.begin(), out.end(), [](const RigidContact& l, const RigidContact& r) { return l.key < r.key; });
    return out;
  }

 private:
  double R0_;
  double box_ = 1;
  std::vector<double> radius_;
  RigidBodies bodies_;
};

}  // namespace fcsolve::scenes

// A pile of spheres falling into an open box (floor z = 0, walls x = 0,
// x = L, y = 0, y = L): the layout and the contact detection. Spheres start
// on a jittered lattice, side ~ 1.5 n^(1/3) per layer, with small random
// velocities; radii 0.8..1.2 R0. Every sphere touches several others once
// the pile settles, so d nc exceeds the 6 dofs per sphere and W = H^T M^-1 H
// is rank-deficient.
#pragma once

#include <fcsolve/scenes/rigid_bodies.hpp>

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

class SpherePile {
 public:
  static constexpr int kWalls = 5;  ///< floor, x = 0, x = L, y = 0, y = L (open on top)

  explicit SpherePile(const SpherePileLayout& p) : R0_(p.radius) {
    const long n = p.spheres;
    side_ = std::max<long>(2, long(std::ceil(1.5 * std::cbrt(double(n)))));
    const double cell = 2.6 * R0_;  // > the largest diameter, 2.4 R0
    box_ = double(side_) * cell;
    Uniform uni(std::uint32_t(p.seed));
    constexpr double kPi = 3.14159265358979323846;
    for (long i = 0; i < n; ++i) {
      const long layer = i / (side_ * side_), col = (i / side_) % side_, row = i % side_;
      const double R = R0_ * uni(0.8, 1.2);
      const double rho = p.density * (i % 7 == 6 ? p.mass_ratio : 1.0);
      const double m = rho * 4.0 / 3.0 * kPi * R * R * R;
      const Vec3 x((double(row) + 0.5) * cell + uni(-0.1, 0.1) * R0_,
                   (double(col) + 0.5) * cell + uni(-0.1, 0.1) * R0_,
                   1.2 * R0_ + double(layer) * cell + uni(0.0, 0.4) * R0_);
      const Vec3 v(uni(-0.2, 0.2), uni(-0.2, 0.2), uni(-0.5, 0.0));
      radius_.push_back(R);
      bodies_.add(x, m, Vec3::Constant(0.4 * m * R * R), v);
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
        const Vec3 d = x(a) - x(b);
        const double dist = d.norm();
        const double gap = dist - radius_[a] - radius_[b];
        if (gap >= margin || dist == 0.0) continue;
        RigidContact c;
        c.a = a;
        c.b = b;
        c.frame = frame_from_normal(d / dist);  // from b into a
        c.point = x(b) + c.frame.col(0) * (radius_[b] + 0.5 * gap);
        c.gap = gap;
        c.key = contact_key(a, std::uint64_t(b));
        out.push_back(c);
      }
    }
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < kWalls; ++k) {
        Vec3 normal = Vec3::Zero();
        double offset = 0;  // wall: normal . x >= offset
        switch (k) {
          case 0: normal.z() = 1; break;
          case 1: normal.x() = 1; break;
          case 2: normal.x() = -1; offset = -box_; break;
          case 3: normal.y() = 1; break;
          default: normal.y() = -1; offset = -box_; break;
        }
        const double gap = normal.dot(x(i)) - offset - radius_[i];
        if (gap >= margin) continue;
        RigidContact c;
        c.a = i;
        c.b = -1 - k;
        c.frame = frame_from_normal(normal);
        c.point = x(i) - radius_[i] * normal;
        c.gap = gap;
        c.key = contact_key(i, std::uint64_t(n + k));
        out.push_back(c);
      }
    }
    std::sort(out.begin(), out.end(), [](const RigidContact& l, const RigidContact& r) { return l.key < r.key; });
    return out;
  }

 private:
  double R0_;
  long side_ = 2;
  double box_ = 1;
  std::vector<double> radius_;
  RigidBodies bodies_;
};

}  // namespace fcsolve::scenes

// Axis-aligned boxes on the ground plane z = 0: the bodies and their contact
// detection (the pair tests: shape_contacts.hpp). Two boxes touch on the face pair whose separation is the
// largest over the three axes (the separating-axis test restricted to the
// face normals of axis-aligned boxes, Ericson 2005, "Real-Time Collision
// Detection", sec. 4.2.1); the contact patch is the overlap rectangle of
// the two faces and carries one contact at each of its 4 corners (as
// engines reduce a face-face manifold, e.g. Bullet's 4-point manifold), so
// a plank crossing three others has 12 contacts on one face. The ground
// holds a box by the 4 corners of its bottom face.
//
// Boxes keep their orientation (rigid_bodies.hpp): their angular velocities
// enter H and M but are not integrated into a rotation, a small-rotation
// approximation that holds for settling stacks, walls and towers.
#pragma once

#include <fcsolve/scenes/rigid_bodies.hpp>
#include <fcsolve/scenes/shape_contacts.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fcsolve::scenes {

class BoxScene {
 public:
  /// A box of half extents `half` centred at x, of this density and velocity.
  int add_box(const Vec3& x, const Vec3& half, double density, const Vec3& v = Vec3::Zero()) {
    const double m = density * 8.0 * half.prod();
    half_.push_back(half);
    size_ = std::min(size_, half.minCoeff());
    return bodies_.add(x, m, cuboid_inertia(m, half), v);
  }

  RigidBodies& bodies() { return bodies_; }
  const RigidBodies& bodies() const { return bodies_; }
  const Vec3& half(int i) const { return half_[std::size_t(i)]; }
  /// The thinnest half extent: the length scale of the contact search.
  double size() const { return size_; }

  /// Contacts whose gap is below `margin`, in a deterministic order (by
  /// key): box pairs found by a sweep along the axis where the boxes spread
  /// most, then the ground.
  std::vector<RigidContact> candidates(double margin) const {
    const int n = bodies_.count();
    std::vector<RigidContact> out;
    if (n == 0) return out;
    const auto x = [&](int i) -> const Vec3& { return bodies_.position(i); };
    Vec3 lo = x(0), hi = x(0);
    for (int i = 1; i < n; ++i) {
      lo = lo.cwiseMin(x(i));
      hi = hi.cwiseMax(x(i));
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    std::vector<int> order(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) order[i] = i;
    const auto low = [&](int i) { return x(i)[axis] - half_[i][axis]; };
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return low(i) < low(j); });
    for (int s = 0; s < n; ++s) {
      const int i = order[s];
      const double reach = x(i)[axis] + half_[i][axis] + margin;
      for (int t = s + 1; t < n && low(order[t]) <= reach; ++t) {
        const int a = std::min(i, order[t]), b = std::max(i, order[t]);
        box_box_contacts(bodies_, a, half_[a], b, half_[b], margin, out);
      }
    }
    const AxisPlane ground{Vec3::UnitZ(), 0.0, 0};
    for (int i = 0; i < n; ++i) box_plane_contacts(bodies_, i, half_[i], ground, margin, out);
    std::sort(out.begin(), out.end(), [](const RigidContact& l, const RigidContact& r) { return l.key < r.key; });
    return out;
  }

 private:
  RigidBodies bodies_;
  std::vector<Vec3> half_;
  double size_ = 1e300;
};

}  // namespace fcsolve::scenes

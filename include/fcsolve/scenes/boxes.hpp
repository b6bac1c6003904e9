// Axis-aligned boxes on the ground plane z = 0: the bodies and their contact
// detection. Two boxes touch on the face pair whose separation is the
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

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fcsolve::scenes {

class BoxScene {
 public:
  /// A box of half extents `half` centred at x, of this density and velocity.
  int add_box(const Vec3& x, const Vec3& half, double density, const Vec3& v = Vec3::Zero()) {
    const double m = density * 8.0 * half.prod();
    // Solid cuboid: J_x = m (b^2 + c^2) / 3 with half extents a, b, c.
    const Vec3 J(m * (half.y() * half.y() + half.z() * half.z()) / 3.0,
                 m * (half.x() * half.x() + half.z() * half.z()) / 3.0,
                 m * (half.x() * half.x() + half.y() * half.y()) / 3.0);
    half_.push_back(half);
    size_ = std::min(size_, half.minCoeff());
    return bodies_.add(x, m, J, v);
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
      for (int t = s + 1; t < n && low(order[t]) <= reach; ++t)
        face_contacts(std::min(i, order[t]), std::max(i, order[t]), margin, out);
    }
    for (int i = 0; i < n; ++i) ground_contacts(i, margin, n, out);
    std::sort(out.begin(), out.end(), [](const RigidContact& l, const RigidContact& r) { return l.key < r.key; });
    return out;
  }

 private:
  /// Box a above (along the separating axis) box b: 4 corner contacts.
  void face_contacts(int a, int b, double margin, std::vector<RigidContact>& out) const {
    const Vec3 d = bodies_.position(a) - bodies_.position(b);
    const Vec3 separation = d.cwiseAbs() - half_[a] - half_[b];
    int k = 0;
    const double gap = separation.maxCoeff(&k);
    if (gap >= margin) return;
    const int i = (k + 1) % 3, j = (k + 2) % 3;  // the face's axes
    const Vec3 lo = (bodies_.position(a) - half_[a]).cwiseMax(bodies_.position(b) - half_[b]);
    const Vec3 hi = (bodies_.position(a) + half_[a]).cwiseMin(bodies_.position(b) + half_[b]);
    const double tiny = 1e-9 * (half_[a] + half_[b]).maxCoeff();
    if (hi[i] - lo[i] <= tiny || hi[j] - lo[j] <= tiny) return;  // edge or corner: no patch
    const double sign = d[k] >= 0 ? 1.0 : -1.0;
    Vec3 normal = Vec3::Zero();
    normal[k] = sign;  // from b into a
    const Mat3 frame = frame_from_normal(normal);
    const double plane = bodies_.position(b)[k] + sign * (half_[b][k] + 0.5 * gap);
    for (unsigned corner = 0; corner < 4; ++corner) {
      RigidContact c;
      c.a = a;
      c.b = b;
      c.frame = frame;
      c.point[k] = plane;
      c.point[i] = (corner & 1) ? hi[i] : lo[i];
      c.point[j] = (corner & 2) ? hi[j] : lo[j];
      c.gap = gap;
      c.key = contact_key(a, std::uint64_t(b), corner);
      out.push_back(c);
    }
  }

  /// Box i on the ground z = 0: its bottom face's 4 corners.
  void ground_contacts(int i, double margin, int n, std::vector<RigidContact>& out) const {
    const Vec3& x = bodies_.position(i);
    const Vec3& e = half_[i];
    const double gap = x.z() - e.z();
    if (gap >= margin) return;
    const Mat3 frame = frame_from_normal(Vec3::UnitZ());
    for (unsigned corner = 0; corner < 4; ++corner) {
      RigidContact c;
      c.a = i;
      c.b = -1;
      c.frame = frame;
      c.point = Vec3(x.x() + ((corner & 1) ? e.x() : -e.x()), x.y() + ((corner & 2) ? e.y() : -e.y()), 0.0);
      c.gap = gap;
      c.key = contact_key(i, std::uint64_t(n), corner);
      out.push_back(c);
    }
  }

  RigidBodies bodies_;
  std::vector<Vec3> half_;
  double size_ = 1e300;
};

}  // namespace fcsolve::scenes

// Mixed shapes: spheres and axis-aligned boxes falling together into the
// open box of the sphere pile (floor z = 0, walls x = 0, x = L, y = 0,
// y = L). Bodies start on the sphere pile's jittered lattice (PileLattice),
// each a sphere (radius 0.8..1.2 R0) or a box (half extents 0.6..1.0 R0 per
// axis, so flat, long and cubic boxes) with even odds, with small random
// velocities; every 7th body is mass_ratio times denser. A settled pile
// mixes the four kinds of contact (shape_contacts.hpp): one-point contacts
// (sphere-sphere, sphere-box, sphere-wall) beside 4-point face patches
// (box-box, box-floor, box-wall), so W holds both rank-deficient face
// patches and the sphere pile's graph.
//
// Boxes keep their orientation (rigid_bodies.hpp, the small-rotation
// approximation of the box scenes).
#pragma once

#include <fcsolve/scenes/rigid_bodies.hpp>
#include <fcsolve/scenes/shape_contacts.hpp>
#include <fcsolve/scenes/sphere_pile.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fcsolve::scenes {

struct MixedShapesLayout {
  long bodies = 200;
  long seed = 1;
  double size = 0.05;      ///< R0 (m): sphere radius, box half extent scale
  double density = 1000;   ///< kg/m^3
  double mass_ratio = 1;   ///< every 7th body is this much denser
};

class MixedShapes {
 public:
  explicit MixedShapes(const MixedShapesLayout& p) {
    const long n = p.bodies;
    const PileLattice lattice(n, p.size);
    box_ = lattice.box();
    Uniform uni(std::uint32_t(p.seed));
    for (long i = 0; i < n; ++i) {
      const double rho = p.density * (i % 7 == 6 ? p.mass_ratio : 1.0);
      const bool sphere = uni(0.0, 1.0) < 0.5;
      Vec3 half;
      double m = 0;
      Vec3 J;
      if (sphere) {
        const double R = p.size * uni(0.8, 1.2);
        half = Vec3::Constant(R);
        m = sphere_mass(rho, R);
        J = sphere_inertia(m, R);
      } else {
        const double hz = uni(0.6, 1.0);  // last coordinate first (geometry.hpp, Uniform)
        const double hy = uni(0.6, 1.0);
        const double hx = uni(0.6, 1.0);
        half = p.size * Vec3(hx, hy, hz);
        m = rho * 8.0 * half.prod();
        J = cuboid_inertia(m, half);
      }
      const Vec3 x = lattice.position(i, uni);
      const Vec3 v = PileLattice::velocity(uni);
      radius_.push_back(sphere ? half.x() : 0.0);
      half_.push_back(half);
      size_ = std::min(size_, half.minCoeff());
      bodies_.add(x, m, J, v);
    }
  }

  RigidBodies& bodies() { return bodies_; }
  const RigidBodies& bodies() const { return bodies_; }
  double box() const { return box_; }
  bool is_sphere(int i) const { return radius_[std::size_t(i)] > 0; }
  /// The smallest half extent: the length scale of the contact search.
  double size() const { return size_; }

  /// Contacts whose gap is below `margin`, in a deterministic order (by
  /// key): pairs found by a sweep along x over the bodies' bounding boxes,
  /// then the floor and walls.
  std::vector<RigidContact> candidates(double margin) const {
    const int n = bodies_.count();
    const auto low = [&](int i) { return bodies_.position(i).x() - half_[i].x(); };
    std::vector<int> order(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return low(i) < low(j); });
    std::vector<RigidContact> out;
    for (int s = 0; s < n; ++s) {
      const int i = order[s];
      const double reach = bodies_.position(i).x() + half_[i].x() + margin;
      for (int t = s + 1; t < n && low(order[t]) <= reach; ++t) {
        const int a = std::min(i, order[t]), b = std::max(i, order[t]);
        if (is_sphere(a) && is_sphere(b)) sphere_sphere_contact(bodies_, a, radius_[a], b, radius_[b], margin, out);
        else if (is_sphere(a)) sphere_box_contact(bodies_, a, radius_[a], b, half_[b], margin, out);
        else if (is_sphere(b)) sphere_box_contact(bodies_, b, radius_[b], a, half_[a], margin, out);
        else box_box_contacts(bodies_, a, half_[a], b, half_[b], margin, out);
      }
    }
    const std::vector<AxisPlane> walls = open_box_planes(box_);
    for (int i = 0; i < n; ++i)
      for (const AxisPlane& wall : walls) {
        if (is_sphere(i)) sphere_plane_contact(bodies_, i, radius_[i], wall, margin, out);
        else box_plane_contacts(bodies_, i, half_[i], wall, margin, out);
      }
    std::sort(out.begin(), out.end(), [](const RigidContact& l, const RigidContact& r) { return l.key < r.key; });
    return out;
  }

 private:
  double box_ = 1;
  double size_ = 1e300;
  std::vector<double> radius_;  ///< a sphere's radius; 0 for a box
  std::vector<Vec3> half_;      ///< a box's half extents; a sphere's bounding box
  RigidBodies bodies_;
};

}  // namespace fcsolve::scenes

// Contact detection between the scenes' shapes, one pair at a time: spheres
// and axis-aligned boxes (bodies keep their orientation, rigid_bodies.hpp),
// against each other and against fixed axis-aligned planes. Each function
// appends the pair's contacts whose gap is below `margin`; the normal points
// from body b into body a (RigidContact), and keys follow contact_key().
//
//   sphere-sphere  one contact on the line of centres;
//   box-box        the face pair of largest separation (the separating-axis
//                  test restricted to the face normals of axis-aligned boxes,
//                  Ericson 2005, "Real-Time Collision Detection", sec.
//                  4.2.1), one contact at each corner of the faces' overlap
//                  rectangle (engines' 4-point face manifold, e.g. Bullet);
//   sphere-box     one contact at the box's point closest to the centre
//                  (Ericson 2005, sec. 5.1.3; a centre inside the box is
//                  pushed out through the face it is nearest to);
//   sphere-plane   one contact; box-plane: the 4 corners of the box's face
//                  parallel to the plane.
#pragma once

#include <fcsolve/scenes/rigid_bodies.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fcsolve::scenes {

/// Fixed obstacle k: the plane normal . x >= offset, normal an axis or its
/// opposite. In a RigidContact it is body -1 - k; in keys, bodies + k.
struct AxisPlane {
  Vec3 normal;
  double offset = 0;
  int index = 0;  ///< k
};

/// The principal inertia of a solid cuboid of mass m and half extents
/// `half`: J_x = m (b^2 + c^2) / 3 with half extents a, b, c.
inline Vec3 cuboid_inertia(double m, const Vec3& half) {
  return Vec3(m * (half.y() * half.y() + half.z() * half.z()) / 3.0,
              m * (half.x() * half.x() + half.z() * half.z()) / 3.0,
              m * (half.x() * half.x() + half.y() * half.y()) / 3.0);
}

/// Spheres a < b of radii ra, rb.
inline void sphere_sphere_contact(const RigidBodies& bodies, int a, double ra, int b, double rb, double margin,
                                  std::vector<RigidContact>& out) {
  const Vec3 d = bodies.position(a) - bodies.position(b);
  const double dist = d.norm();
  const double gap = dist - ra - rb;
  if (gap >= margin || dist == 0.0) return;
  RigidContact c;
  c.a = a;
  c.b = b;
  c.frame = frame_from_normal(d / dist);  // from b into a
  c.point = bodies.position(b) + c.frame.col(0) * (rb + 0.5 * gap);
  c.gap = gap;
  c.key = contact_key(a, std::uint64_t(b));
  out.push_back(c);
}

/// Boxes a < b of half extents ha, hb: 4 corner contacts on the face pair
/// of largest separation, none when the faces' overlap is an edge or a point.
inline void box_box_contacts(const RigidBodies& bodies, int a, const Vec3& ha, int b, const Vec3& hb, double margin,
                             std::vector<RigidContact>& out) {
  const Vec3 d = bodies.position(a) - bodies.position(b);
  const Vec3 separation = d.cwiseAbs() - ha - hb;
  int k = 0;
  const double gap = separation.maxCoeff(&k);
  if (gap >= margin) return;
  const int i = (k + 1) % 3, j = (k + 2) % 3;  // the face's axes
  const Vec3 lo = (bodies.position(a) - ha).cwiseMax(bodies.position(b) - hb);
  const Vec3 hi = (bodies.position(a) + ha).cwiseMin(bodies.position(b) + hb);
  const double tiny = 1e-9 * (ha + hb).maxCoeff();
  if (hi[i] - lo[i] <= tiny || hi[j] - lo[j] <= tiny) return;  // edge or corner: no patch
  const double sign = d[k] >= 0 ? 1.0 : -1.0;
  Vec3 normal = Vec3::Zero();
  normal[k] = sign;  // from b into a
  const Mat3 frame = frame_from_normal(normal);
  const double plane = bodies.position(b)[k] + sign * (hb[k] + 0.5 * gap);
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

/// Sphere s of radius r and box x of half extents h (s != x): one contact
/// at the box's point closest to the sphere's centre.
inline void sphere_box_contact(const RigidBodies& bodies, int s, double r, int x, const Vec3& h, double margin,
                               std::vector<RigidContact>& out) {
  const Vec3 centre = bodies.position(s), box = bodies.position(x);
  const Vec3 closest = centre.cwiseMax(box - h).cwiseMin(box + h);
  const Vec3 d = centre - closest;
  const double dist = d.norm();
  Vec3 normal;  // from the box into the sphere
  double gap = 0;
  if (dist > 0) {
    normal = d / dist;
    gap = dist - r;
  } else {  // the centre inside the box: out through the nearest face
    const Vec3 offset = centre - box;
    int k = 0;
    (h - offset.cwiseAbs()).minCoeff(&k);
    normal = Vec3::Zero();
    normal[k] = offset[k] >= 0 ? 1.0 : -1.0;
    gap = std::abs(offset[k]) - h[k] - r;
  }
  if (gap >= margin) return;
  RigidContact c;
  c.a = std::min(s, x);
  c.b = std::max(s, x);
  c.frame = frame_from_normal(c.a == s ? normal : Vec3(-normal));
  c.point = centre - (r + 0.5 * gap) * normal;
  c.gap = gap;
  c.key = contact_key(c.a, std::uint64_t(c.b));
  out.push_back(c);
}

/// Sphere i of radius r on a fixed plane.
inline void sphere_plane_contact(const RigidBodies& bodies, int i, double r, const AxisPlane& plane, double margin,
                                 std::vector<RigidContact>& out) {
  const double gap = plane.normal.dot(bodies.position(i)) - plane.offset - r;
  if (gap >= margin) return;
  RigidContact c;
  c.a = i;
  c.b = -1 - plane.index;
  c.frame = frame_from_normal(plane.normal);
  c.point = bodies.position(i) - r * plane.normal;
  c.gap = gap;
  c.key = contact_key(i, std::uint64_t(bodies.count() + plane.index));
  out.push_back(c);
}

/// Box i of half extents h on a fixed plane: the 4 corners of its face
/// against the plane.
inline void box_plane_contacts(const RigidBodies& bodies, int i, const Vec3& h, const AxisPlane& plane, double margin,
                               std::vector<RigidContact>& out) {
  int k = 0;
  plane.normal.cwiseAbs().maxCoeff(&k);
  const Vec3& x = bodies.position(i);
  const double gap = plane.normal.dot(x) - plane.offset - h[k];
  if (gap >= margin) return;
  const int u = (k + 1) % 3, v = (k + 2) % 3;  // the face's axes
  const Mat3 frame = frame_from_normal(plane.normal);
  for (unsigned corner = 0; corner < 4; ++corner) {
    RigidContact c;
    c.a = i;
    c.b = -1 - plane.index;
    c.frame = frame;
    c.point[k] = plane.offset * plane.normal[k];  // on the plane (normal[k] = +-1)
    c.point[u] = x[u] + ((corner & 1) ? h[u] : -h[u]);
    c.point[v] = x[v] + ((corner & 2) ? h[v] : -h[v]);
    c.gap = gap;
    c.key = contact_key(i, std::uint64_t(bodies.count() + plane.index), corner);
    out.push_back(c);
  }
}

/// The open box of side L that sphere piles and mixed piles fall into:
/// obstacles 0 to 4, the floor z = 0 and the walls x = 0, x = L, y = 0, y = L.
inline std::vector<AxisPlane> open_box_planes(double L) {
  return {{Vec3(0, 0, 1), 0.0, 0},  {Vec3(1, 0, 0), 0.0, 1}, {Vec3(-1, 0, 0), -L, 2},
          {Vec3(0, 1, 0), 0.0, 3}, {Vec3(0, -1, 0), -L, 4}};
}

}  // namespace fcsolve::scenes

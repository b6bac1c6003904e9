// The scenes' contact detection (scenes/shape_contacts.hpp) on placements
// whose contacts are known in closed form: gap, normal direction (from b
// into a, so that a separating motion has u_N > 0), point, and count; and
// the mixed-shapes pile (scenes/mixed_shapes.hpp) holding every kind of
// contact once it has fallen.
#include <fcsolve/scenes/mixed_shapes.hpp>
#include <fcsolve/scenes/rigid_stepper.hpp>
#include <fcsolve/scenes/shape_contacts.hpp>

#include <catch2/catch.hpp>

#include <set>

using namespace fcsolve;
using namespace fcsolve::scenes;

namespace {

/// u_N of contact c when body `moving` moves with velocity v (others at rest).
double normal_velocity(const RigidBodies& bodies, const RigidContact& c, int moving, const Vec3& v) {
  Vector V = Vector::Zero(bodies.dofs());
  V.segment<3>(6 * moving) = v;
  return bodies.local_velocity(c, V)[0];
}

}  // namespace

TEST_CASE("sphere on a box: one contact at the closest point, normal from the box", "[scenes]") {
  for (const bool sphere_first : {true, false}) {
    RigidBodies bodies;
    const Vec3 half(1, 1, 0.4);
    int s = 0, x = 0;
    if (sphere_first) {
      s = bodies.add(Vec3(0.2, -0.3, 1.4), 1, Vec3::Ones());
      x = bodies.add(Vec3::Zero(), 1, Vec3::Ones());
    } else {
      x = bodies.add(Vec3::Zero(), 1, Vec3::Ones());
      s = bodies.add(Vec3(0.2, -0.3, 1.4), 1, Vec3::Ones());
    }
    std::vector<RigidContact> out;
    sphere_box_contact(bodies, s, 0.5, x, half, 0.1, out);
    CHECK(out.empty());  // gap 0.5 >= margin 0.1
    sphere_box_contact(bodies, s, 0.5, x, half, 1.0, out);
    REQUIRE(out.size() == 1);
    const RigidContact& c = out[0];
    CHECK(c.gap == Approx(0.5));
    CHECK(c.point.isApprox(Vec3(0.2, -0.3, 0.65)));  // midway between the top face (0.4) and the sphere (0.9)
    CHECK(normal_velocity(bodies, c, s, Vec3::UnitZ()) == Approx(1.0));  // the sphere lifting off separates
    CHECK(normal_velocity(bodies, c, x, Vec3::UnitZ()) == Approx(-1.0));
  }
}

TEST_CASE("sphere against a box edge, and a centre inside the box", "[scenes]") {
  RigidBodies bodies;
  const int x = bodies.add(Vec3::Zero(), 1, Vec3::Ones());
  const int s = bodies.add(Vec3(1.3, 0, 0.7), 1, Vec3::Ones());
  const Vec3 half(1, 1, 0.4);
  std::vector<RigidContact> out;
  sphere_box_contact(bodies, s, 0.5, x, half, 0.0, out);
  REQUIRE(out.size() == 1);
  CHECK(out[0].gap == Approx(std::sqrt(0.18) - 0.5));  // closest point (1, 0, 0.4)
  CHECK(normal_velocity(bodies, out[0], s, Vec3(1, 0, 1) / std::sqrt(2.0)) == Approx(1.0));
  RigidBodies inside;
  const int b = inside.add(Vec3::Zero(), 1, Vec3::Ones());
  const int t = inside.add(Vec3(0.1, 0.95, 0), 1, Vec3::Ones());  // nearest face y = 1
  out.clear();
  sphere_box_contact(inside, t, 0.2, b, half, 0.0, out);
  REQUIRE(out.size() == 1);
  CHECK(out[0].gap == Approx(0.95 - 1 - 0.2));
  CHECK(normal_velocity(inside, out[0], t, Vec3::UnitY()) == Approx(1.0));
}

TEST_CASE("box on a wall plane and on a box: 4 corners of the overlap", "[scenes]") {
  RigidBodies bodies;
  const Vec3 half(0.5, 0.25, 0.125);
  const int a = bodies.add(Vec3(1.2, 1, 1), 1, Vec3::Ones());
  std::vector<RigidContact> out;
  const AxisPlane wall{Vec3(-1, 0, 0), -2.0, 2};  // x <= 2
  box_plane_contacts(bodies, a, half, wall, 0.25, out);
  CHECK(out.empty());  // gap 0.3, above the margin
  box_plane_contacts(bodies, a, half, wall, 1.0, out);
  REQUIRE(out.size() == 4);
  std::set<std::uint64_t> keys;
  for (const RigidContact& c : out) {
    CHECK(c.gap == Approx(0.3));
    CHECK(c.b == -3);
    CHECK(c.point.x() == Approx(2.0));
    CHECK(std::abs(c.point.y() - 1) == Approx(0.25));
    CHECK(std::abs(c.point.z() - 1) == Approx(0.125));
    CHECK(normal_velocity(bodies, c, a, -Vec3::UnitX()) == Approx(1.0));  // moving off the wall
    keys.insert(c.key);
  }
  CHECK(keys.size() == 4);
  // a box resting across another one: the patch is the overlap rectangle
  const int b = bodies.add(Vec3(1.6, 1.1, 1.26), 1, Vec3::Ones());
  out.clear();
  box_box_contacts(bodies, a, half, b, half, 0.1, out);
  REQUIRE(out.size() == 4);
  for (const RigidContact& c : out) {
    CHECK(c.gap == Approx(0.01));
    CHECK(c.point.x() >= 1.1 - 1e-12);
    CHECK(c.point.x() <= 1.7 + 1e-12);
    CHECK(c.point.y() >= 0.85 - 1e-12);
    CHECK(c.point.y() <= 1.25 + 1e-12);
    CHECK(c.point.z() == Approx(1.13));                                  // midway in the gap
    CHECK(normal_velocity(bodies, c, b, Vec3::UnitZ()) == Approx(1.0));  // b, above, lifting off
  }
}

TEST_CASE("mixed shapes: the pile falls and holds every kind of contact", "[scenes]") {
  MixedShapesLayout layout;
  layout.bodies = 60;
  layout.seed = 7;
  MixedShapes pile(layout);
  int spheres = 0;
  for (int i = 0; i < pile.bodies().count(); ++i) spheres += pile.is_sphere(i);
  CHECK(spheres > 10);
  CHECK(spheres < 50);
  StepSettings s;
  s.h = 5e-3;
  s.tol = 1e-4;
  s.max_iter = 50;
  RigidStepper<MixedShapes> stepper(pile, s);
  for (int k = 0; k < 150; ++k) stepper.step();
  bool sphere_sphere = false, sphere_box = false, box_box = false, sphere_wall = false, box_wall = false;
  for (const RigidContact& c : stepper.contacts()) {
    const bool a = pile.is_sphere(c.a);
    if (c.b < 0) (a ? sphere_wall : box_wall) = true;
    else if (a && pile.is_sphere(c.b)) sphere_sphere = true;
    else if (a || pile.is_sphere(c.b)) sphere_box = true;
    else box_box = true;
  }
  CHECK(sphere_sphere);
  CHECK(sphere_box);
  CHECK(box_box);
  CHECK(sphere_wall);
  CHECK(box_wall);
  // settled, not sinking: no body below the floor by more than a tenth of its size
  for (int i = 0; i < pile.bodies().count(); ++i) CHECK(pile.bodies().position(i).z() > 0.02);
}

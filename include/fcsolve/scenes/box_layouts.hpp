// The box scenes of `fcsolve generate`, each sized so that it holds about
// `contacts` contacts once it has settled:
//   box-stack       columns of cubes, 4 contacts per face below;
//   heavy-on-light  columns whose upper half is mass_ratio times denser;
//   wall            a running-bond wall of bricks, each brick on two below (8 contacts);
//   tower           Kapla-style towers: levels of 3 planks, crossed at right
//                   angles from level to level (9 crossings x 4 = 36 contacts);
// The other layouts make their top layer mass_ratio times denser. Bodies
// start a little apart (gaps of 0.5..1 % of their height) with small random
// horizontal velocities: they fall, land, settle and slide.
#pragma once

#include <fcsolve/scenes/boxes.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace fcsolve::scenes {

struct BoxLayout {
  long contacts = 100;     ///< target number of contacts once settled
  long seed = 1;
  double mass_ratio = 1;   ///< heavy / light density
  double density = 1000;   ///< kg/m^3 of the light bodies
};

namespace detail {

/// The centre height of the next body of height 2 hz above a top at `top`,
/// with a random initial gap.
inline double stacked(double top, double hz, Uniform& uni) { return top + hz * (1.0 + uni(0.01, 0.02)); }

inline Vec3 drift(Uniform& uni, double speed) {
  const double vy = uni(-speed, speed);  // last coordinate first (geometry.hpp, Uniform)
  const double vx = uni(-speed, speed);
  return Vec3(vx, vy, 0.0);
}

inline long rounded(double x) { return std::max(1L, long(std::lround(x))); }

}  // namespace detail

/// Columns of cubes (edge 0.1 m): a box lies on the one below with 4
/// contacts. Heavy (mass_ratio) from level `heavy_from` of a column of
/// `height` (heavy_from >= height: only the top box is heavy).
inline BoxScene box_columns(const BoxLayout& p, long height, long heavy_from) {
  const double e = 0.05;
  const long boxes = std::max(1L, (p.contacts + 3) / 4);
  height = std::min(height, boxes);
  const long columns = (boxes + height - 1) / height;
  const long side = long(std::ceil(std::sqrt(double(columns))));
  Uniform uni(std::uint32_t(p.seed));
  BoxScene scene;
  for (long c = 0; c < columns; ++c) {
    const double cx = 3 * e * double(c % side), cy = 3 * e * double(c / side);
    double top = 0;
    for (long k = 0; k < height; ++k) {
      const bool heavy = k >= heavy_from || k == height - 1;
      const double z = detail::stacked(top, e, uni);
      const double dy = uni(-0.1, 0.1);  // last coordinate first (geometry.hpp, Uniform)
      const double dx = uni(-0.1, 0.1);
      const Vec3 x(cx + dx * e, cy + dy * e, z);
      scene.add_box(x, Vec3::Constant(e), p.density * (heavy ? p.mass_ratio : 1.0), detail::drift(uni, 0.02));
      top = z + e;
    }
  }
  return scene;
}

inline BoxScene box_stack(const BoxLayout& p) { return box_columns(p, 10, 10); }

inline BoxScene heavy_on_light(const BoxLayout& p) { return box_columns(p, 6, 3); }

/// A running-bond wall of 0.2 x 0.1 x 0.06 m bricks with 2 mm joints, rows
/// offset by half a brick: about 8 contacts per brick above the first row.
inline BoxScene brick_wall(const BoxLayout& p) {
  const Vec3 e(0.1, 0.05, 0.03);
  const double joint = 0.002;
  const long rows = detail::rounded(std::sqrt(double(p.contacts) / 16.0));
  const long per_row = detail::rounded(double(p.contacts) / double(8 * rows - 4));
  Uniform uni(std::uint32_t(p.seed));
  BoxScene scene;
  double top = 0;
  for (long r = 0; r < rows; ++r) {
    const double z = detail::stacked(top, e.z(), uni);
    const double shift = (r % 2) ? e.x() + 0.5 * joint : 0.0;
    for (long j = 0; j < per_row; ++j) {
      const double dy = uni(-0.02, 0.02);  // last coordinate first (geometry.hpp, Uniform)
      const double dx = uni(-0.2, 0.2);
      const Vec3 x(shift + double(j) * (2 * e.x() + joint) + dx * joint, dy * e.y(), z);
      scene.add_box(x, e, p.density * (r == rows - 1 ? p.mass_ratio : 1.0), detail::drift(uni, 0.01));
    }
    top = z + e.z();
  }
  return scene;
}

/// Kapla-style towers of 0.12 x 0.024 x 0.008 m planks: 3 parallel planks
/// per level, along x on even levels and along y on odd ones; a plank
/// crosses 3 below, 12 contacts on its lower face.
inline BoxScene kapla_towers(const BoxLayout& p) {
  const double a = 0.06, b = 0.012, c = 0.004;  // half extents
  const long levels = std::clamp(detail::rounded(2.0 * std::sqrt(double(p.contacts) / 36.0)), 1L, 20L);
  const long per_tower = 12 + 36 * (levels - 1);
  const long towers = detail::rounded(double(p.contacts) / double(per_tower));
  const long side = long(std::ceil(std::sqrt(double(towers))));
  Uniform uni(std::uint32_t(p.seed));
  BoxScene scene;
  for (long t = 0; t < towers; ++t) {
    const double tx = 0.2 * double(t % side), ty = 0.2 * double(t / side);
    double top = 0;
    for (long l = 0; l < levels; ++l) {
      const double z = detail::stacked(top, c, uni);
      const bool along_x = l % 2 == 0;
      for (int k = -1; k <= 1; ++k) {
        const double across = 4 * b * double(k) + uni(-0.05, 0.05) * b;
        const double along = uni(-0.02, 0.02) * a;
        const Vec3 x = along_x ? Vec3(tx + along, ty + across, z) : Vec3(tx + across, ty + along, z);
        const Vec3 e = along_x ? Vec3(a, b, c) : Vec3(b, a, c);
        scene.add_box(x, e, p.density * (l == levels - 1 ? p.mass_ratio : 1.0), detail::drift(uni, 0.005));
      }
      top = z + c;
    }
  }
  return scene;
}

}  // namespace fcsolve::scenes

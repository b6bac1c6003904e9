// Small geometric helpers of the scenes: contact frames, the cross-product
// matrix, and a platform-independent uniform random number source.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <random>

namespace fcsolve::scenes {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// An orthonormal frame [n t1 t2] from a unit normal, without a branch on
/// the direction (Duff et al. 2017, "Building an orthonormal basis,
/// revisited", JCGT 6(1), listing 3).
inline Mat3 frame_from_normal(const Vec3& n) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  Mat3 R;
  R.col(0) = n;
  R.col(1) = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  R.col(2) = Vec3(b, sign + n.y() * n.y() * a, -n.y());
  return R;
}

/// [a]_x with [a]_x b = a x b.
inline Mat3 cross_matrix(const Vec3& a) {
  Mat3 X;
  X << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return X;
}

/// A 32-bit Mersenne twister is specified bit for bit by the standard (its
/// distributions are not): uniform numbers from its raw output keep a scene
/// identical on every platform for a given seed, if each number is drawn in
/// a statement of its own. Two draws in the arguments of one call come in
/// an order C++ leaves unspecified (GCC evaluates Vec3(x, y, z) from z to
/// x, Clang from x to z), which the scenes did until 2026-11-29; they now
/// draw one per statement, from the last coordinate to the first, as GCC
/// did, so that the files written before stay the same.
class Uniform {
 public:
  explicit Uniform(std::uint32_t seed) : gen_(seed) {}
  double operator()(double a, double b) { return a + (b - a) * (double(gen_()) / 4294967296.0); }

 private:
  std::mt19937 gen_;
};

}  // namespace fcsolve::scenes

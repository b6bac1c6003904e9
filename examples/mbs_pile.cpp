// A pile of spheres falling into an open box: rigid bodies stepped in time by
// the Moreau-Jean scheme, one FC/II problem per step solved by fcsolve's NSGS
// through its user header, warm-started from the previous step's reactions.
//
//   mbs_pile [--spheres N] [--steps K] [--seed S] [--mu X] [--theta T] [--dt H]
//            [--tol X] [--max-iter N] [--restitution E] [--beta B] [--slop S]
//            [--no-warm-start] [--quiet] [--dump STEP FILE.hdf5] [--dump-local FILE.hdf5]
//
// Prints one line per step (step, contacts, iterations, error, time) and a
// summary; exits with 0 when every step reached --tol, 1 otherwise, 2 on bad
// usage. --dump writes step STEP's FC/I problem (M, H, f, w, mu) with the
// solution found as /solution; --dump-local writes its FC/II reduction too.
//
// Mechanics (Acary & Brogliato 2008, ch. 10; Jean 1999): body i has the
// generalised velocity (v_i, omega_i) in R^6 and the diagonal mass matrix
// diag(m_i I3, J_i I3), J_i = 2/5 m_i R_i^2. A sphere's inertia is isotropic,
// so the gyroscopic term omega x J omega is zero and orientations never enter
// the contact geometry: they are not tracked. One step (contact_law.hpp):
//   v_free = v + h M^-1 f_ext                       (f_ext: gravity)
//   M v+ = M v + h f_ext + H r,  u = H^T v+ + w     (FC/I)
//   W = H^T M^-1 H,  q = H^T v_free + w             (FC/II, problem/reduction.hpp)
//   x+ = x + h (theta v+ + (1 - theta) v)
// Contact a between body A and body B (or a wall) has the normal n pointing
// from B into A, tangents t1, t2 and frame R = [n t1 t2]; its local velocity is
//   u_a = R^T ((v_A + omega_A x (p - x_A)) - (v_B + omega_B x (p - x_B)))
// so H's 6 x 3 block for A is [R ; [p - x_A]_x R] and minus that for B.
#include <fcsolve/nsgs.hpp>

#include "stepping/contact_law.hpp"
#include "stepping/options.hpp"
#include "stepping/step_log.hpp"
#include "stepping/warm_start.hpp"
#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
#include "stepping/dump.hpp"
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace {

using fcsolve::Index;
using fcsolve::SparseMatrix;
using fcsolve::Vector;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Triplet = Eigen::Triplet<double, int>;

// Scene constants (SI units): spheres of radius 0.8..1.2 R0, density rho.
constexpr double kR0 = 0.05, kDensity = 1000.0, kGravity = 9.81, kPi = 3.14159265358979323846;
constexpr int kWalls = 5;  // floor, x = 0, x = L, y = 0, y = L (the box is open on top)

struct Parameters {
  Parameters() { law.slop = 0.005 * kR0; }
  long spheres = 200, steps = 200, seed = 1;
  double mu = 0.5, theta = 0.5, h = 2e-3, tol = 1e-8;
  long max_iter = 10000;
  stepping::ContactLaw law;
  bool warm_start = true, quiet = false;
  long dump_step = -1;
  std::string dump_file, dump_local_file;
};

/// A 32-bit Mersenne twister is specified bit for bit by the standard (its
/// distributions are not): uniform numbers from its raw output keep the scene
/// identical on every platform for a given seed.
class Uniform {
 public:
  explicit Uniform(std::uint32_t seed) : gen_(seed) {}
  double operator()(double a, double b) { return a + (b - a) * (double(gen_()) / 4294967296.0); }

 private:
  std::mt19937 gen_;
};

/// An orthonormal frame [n t1 t2] from a unit normal, without a branch on
/// the direction (Duff et al. 2017, "Building an orthonormal basis,
/// revisited", JCGT 6(1), listing 3).
Mat3 frame_from_normal(const Vec3& n) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  Mat3 R;
  R.col(0) = n;
  R.col(1) = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  R.col(2) = Vec3(b, sign + n.y() * n.y() * a, -n.y());
  return R;
}

Mat3 cross_matrix(const Vec3& a) {
  Mat3 X;
  X << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return X;
}

struct Contact {
  int a = 0;  ///< first body (a sphere)
  int b = 0;  ///< second body: a sphere index, or -1 - wall
  Mat3 frame;
  Vec3 point;
  double gap = 0;
  stepping::WarmStart::Key key = 0;
};

class Pile {
 public:
  explicit Pile(const Parameters& p) : p_(p) {
    const long n = p.spheres;
    side_ = std::max<long>(2, long(std::ceil(1.5 * std::cbrt(double(n)))));
    const double cell = 2.6 * kR0;  // > the largest diameter, 2.4 R0
    box_ = double(side_) * cell;
    radius_.resize(std::size_t(n));
    mass_.resize(std::size_t(n));
    x_.resize(std::size_t(n));
    V_ = Vector::Zero(6 * n);
    minv_.resize(6 * n);
    Uniform uni(std::uint32_t(p.seed));
    for (long i = 0; i < n; ++i) {
      const long layer = i / (side_ * side_), col = (i / side_) % side_, row = i % side_;
      const double R = kR0 * uni(0.8, 1.2);
      radius_[i] = R;
      mass_[i] = kDensity * 4.0 / 3.0 * kPi * R * R * R;
      const double J = 0.4 * mass_[i] * R * R;
      minv_.segment<3>(6 * i).setConstant(1.0 / mass_[i]);
      minv_.segment<3>(6 * i + 3).setConstant(1.0 / J);
      x_[i] = Vec3((double(row) + 0.5) * cell + uni(-0.1, 0.1) * kR0,
                   (double(col) + 0.5) * cell + uni(-0.1, 0.1) * kR0,
                   1.2 * kR0 + double(layer) * cell + uni(0.0, 0.4) * kR0);
      V_.segment<3>(6 * i) = Vec3(uni(-0.2, 0.2), uni(-0.2, 0.2), uni(-0.5, 0.0));
    }
  }

  long spheres() const { return long(x_.size()); }
  Index dofs() const { return V_.size(); }
  double box() const { return box_; }
  const Vector& inverse_mass() const { return minv_; }
  const Vector& velocity() const { return V_; }

  /// Contacts whose gap is below `margin`, in a deterministic order:
  /// sphere pairs by a sweep along x, then walls.
  std::vector<Contact> candidates(double margin) const {
    const int n = int(x_.size());
    std::vector<int> order(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
      return x_[i].x() - radius_[i] < x_[j].x() - radius_[j];
    });
    std::vector<Contact> out;
    for (int s = 0; s < n; ++s) {
      const int i = order[s];
      const double reach = x_[i].x() + radius_[i] + margin;
      for (int t = s + 1; t < n && x_[order[t]].x() - radius_[order[t]] <= reach; ++t) {
        const int j = order[t];
        const int a = std::min(i, j), b = std::max(i, j);
        const Vec3 d = x_[a] - x_[b];
        const double dist = d.norm();
        const double gap = dist - radius_[a] - radius_[b];
        if (gap >= margin || dist == 0.0) continue;
        Contact c;
        c.a = a;
        c.b = b;
        c.frame = frame_from_normal(d / dist);  // from b into a
        c.point = x_[b] + c.frame.col(0) * (radius_[b] + 0.5 * gap);
        c.gap = gap;
        c.key = (std::uint64_t(a) << 32) | std::uint64_t(b);
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
        const double gap = normal.dot(x_[i]) - offset - radius_[i];
        if (gap >= margin) continue;
        Contact c;
        c.a = i;
        c.b = -1 - k;
        c.frame = frame_from_normal(normal);
        c.point = x_[i] - radius_[i] * normal;
        c.gap = gap;
        c.key = (std::uint64_t(i) << 32) | std::uint64_t(n + k);
        out.push_back(c);
      }
    }
    std::sort(out.begin(), out.end(), [](const Contact& l, const Contact& r) { return l.key < r.key; });
    return out;
  }

  /// The local velocity R^T (relative velocity at the contact point) for the
  /// generalised velocity V: the column block of H^T for this contact.
  Vec3 local_velocity(const Contact& c, const Vector& V) const {
    Vec3 rel = V.segment<3>(6 * c.a) + V.segment<3>(6 * c.a + 3).cross(c.point - x_[c.a]);
    if (c.b >= 0) rel -= V.segment<3>(6 * c.b) + V.segment<3>(6 * c.b + 3).cross(c.point - x_[c.b]);
    return c.frame.transpose() * rel;
  }

  /// Appends contact number `col`'s 6 x 3 blocks of H (class comment).
  void add_columns(const Contact& c, int col, std::vector<Triplet>& t) const {
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
  void advance(const Vector& V_next) {
    for (std::size_t i = 0; i < x_.size(); ++i)
      x_[i] += p_.h * (p_.theta * V_next.segment<3>(6 * Index(i)) +
                       (1 - p_.theta) * V_.segment<3>(6 * Index(i)));
    V_ = V_next;
  }

  /// Gravity's impulse over a step, h f_ext.
  Vector external_impulse() const {
    Vector f = Vector::Zero(V_.size());
    for (std::size_t i = 0; i < x_.size(); ++i) f[6 * Index(i) + 2] = -p_.h * mass_[i] * kGravity;
    return f;
  }

  double max_speed() const {
    double s = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) s = std::max(s, V_.segment<3>(6 * Index(i)).norm());
    return s;
  }

 private:
  Parameters p_;
  long side_ = 2;
  double box_ = 1;
  std::vector<double> radius_, mass_;
  std::vector<Vec3> x_;
  Vector V_;     ///< (v_i, omega_i) per sphere
  Vector minv_;  ///< the diagonal of M^-1
};

Parameters parse(int argc, char** argv) {
  stepping::Options o(argc, argv);
  Parameters p;
  p.spheres = o.integer("spheres", p.spheres);
  p.steps = o.integer("steps", p.steps);
  p.seed = o.integer("seed", p.seed);
  p.mu = o.real("mu", p.mu);
  p.theta = o.real("theta", p.theta);
  p.h = o.real("dt", p.h);
  p.tol = o.real("tol", p.tol);
  p.max_iter = o.integer("max-iter", p.max_iter);
  p.law.restitution = o.real("restitution", p.law.restitution);
  p.law.beta = o.real("beta", p.law.beta);
  p.law.slop = o.real("slop", p.law.slop);
  p.warm_start = !o.flag("no-warm-start");
  p.quiet = o.flag("quiet");
  const auto dump = o.values("dump", 2);
  if (!dump.empty()) {
    p.dump_step = stepping::Options::to_integer("dump", dump[0]);
    p.dump_file = dump[1];
  }
  p.dump_local_file = o.text("dump-local", "");
  o.expect_all_used();
  if (p.spheres < 1 || p.steps < 1 || p.max_iter < 1) throw std::invalid_argument("--spheres, --steps and --max-iter must be positive");
  if (!(p.theta >= 0.5 && p.theta <= 1.0)) throw std::invalid_argument("--theta must be in [1/2, 1]");
  if (!(p.h > 0) || !(p.tol > 0) || !(p.mu >= 0)) throw std::invalid_argument("--dt and --tol must be positive, --mu not negative");
  if (!p.dump_local_file.empty() && p.dump_step < 0) throw std::invalid_argument("--dump-local needs --dump STEP FILE");
#ifndef FCSOLVE_EXAMPLES_WITH_FCLIB
  if (p.dump_step >= 0) throw std::invalid_argument("--dump needs HDF5: build with the fcsolve::fclib target");
#endif
  return p;
}

int run(const Parameters& p) {
  Pile pile(p);
  const Index n = pile.dofs();
  std::printf("# mbs_pile spheres=%ld steps=%ld seed=%ld mu=%g theta=%g dt=%g tol=%g box=%.3f "
              "restitution=%g beta=%g slop=%g warm_start=%d\n",
              p.spheres, p.steps, p.seed, p.mu, p.theta, p.h, p.tol, pile.box(), p.law.restitution,
              p.law.beta, p.law.slop, int(p.warm_start));
  stepping::StepLog log(p.quiet);
  stepping::WarmStart warm;
  // One solver for the whole trajectory: BSR storage of W (row products for
  // the sweeps), the exact one-contact solver by default (nsgs.hpp).
  fcsolve::Nsgs<fcsolve::Coulomb3D, fcsolve::BlockSparseStorage<3>> nsgs;
  nsgs.settings().tol = p.tol;
  nsgs.settings().max_iter = int(p.max_iter);

  const Vector& minv = pile.inverse_mass();
  std::vector<Triplet> triplets;
  bool dumped = false;
  for (long step = 1; step <= p.steps; ++step) {
    const Vector& V = pile.velocity();
    const Vector impulse = pile.external_impulse();
    const Vector V_free = V + minv.cwiseProduct(impulse);

    // Index set (contact_law.hpp): candidates within reach of a step's motion.
    const double margin = 0.5 * kR0 + 2.0 * p.h * pile.max_speed();
    std::vector<Contact> contacts;
    std::vector<double> w_normal;
    for (const Contact& c : pile.candidates(margin)) {
      if (!stepping::ContactLaw::active(c.gap, pile.local_velocity(c, V_free)[0], p.h)) continue;
      w_normal.push_back(p.law.normal_offset(c.gap, pile.local_velocity(c, V)[0], p.h));
      contacts.push_back(c);
    }
    const int nc = int(contacts.size());

    Vector V_next = V_free;
    if (nc == 0) {
      log.step(step, 0, 0, 0.0, 0.0, 0.0, "no-contact", true);
      warm.clear();
      pile.advance(V_next);
      continue;
    }
    triplets.clear();
    for (int a = 0; a < nc; ++a) pile.add_columns(contacts[a], a, triplets);
    SparseMatrix H(n, 3 * nc);
    H.setFromTriplets(triplets.begin(), triplets.end());
    H.makeCompressed();
    Vector w = Vector::Zero(3 * nc);
    for (int a = 0; a < nc; ++a) w[3 * a] = w_normal[a];

    fcsolve::LocalProblem local;
    local.d = 3;
    local.W = SparseMatrix(H.transpose()) * (minv.asDiagonal() * H);
    local.W.makeCompressed();
    local.q = H.transpose() * V_free + w;
    local.mu = Vector::Constant(nc, p.mu);

    Vector r = Vector::Zero(3 * nc), u(3 * nc);
    if (p.warm_start)
      for (int a = 0; a < nc; ++a) r.segment<3>(3 * a) = warm.initial(contacts[a].key, contacts[a].frame);

    fcsolve::Stopwatch clock;
    nsgs.compute(local);
    const fcsolve::SolverInfo& info = nsgs.solve(r, u);
    const double seconds = clock.seconds();
    log.step(step, nc, info.iterations, info.error, seconds, info.setup_seconds,
             fcsolve::to_string(info.status),
             info.converged());

    V_next += minv.cwiseProduct(H * r);  // v+ = v_free + M^-1 H r
    warm.begin_record();
    for (int a = 0; a < nc; ++a) warm.record(contacts[a].key, contacts[a].frame, r.segment<3>(3 * a));
    warm.end_record();

#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
    if (step == p.dump_step) {
      // FC/I: M v+ = f + H r with f = M v + h f_ext (so M^-1 f = v_free).
      fcsolve::GlobalProblem global;
      global.d = 3;
      global.M = SparseMatrix(n, n);
      global.M.reserve(Eigen::VectorXi::Constant(n, 1));
      for (Index i = 0; i < n; ++i) global.M.insert(i, i) = 1.0 / minv[i];
      global.M.makeCompressed();
      global.H = H;
      global.f = V.cwiseQuotient(minv) + impulse;
      global.w = w;
      global.mu = local.mu;
      const std::string params = "spheres=" + std::to_string(p.spheres) + " seed=" +
                                 std::to_string(p.seed) + " mu=" + std::to_string(p.mu) +
                                 " theta=" + std::to_string(p.theta) + " dt=" + std::to_string(p.h) +
                                 " restitution=" + std::to_string(p.law.restitution) +
                                 " beta=" + std::to_string(p.law.beta) + " slop=" +
                                 std::to_string(p.law.slop) + " step=" + std::to_string(step);
      global.text.title = "mbs_pile step " + std::to_string(step);
      global.text.description = "fcsolve examples/mbs_pile.cpp: spheres falling into an open box; " + params;
      global.text.math_info =
          "Moreau-Jean step: M v+ = f + H r, f = M v + h f_ext, u = H^T v+ + w, "
          "w_N = e min(u_N,0) + beta min(gap+slop,0)/h; solution: NSGS on W = H^T M^-1 H";
      stepping::dump_global(p.dump_file, global, r, V_next);
      if (!p.dump_local_file.empty()) {
        local.text = global.text;
        stepping::dump_local(p.dump_local_file, local, r);
      }
      std::printf("# dumped step %ld (%d contacts) to %s\n", step, nc, p.dump_file.c_str());
      dumped = true;
    }
#endif
    pile.advance(V_next);
  }
  log.summary();
  if (p.dump_step >= 0 && !dumped) {
    std::cerr << "mbs_pile: nothing dumped: step " << p.dump_step << " has no contact or is not simulated\n";
    return 1;
  }
  return log.all_converged() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Parameters p;
  try {
    p = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "mbs_pile: " << e.what() << "\n";
    return 2;
  }
  try {
    return run(p);
  } catch (const std::exception& e) {
    std::cerr << "mbs_pile: " << e.what() << "\n";
    return 3;
  }
}

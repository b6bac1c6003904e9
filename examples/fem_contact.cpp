// An elastic block pressed on a rigid plane: linear hexahedra (small strain)
// stepped in time by the Moreau-Jean scheme, one FC/I problem
// (M_hat, H, f, w, mu) per step solved natively (W never formed) by fcsolve's
// global semismooth Newton solver through its user header, warm-started from
// the previous step's reactions.
//
//   fem_contact [--nx 8] [--ny 8] [--nz 4] [--steps K] [--mu X] [--theta T] [--dt H]
//               [--young E] [--poisson NU] [--pressure P] [--shear S] [--consistent-mass]
//               [--tol X] [--max-iter N] [--beta B] [--slop S]
//               [--no-warm-start] [--quiet] [--dump STEP FILE.hdf5] [--dump-local FILE.hdf5]
//
// Prints one line per step (step, contacts, iterations, error, time) and a
// summary; exits with 0 when every step reached --tol, 1 otherwise, 2 on bad
// usage. --dump writes step STEP's FC/I problem with the solution found as
// /solution; --dump-local writes its FC/II reduction W = H^T M_hat^-1 H too.
//
// Mechanics. The block [0, Lx] x [0, Ly] x [0, Lz] starts at rest a little
// above the plane z = 0. It carries gravity and, on its top face, a pressure
// P and a shear traction S P along x, both ramped up over the first half of
// the run; its bottom nodes are node-to-plane contacts (normal e_z, tangents
// e_x, e_y). With the displacement x, the velocity v, the stiffness K and
// the mass M (lumped by row sums, or consistent), the Moreau-Jean step
// (Acary & Brogliato 2008, sec. 10.1 on linear systems; Jean 1999) is
//   M (v+ - v) = -h K x_theta + h f_ext(t + theta h) + H r,
//   x_theta = x + h theta (theta v+ + (1 - theta) v),
//   x+ = x + h (theta v+ + (1 - theta) v),
// that is FC/I with
//   M_hat = M + h^2 theta^2 K,
//   f = M v - h K (x + h theta (1 - theta) v) + h f_ext,
//   u = H^T v+ + w   (w: stepping/contact_law.hpp).
// M_hat is constant (small strain): it is factorised once for the free
// velocity M_hat^-1 f that decides which contacts are active.
#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/newton.hpp>

#include "stepping/contact_law.hpp"
#include "stepping/options.hpp"
#include "stepping/step_log.hpp"
#include "stepping/warm_start.hpp"
#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
#include <fcsolve/problem/reduction.hpp>

#include "stepping/dump.hpp"
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace {

using fcsolve::Index;
using fcsolve::SparseMatrix;
using fcsolve::Vector;
using Triplet = Eigen::Triplet<double, int>;
using Element24 = Eigen::Matrix<double, 24, 24>;

constexpr double kDensity = 1000.0, kGravity = 9.81;

struct Parameters {
  long nx = 8, ny = 8, nz = 4, steps = 100;
  double size_x = 0.4, size_y = 0.4, size_z = 0.2;  // m
  double mu = 0.5, theta = 0.5, h = 1e-3, tol = 1e-8;
  double young = 1e6, poisson = 0.3;  // Pa, -
  double pressure = 5e4, shear = 0.45;  // Pa on the top face; shear traction = shear * pressure
  double initial_gap = 1e-4;  // m
  bool consistent_mass = false;
  long max_iter = 200;
  stepping::ContactLaw law;
  bool warm_start = true, quiet = false;
  long dump_step = -1;
  std::string dump_file, dump_local_file;
};

/// The (xi, eta, zeta) signs of the 8 nodes of the reference hexahedron.
constexpr std::array<std::array<int, 3>, 8> kCorner = {{
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
    {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}};

/// Stiffness and consistent mass of one dx x dy x dz trilinear hexahedron
/// (Hughes 2000, "The Finite Element Method", sec. 3.5), 2 x 2 x 2 Gauss
/// points; unknowns ordered (node a, component i) -> 3 a + i. All elements
/// of the regular mesh are translates of each other: computed once.
void element_matrices(const Parameters& p, double dx, double dy, double dz, Element24& Ke,
                      Element24& Me) {
  const double E = p.young, nu = p.poisson;
  Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();  // isotropic, Voigt
  const double c = E / ((1 + nu) * (1 - 2 * nu));
  D.topLeftCorner<3, 3>().setConstant(c * nu);
  for (int i = 0; i < 3; ++i) D(i, i) = c * (1 - nu);
  for (int i = 3; i < 6; ++i) D(i, i) = c * (1 - 2 * nu) / 2;  // engineering shear strains
  const double g = 1.0 / std::sqrt(3.0);
  const double detJ = dx * dy * dz / 8.0;  // the map is diagonal: J = diag(dx, dy, dz) / 2
  Ke.setZero();
  Me.setZero();
  for (int gp = 0; gp < 8; ++gp) {
    const double xi = g * kCorner[gp][0], eta = g * kCorner[gp][1], zeta = g * kCorner[gp][2];
    Eigen::Matrix<double, 6, 24> B = Eigen::Matrix<double, 6, 24>::Zero();
    Eigen::Matrix<double, 8, 1> N;
    for (int a = 0; a < 8; ++a) {
      const double sa = kCorner[a][0], ta = kCorner[a][1], ua = kCorner[a][2];
      N[a] = (1 + sa * xi) * (1 + ta * eta) * (1 + ua * zeta) / 8;
      const double Nx = sa * (1 + ta * eta) * (1 + ua * zeta) / 8 * 2 / dx;
      const double Ny = ta * (1 + sa * xi) * (1 + ua * zeta) / 8 * 2 / dy;
      const double Nz = ua * (1 + sa * xi) * (1 + ta * eta) / 8 * 2 / dz;
      // rows: e_xx, e_yy, e_zz, g_yz, g_xz, g_xy
      B(0, 3 * a) = Nx;
      B(1, 3 * a + 1) = Ny;
      B(2, 3 * a + 2) = Nz;
      B(3, 3 * a + 1) = Nz;
      B(3, 3 * a + 2) = Ny;
      B(4, 3 * a) = Nz;
      B(4, 3 * a + 2) = Nx;
      B(5, 3 * a) = Ny;
      B(5, 3 * a + 1) = Nx;
    }
    Ke += B.transpose() * D * B * detJ;
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
        for (int i = 0; i < 3; ++i) Me(3 * a + i, 3 * b + i) += kDensity * N[a] * N[b] * detJ;
  }
}

class Block {
 public:
  explicit Block(const Parameters& p) : p_(p) {
    const long nodes = (p.nx + 1) * (p.ny + 1) * (p.nz + 1);
    n_ = 3 * nodes;
    const double dx = p.size_x / double(p.nx), dy = p.size_y / double(p.ny), dz = p.size_z / double(p.nz);
    Element24 Ke, Me;
    element_matrices(p, dx, dy, dz, Ke, Me);
    if (!p.consistent_mass) {  // row-sum lumping: m / 8 per node for a hexahedron
      const Eigen::Matrix<double, 24, 1> lumped = Me.rowwise().sum();
      Me = lumped.asDiagonal();
    }
    std::vector<Triplet> tk, tm;
    for (long k = 0; k < p.nz; ++k)
      for (long j = 0; j < p.ny; ++j)
        for (long i = 0; i < p.nx; ++i) {
          std::array<int, 24> dof;
          for (int a = 0; a < 8; ++a) {
            const long node = node_index(i + (kCorner[a][0] > 0), j + (kCorner[a][1] > 0), k + (kCorner[a][2] > 0));
            for (int c = 0; c < 3; ++c) dof[3 * a + c] = int(3 * node + c);
          }
          for (int r = 0; r < 24; ++r)
            for (int c = 0; c < 24; ++c) {
              tk.emplace_back(dof[r], dof[c], Ke(r, c));
              if (Me(r, c) != 0.0) tm.emplace_back(dof[r], dof[c], Me(r, c));
            }
        }
    K_.resize(n_, n_);
    K_.setFromTriplets(tk.begin(), tk.end());
    M_.resize(n_, n_);
    M_.setFromTriplets(tm.begin(), tm.end());
    M_hat_ = M_ + (p.h * p.h * p.theta * p.theta) * K_;
    K_.makeCompressed();
    M_.makeCompressed();
    M_hat_.makeCompressed();

    // Gravity (M times a uniform acceleration: exact for either mass) and
    // the top face's unit load, area / 4 per node and quadrilateral.
    Vector g = Vector::Zero(n_);
    for (Index a = 0; a < nodes; ++a) g[3 * a + 2] = -kGravity;
    gravity_ = M_ * g;
    top_load_ = Vector::Zero(n_);
    for (long j = 0; j < p.ny; ++j)
      for (long i = 0; i < p.nx; ++i)
        for (int a = 0; a < 4; ++a) {
          const long node = node_index(i + (a == 1 || a == 2), j + (a >= 2), p.nz);
          top_load_[3 * node] += p.shear * dx * dy / 4;   // shear traction per unit pressure
          top_load_[3 * node + 2] -= dx * dy / 4;         // pressure pushes down
        }
    x_ = Vector::Zero(n_);
    v_ = Vector::Zero(n_);
    for (long j = 0; j <= p.ny; ++j)
      for (long i = 0; i <= p.nx; ++i) bottom_.push_back(node_index(i, j, 0));
    factor_.compute(M_hat_);
    if (factor_.info() != Eigen::Success) throw std::runtime_error("M_hat is not positive definite");
  }

  Index dofs() const { return n_; }
  const SparseMatrix& M_hat() const { return M_hat_; }
  const Vector& velocity() const { return v_; }
  const std::vector<long>& bottom_nodes() const { return bottom_; }
  /// Height of a bottom node above the plane (the reference height is initial_gap).
  double gap(long node) const { return p_.initial_gap + x_[3 * node + 2]; }

  /// f = M v - h K (x + h theta (1 - theta) v) + h f_ext(t + theta h), t = (step - 1) h.
  Vector step_force(long step) const {
    const double t = (double(step - 1) + p_.theta) * p_.h;
    const double ramp = std::min(1.0, t / (0.5 * double(p_.steps) * p_.h));
    const Vector f_ext = gravity_ + (ramp * p_.pressure) * top_load_;
    return M_ * v_ - p_.h * (K_ * (x_ + (p_.h * p_.theta * (1 - p_.theta)) * v_)) + p_.h * f_ext;
  }
  Vector free_velocity(const Vector& f) const { return factor_.solve(f); }

  void advance(const Vector& v_next) {
    x_ += p_.h * (p_.theta * v_next + (1 - p_.theta) * v_);
    v_ = v_next;
  }

 private:
  long node_index(long i, long j, long k) const { return i + (p_.nx + 1) * (j + (p_.ny + 1) * k); }

  Parameters p_;
  Index n_ = 0;
  SparseMatrix K_, M_, M_hat_;
  Vector gravity_, top_load_, x_, v_;
  std::vector<long> bottom_;
  fcsolve::DefaultBackend::SymmetricSolver factor_;
};

Parameters parse(int argc, char** argv) {
  stepping::Options o(argc, argv);
  Parameters p;
  p.nx = o.integer("nx", p.nx);
  p.ny = o.integer("ny", p.ny);
  p.nz = o.integer("nz", p.nz);
  p.steps = o.integer("steps", p.steps);
  p.mu = o.real("mu", p.mu);
  p.theta = o.real("theta", p.theta);
  p.h = o.real("dt", p.h);
  p.young = o.real("young", p.young);
  p.poisson = o.real("poisson", p.poisson);
  p.pressure = o.real("pressure", p.pressure);
  p.shear = o.real("shear", p.shear);
  p.consistent_mass = o.flag("consistent-mass");
  p.tol = o.real("tol", p.tol);
  p.max_iter = o.integer("max-iter", p.max_iter);
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
  if (p.nx < 1 || p.ny < 1 || p.nz < 1 || p.steps < 1 || p.max_iter < 1)
    throw std::invalid_argument("--nx, --ny, --nz, --steps and --max-iter must be positive");
  if (!(p.theta >= 0.5 && p.theta <= 1.0)) throw std::invalid_argument("--theta must be in [1/2, 1]");
  if (!(p.h > 0) || !(p.tol > 0) || !(p.mu > 0) || !(p.young > 0) || !(p.poisson > -1 && p.poisson < 0.5))
    throw std::invalid_argument("--dt, --tol, --mu, --young must be positive, --poisson in (-1, 1/2)");
  if (!p.dump_local_file.empty() && p.dump_step < 0) throw std::invalid_argument("--dump-local needs --dump STEP FILE");
#ifndef FCSOLVE_EXAMPLES_WITH_FCLIB
  if (p.dump_step >= 0) throw std::invalid_argument("--dump needs HDF5: build with the fcsolve::fclib target");
#endif
  return p;
}

int run(const Parameters& p) {
  Block block(p);
  const Index n = block.dofs();
  std::printf("# fem_contact nx=%ld ny=%ld nz=%ld dofs=%ld steps=%ld mu=%g theta=%g dt=%g tol=%g "
              "young=%g poisson=%g pressure=%g shear=%g mass=%s beta=%g slop=%g warm_start=%d\n",
              p.nx, p.ny, p.nz, long(n), p.steps, p.mu, p.theta, p.h, p.tol, p.young, p.poisson,
              p.pressure, p.shear, p.consistent_mass ? "consistent" : "lumped", p.law.beta,
              p.law.slop, int(p.warm_start));
  stepping::StepLog log(p.quiet);
  stepping::WarmStart warm;
  const stepping::WarmStart::Frame frame =
      (stepping::WarmStart::Frame() << 0, 1, 0, 0, 0, 1, 1, 0, 0).finished();  // [e_z e_x e_y]

  // Semismooth Newton on (v, r) with the Alart-Curnier function (newton.hpp):
  // FC/I as it is, M_hat factorised by the solver (CHOLMOD when linked).
  fcsolve::NewtonSettings settings;
  settings.tol = p.tol;
  settings.max_iter = int(p.max_iter);
  fcsolve::GlobalNewton<fcsolve::AlartCurnierFunction, fcsolve::Coulomb3D> newton(settings);

  // The step's FC/I: M_hat is set once, the rest per step. The solver views
  // it: it must outlive the solve.
  fcsolve::GlobalProblem problem;
  problem.d = 3;
  problem.M = block.M_hat();
  std::vector<Triplet> triplets;
  bool dumped = false;
  for (long step = 1; step <= p.steps; ++step) {
    const Vector& v = block.velocity();
    const Vector f = block.step_force(step);
    const Vector v_free = block.free_velocity(f);

    // Node-to-plane contacts (contact_law.hpp): u = (v_z, v_x, v_y) at the node.
    std::vector<long> nodes;
    std::vector<double> w_normal;
    for (const long node : block.bottom_nodes()) {
      const double gap = block.gap(node);
      if (!stepping::ContactLaw::active(gap, v_free[3 * node + 2], p.h)) continue;
      nodes.push_back(node);
      w_normal.push_back(p.law.normal_offset(gap, v[3 * node + 2], p.h));
    }
    const int nc = int(nodes.size());
    Vector v_next = v_free;
    if (nc == 0) {
      log.step(step, 0, 0, 0.0, 0.0, 0.0, "no-contact", true);
      warm.clear();
      block.advance(v_next);
      continue;
    }
    triplets.clear();
    for (int a = 0; a < nc; ++a) {
      triplets.emplace_back(int(3 * nodes[a] + 2), 3 * a, 1.0);  // normal: e_z
      triplets.emplace_back(int(3 * nodes[a]), 3 * a + 1, 1.0);   // tangent 1: e_x
      triplets.emplace_back(int(3 * nodes[a] + 1), 3 * a + 2, 1.0);  // tangent 2: e_y
    }
    problem.H.resize(n, 3 * nc);
    problem.H.setFromTriplets(triplets.begin(), triplets.end());
    problem.H.makeCompressed();
    problem.f = f;
    problem.w = Vector::Zero(3 * nc);
    for (int a = 0; a < nc; ++a) problem.w[3 * a] = w_normal[a];
    problem.mu = Vector::Constant(nc, p.mu);

    Vector r = Vector::Zero(3 * nc);
    if (p.warm_start)
      for (int a = 0; a < nc; ++a) r.segment<3>(3 * a) = warm.initial(stepping::WarmStart::Key(nodes[a]), frame);

    fcsolve::Stopwatch clock;
    newton.compute(problem);
    const fcsolve::SolverInfo& info = newton.solve(r, v_next);
    const double seconds = clock.seconds();
    log.step(step, nc, info.iterations, info.error, seconds, info.setup_seconds,
             fcsolve::to_string(info.status),
             info.converged());

    warm.begin_record();
    for (int a = 0; a < nc; ++a) warm.record(stepping::WarmStart::Key(nodes[a]), frame, r.segment<3>(3 * a));
    warm.end_record();

#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
    if (step == p.dump_step) {
      problem.text.title = "fem_contact step " + std::to_string(step);
      problem.text.description =
          "fcsolve examples/fem_contact.cpp: elastic block (trilinear hexahedra, " +
          std::string(p.consistent_mass ? "consistent" : "lumped") + " mass) pressed on a rigid plane; nx=" +
          std::to_string(p.nx) + " ny=" + std::to_string(p.ny) + " nz=" + std::to_string(p.nz) +
          " mu=" + std::to_string(p.mu) + " theta=" + std::to_string(p.theta) + " dt=" +
          std::to_string(p.h) + " young=" + std::to_string(p.young) + " poisson=" +
          std::to_string(p.poisson) + " pressure=" + std::to_string(p.pressure) + " shear=" +
          std::to_string(p.shear) + " step=" + std::to_string(step);
      problem.text.math_info =
          "Moreau-Jean step: M_hat v+ = f + H r, M_hat = M + h^2 theta^2 K, "
          "f = M v - h K (x + h theta (1-theta) v) + h f_ext, u = H^T v+ + w, "
          "w_N = beta min(gap+slop,0)/h; solution: GlobalNewton (Alart-Curnier)";
      stepping::dump_global(p.dump_file, problem, r, v_next);
      if (!p.dump_local_file.empty()) {
        fcsolve::LocalProblem local = fcsolve::GlobalReduction<fcsolve::DefaultBackend>(problem).local();
        local.text = problem.text;
        stepping::dump_local(p.dump_local_file, local, r);
      }
      std::printf("# dumped step %ld (%d contacts) to %s\n", step, nc, p.dump_file.c_str());
      dumped = true;
    }
#endif
    block.advance(v_next);
  }
  log.summary();
  if (p.dump_step >= 0 && !dumped) {
    std::cerr << "fem_contact: nothing dumped: step " << p.dump_step << " has no contact or is not simulated\n";
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
    std::cerr << "fem_contact: " << e.what() << "\n";
    return 2;
  }
  try {
    return run(p);
  } catch (const std::exception& e) {
    std::cerr << "fem_contact: " << e.what() << "\n";
    return 3;
  }
}

// The FCLIB error measure (closed-form values) and the global -> reduced
// transformation (against dense linear algebra, both backends, bilateral
// constraints, recovery of v and lambda).
#include "test_support.hpp"

#include <fcsolve/cone/tresca.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/linalg/suitesparse_backend.hpp>
#include <fcsolve/problem/reduction.hpp>

#include <Eigen/Dense>
#include <random>
#include <catch2/catch.hpp>

using namespace fcsolve;

namespace {

LocalProblem one_contact(double mu, const Eigen::Vector3d& q, const Eigen::Matrix3d& Wd) {
  LocalProblem p;
  p.d = 3;
  p.W = Wd.sparseView();
  p.W.makeCompressed();
  p.q = q;
  p.mu = Vector::Constant(1, mu);
  return p;
}

}  // namespace

TEST_CASE("error is zero at the closed-form solutions of one contact", "[error]") {
  const Eigen::Matrix3d W = Eigen::Vector3d(2, 1, 1).asDiagonal();
  const double mu = 0.5;
  SECTION("take-off: q_N > 0 gives r = 0, u = q") {
    const LocalProblem p = one_contact(mu, Eigen::Vector3d(1, 0.3, -0.2), W);
    CHECK(local_error(p, Vector::Zero(3)) == 0.0);
    CHECK(local_error(p, Eigen::Vector3d(0.1, 0, 0)) > 0.0);
  }
  SECTION("sticking: u = 0, r = -W^-1 q inside K") {
    const LocalProblem p = one_contact(mu, Eigen::Vector3d(-2, 0.1, 0.1), W);
    const Vector r = -W.inverse() * p.q;  // (1, -0.1, -0.1): ||r_T|| < mu r_N
    REQUIRE(Coulomb3D::contains(Coulomb3D::Vec(r), mu));
    CHECK(local_error(p, r) < 1e-16);
  }
  SECTION("sliding: r on the boundary, opposed to u_T") {
    // W = diag(2,1,1), q = (-2, 3, 0): r_N = 1, r_T = (-mu, 0), u = (0, 3 - mu, 0)
    const LocalProblem p = one_contact(mu, Eigen::Vector3d(-2, 3, 0), W);
    const Vector r = Eigen::Vector3d(1, -mu, 0);
    CHECK(local_error(p, r) < 1e-15);
    const LocalErrorReport rep = local_error_report(p, r);
    CHECK(rep.worst_contact <= 0);
  }
}

TEST_CASE("error value matches the natural map formula", "[error]") {
  const Eigen::Matrix3d W = Eigen::Matrix3d::Identity();
  const LocalProblem p = one_contact(0.0, Eigen::Vector3d(3, 0, 4), W);  // ||q|| = 5
  // r = (1, 0, 0): u = (4, 0, 4); mu = 0 -> u~ = u; r - u~ = (-3, 0, -4) -> P_K = 0
  // F = r - 0 = (1, 0, 0), error = 1 / 5, Siconos: 1 / max(5, 1, ||u|| = 5.657)
  const LocalErrorReport rep = local_error_report(p, Eigen::Vector3d(1, 0, 0));
  CHECK(rep.error == Approx(0.2));
  CHECK(rep.absolute == Approx(1.0));
  CHECK(rep.siconos_error == Approx(1.0 / std::sqrt(32.0)));
  CHECK(rep.max_contact == Approx(0.2));
  CHECK(rep.worst_contact == 0);
  // q = 0: absolute error
  const LocalProblem z = one_contact(0.0, Eigen::Vector3d::Zero(), W);
  CHECK(local_error(z, Eigen::Vector3d(1, 0, 0)) == Approx(1.0));
}

TEST_CASE("zero_reaction_error_bound is below the error of r = 0, and tight on the boundary ray",
          "[error]") {
  // per contact: ||F^a(0)|| >= max(0, -q_N) / (1 + mu^2); random contacts,
  // every cone the bound covers; equality when -(q + g(q)) projects onto
  // the boundary ray (q_T large against -q_N)
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> uni(-2, 2), pos(0, 2);
  for (int trial = 0; trial < 2000; ++trial) {
    const double mu = trial % 7 == 0 ? 0.0 : pos(gen);
    const Eigen::Vector3d q(uni(gen), uni(gen), uni(gen));
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    const double F3 = natural_map<Coulomb3D>(zero, q, mu).norm();
    const double b3 = zero_reaction_error_bound<Coulomb3D>(q, Vector::Constant(1, mu));
    CHECK(b3 <= F3 * (1 + 1e-14));
    CHECK(b3 == Approx(std::max(0.0, -q[0]) / (1 + mu * mu)).epsilon(1e-15));
    const Eigen::Vector2d q2 = q.head<2>();
    CHECK(zero_reaction_error_bound<Coulomb2D>(q2, Vector::Constant(1, mu)) <=
          natural_map<Coulomb2D>(Eigen::Vector2d::Zero(), q2, mu).norm() * (1 + 1e-14));
    const Eigen::Matrix<double, 1, 1> q1(q[0]);
    CHECK(zero_reaction_error_bound<Frictionless>(q1, Vector::Constant(1, mu)) <=
          natural_map<Frictionless>(Eigen::Matrix<double, 1, 1>::Zero(), q1, mu).norm() * (1 + 1e-14));
  }
  // the boundary ray: q = (-1, 10, 0), mu = 0.5: F(0) = -(1 / 1.25) (1, -0.5, 0)
  const Eigen::Vector3d q(-1, 10, 0);
  const double F = natural_map<Coulomb3D>(Eigen::Vector3d::Zero(), q, 0.5)[0];
  CHECK(-F == Approx(1 / 1.25));
  CHECK(zero_reaction_error_bound<Coulomb3D>(q, Vector::Constant(1, 0.5)) == Approx(-F));
  // a cone the bound does not cover gets 0
  CHECK(zero_reaction_error_bound<TrescaCylinder<3>>(q, Vector::Constant(1, 0.5)) == 0);
}

TEST_CASE("LocalErrorEvaluator agrees with local_error", "[error]") {
  for (const auto& f : fcsolve_test::fclib_files("local")) {
    const LocalProblem p = fclib::read_local(f);
    Vector r = Vector::Zero(p.size());
    for (Index a = 0; a < p.num_contacts(); ++a) r.segment<3>(3 * a) << 1.0 + 0.1 * a, 0.05, -0.02;
    LocalErrorEvaluator<Coulomb3D> eval(p);
    CHECK(eval(r) == Approx(local_error(p, r)).epsilon(1e-14));
  }
}

namespace {

template <class Backend>
void check_reduction(const GlobalProblem& g, const std::string& name) {
  INFO(name << " backend " << Backend::name);
  GlobalReduction<Backend> red(g);
  const DenseMatrix M = DenseMatrix(g.M), H = DenseMatrix(g.H);
  const Eigen::PartialPivLU<DenseMatrix> lu(M);
  const DenseMatrix Wref = H.transpose() * lu.solve(H);
  const Vector qref = H.transpose() * lu.solve(g.f) + g.w;
  const DenseMatrix W = DenseMatrix(red.local().W);
  REQUIRE((W - Wref).norm() <= 1e-8 * Wref.norm());
  REQUIRE((red.local().q - qref).norm() <= 1e-8 * std::max(1e-300, qref.norm()));
  CHECK(red.free_velocity_norm() == Approx(qref.norm()).epsilon(1e-8));
  // the LMGC M is not symmetric: LU, never Cholesky
  if (red.asymmetry_of_M() > kSymmetryRoundoff) CHECK_FALSE(red.uses_cholesky());
  // recovery: M v = H r + f to rounding
  Vector r = Vector::Zero(g.size());
  for (Index a = 0; a < g.num_contacts(); ++a) r[3 * a] = 1.0 + a;
  const Vector v = red.velocity(r);
  const Vector res = DenseMatrix(g.M) * v - H * r - g.f;
  CHECK(res.norm() <= 1e-9 * std::max({g.f.norm(), (H * r).norm(), 1e-300}));
  // and the global error of (r, v) equals the local error of r
  const GlobalErrorReport ge = global_error_report(g, red.free_velocity_norm(), r, v);
  CHECK(ge.complementarity == Approx(local_error(red.local(), r)).epsilon(1e-6));
}

}  // namespace

TEST_CASE("reduction matches dense linear algebra on every global problem", "[reduction][fclib]") {
  for (const auto& f : fcsolve_test::fclib_files("global")) {
    const GlobalProblem g = fclib::read_global(f);
    if (g.num_dofs() > 2000) continue;  // dense reference too slow (Spheres: n = 12000)
    check_reduction<EigenBackend>(g, f);
    check_reduction<SuiteSparseBackend>(g, f);
  }
}

namespace {
// 3 dofs, 1 contact (d = 3), one bilateral constraint v0 - v2 = -b
GlobalProblem bilateral_problem(double b) {
  GlobalProblem g;
  g.d = 3;
  DenseMatrix M(3, 3);
  M << 4, 1, 0, 1, 3, 0.5, 0, 0.5, 2;
  g.M = M.sparseView();
  DenseMatrix H = DenseMatrix::Identity(3, 3);
  H(2, 1) = 0.3;
  g.H = H.sparseView();
  DenseMatrix G(3, 1);
  G << 1, 0, -1;
  g.G = G.sparseView();
  g.f = Vector::LinSpaced(3, -1, 1);
  g.w = Vector::Constant(3, 0.1);
  g.b = Vector::Constant(1, b);
  g.mu = Vector::Constant(1, 0.3);
  for (auto* A : {&g.M, &g.H, &g.G}) A->makeCompressed();
  return g;
}
}  // namespace

TEST_CASE("reduction with bilateral constraints eliminates lambda", "[reduction]") {
  // b = 0 (a joint) is the common case: the error's scale must not vanish
  // with the residual there (issue 15, item 4).
  const double b = GENERATE(0.25, 0.0);
  const GlobalProblem g = bilateral_problem(b);
  const DenseMatrix M(g.M), H(g.H), G(g.G);

  GlobalReduction<> red(g);
  // dense Schur complement: W = H^T (Mi - Mi G S^-1 G^T Mi) H, S = G^T Mi G
  const DenseMatrix Mi = M.inverse();
  const DenseMatrix S = G.transpose() * Mi * G;
  const DenseMatrix P = Mi - Mi * G * S.inverse() * G.transpose() * Mi;
  const DenseMatrix Wref = H.transpose() * P * H;
  const Vector qref = H.transpose() * (P * g.f - Mi * G * S.inverse() * g.b) + g.w;
  CHECK((DenseMatrix(red.local().W) - Wref).norm() < 1e-12);
  CHECK((red.local().q - qref).norm() < 1e-12);

  const Vector r = Eigen::Vector3d(1.0, 0.2, -0.1);
  const Vector v = red.velocity(r), lambda = red.multipliers(r);
  CHECK((M * v - H * r - G * lambda - g.f).norm() < 1e-12);
  CHECK((G.transpose() * v + g.b).norm() < 1e-12);
  const GlobalErrorReport e = global_error_report(g, red.free_velocity_norm(), r, v, lambda);
  CHECK(e.equilibrium < 1e-14);
  CHECK(e.complementarity == Approx(local_error(red.local(), r)).epsilon(1e-10));

  // a violated constraint still scores as one: v shifted along G
  const Vector v_bad = v + 0.1 * G.col(0);
  CHECK(global_error_report(g, red.free_velocity_norm(), r, v_bad, lambda).equilibrium > 1e-3);
}

TEST_CASE("reduction rejects a singular M", "[reduction]") {
  GlobalProblem g;
  g.M = SparseMatrix(3, 3);  // all zero
  g.M.makeCompressed();
  g.H = DenseMatrix(DenseMatrix::Identity(3, 3)).sparseView();
  g.H.makeCompressed();
  g.f = Vector::Ones(3);
  g.w = Vector::Zero(3);
  g.mu = Vector::Constant(1, 0.1);
  CHECK_THROWS_AS(GlobalReduction<>(g), InvalidProblem);
}

namespace {
// Bodies of 6 dofs whose dofs are interleaved (dof i belongs to body i % nb),
// random well-conditioned blocks (SPD, or SPD plus a small skew part), and a
// random sparse H: W must equal the dense H^T M^-1 H whichever path forms it.
GlobalProblem interleaved_bodies(Index bodies, Index contacts, bool symmetric, unsigned seed) {
  std::srand(seed);
  const Index n = 6 * bodies;
  DenseMatrix M = DenseMatrix::Zero(n, n);
  for (Index b = 0; b < bodies; ++b) {
    const DenseMatrix A = DenseMatrix::Random(6, 6);
    DenseMatrix block = A * A.transpose() + 6 * DenseMatrix::Identity(6, 6);
    if (!symmetric) block += 0.01 * (A - A.transpose());
    for (Index i = 0; i < 6; ++i)
      for (Index j = 0; j < 6; ++j) M(b + bodies * i, b + bodies * j) = block(i, j);
  }
  DenseMatrix H = DenseMatrix::Zero(n, 3 * contacts);
  for (Index c = 0; c < 3 * contacts; ++c)
    for (Index k = 0; k < 4; ++k) H(std::rand() % n, c) = DenseMatrix::Random(1, 1)(0, 0);
  GlobalProblem g;
  g.d = 3;
  g.M = M.sparseView();
  g.H = H.sparseView();
  g.f = Vector::Random(n);
  g.w = Vector::Random(3 * contacts);
  g.mu = Vector::Constant(contacts, 0.4);
  g.M.makeCompressed();
  g.H.makeCompressed();
  return g;
}
}  // namespace

TEST_CASE("block-diagonal M: W from the block inverse matches dense algebra", "[reduction]") {
  const bool symmetric = GENERATE(true, false);
  const GlobalProblem g = interleaved_bodies(7, 12, symmetric, 11);
  INFO((symmetric ? "symmetric" : "unsymmetric") << " blocks");
  const auto Minv = block_diagonal_inverse(GlobalProblemView(g).M, symmetric);
  REQUIRE(Minv.has_value());
  const DenseMatrix M(g.M);
  CHECK((DenseMatrix(*Minv) * M - DenseMatrix::Identity(M.rows(), M.cols())).norm() < 1e-12);
  check_reduction<EigenBackend>(g, "interleaved bodies");
  check_reduction<SuiteSparseBackend>(g, "interleaved bodies");
}

TEST_CASE("block inverse declines coupled or singular M", "[reduction]") {
  // one component larger than a rigid body (an elastic body): the factorisation does it
  const Index n = 2 * kMaxDenseInverseBlock;
  DenseMatrix tridiagonal = 4 * DenseMatrix::Identity(n, n);
  for (Index i = 0; i + 1 < n; ++i) tridiagonal(i, i + 1) = tridiagonal(i + 1, i) = -1;
  const SparseMatrix coupled = tridiagonal.sparseView();
  CHECK_FALSE(block_diagonal_inverse(SparseMap(coupled.rows(), coupled.cols(), coupled.nonZeros(),
                                               coupled.outerIndexPtr(), coupled.innerIndexPtr(),
                                               coupled.valuePtr()),
                                     true)
                  .has_value());
  // a singular body: no inverse, and the reduction reports M
  GlobalProblem g = interleaved_bodies(3, 4, true, 5);
  DenseMatrix M(g.M);
  M.row(1).setZero();
  M.col(1).setZero();
  g.M = M.sparseView();
  g.M.makeCompressed();
  CHECK_FALSE(block_diagonal_inverse(GlobalProblemView(g).M, true).has_value());
  CHECK_THROWS_AS(GlobalReduction<>(g), InvalidProblem);
}

// The semismooth Newton solvers (newton.hpp): closed-form one- and
// two-contact cases (take-off, stick, slide; 3D, 2D, frictionless), every
// FCLIB problem solved to 1e-8 (checked with the independent error of
// problem/error.hpp), superlinear local convergence on full-rank problems (from
// the recorded error sequence), 1e-12 on the full-rank global problems,
// clean failures on rank-deficient or unsolvable problems, policies
// (storages, linear solvers, line searches, rho strategies), warm start, bad
// input and the catalogue entries.
#include "test_support.hpp"

#include <fcsolve/newton.hpp>
#include "test_catalogue.hpp"

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

using namespace fcsolve;

namespace {

using fcsolve_test::make_local;

template <template <class> class F, class Cone, class Storage = DenseStorage<Cone::dim>,
          class Linear = DefaultNewtonLinearSolver<Storage>>
Vector solve_local(const LocalProblemView& p, NewtonSettings s = {}, SolverInfo* info = nullptr) {
  Newton<F, Cone, Storage, Linear> nsn(s);
  nsn.compute(p);
  Vector r = Vector::Zero(p.size()), u(p.size());
  nsn.solve(r, u);
  if (info) *info = nsn.info();
  // what the solver says is what the independent measure says (up to the
  // rounding of W r: the storages multiply in different orders)
  CHECK(nsn.info().error == Approx(local_error(p, r)).epsilon(1e-6).margin(1e-15));
  CHECK(r.allFinite());
  CHECK((u - (SparseMatrix(p.W) * r + Vector(p.q))).norm() <= 1e-12 * (1 + u.norm()));
  return r;
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

/// The observed order log(e_{k+1}/e_k) / log(e_k/e_{k-1}) of the last three
/// decreasing errors above the round-off floor (1e-13: a step that ends on
/// the floor says nothing of the order); none if there are no such three.
std::optional<double> observed_order(const std::vector<double>& e) {
  for (std::size_t k = e.size(); k-- > 2;) {
    if (e[k] > 1e-13 && e[k] < e[k - 1] && e[k - 1] < e[k - 2])
      return std::log(e[k] / e[k - 1]) / std::log(e[k - 1] / e[k - 2]);
  }
  return std::nullopt;
}

const std::set<std::string> kFullRankGlobal = {  // rank W = m (checked by SVD, see the report)
    "Box_Stacks-i0035-31-0", "CubeH8", "GFC3D_Example0", "GFC3D_Example00",
    "GFC3D_Example00_badly_scaled", "GFC3D_Example1", "GFC3D_OneContact",
    "LMGC_GlobalFrictionContactProblem00046", "Spheres-i099-356-679"};

}  // namespace

TEMPLATE_TEST_CASE("Newton: closed-form one-contact solutions (3D)", "[newton][closed-form]",
                   AlartCurnierFunction<Coulomb3D>, JeanMoreauFunction<Coulomb3D>,
                   NaturalMapFunction<Coulomb3D>, FischerBurmeisterFunction<Coulomb3D>) {
  const DenseMatrix W = Eigen::Vector3d(2, 1, 1).asDiagonal();
  const Vector mu = Vector::Constant(1, 0.5);
  auto run = [&](const Vector& q) {
    const LocalProblem p = make_local(3, W, q, mu);
    NewtonSettings s;
    s.tol = 1e-12;
    SolverInfo info;
    Vector r;
    if constexpr (std::is_same_v<TestType, AlartCurnierFunction<Coulomb3D>>)
      r = solve_local<AlartCurnierFunction, Coulomb3D>(p, s, &info);
    else if constexpr (std::is_same_v<TestType, JeanMoreauFunction<Coulomb3D>>)
      r = solve_local<JeanMoreauFunction, Coulomb3D>(p, s, &info);
    else if constexpr (std::is_same_v<TestType, NaturalMapFunction<Coulomb3D>>)
      r = solve_local<NaturalMapFunction, Coulomb3D>(p, s, &info);
    else
      r = solve_local<FischerBurmeisterFunction, Coulomb3D>(p, s, &info);
    CHECK(info.status == Status::Converged);
    CHECK(local_error(p, r) <= 1e-12);
    return r;
  };
  SECTION("take-off: q_N > 0, r = 0") {
    CHECK(run(Eigen::Vector3d(1, 0.3, -0.2)).norm() <= 1e-12);
  }
  SECTION("stick: r = -W^-1 q inside the cone, u = 0") {
    CHECK((run(Eigen::Vector3d(-2, 0.1, 0.1)) - Eigen::Vector3d(1, -0.1, -0.1)).norm() <= 1e-12);
  }
  SECTION("slide: r_N = 1, r_T = -mu r_N u_T / ||u_T||") {
    // W = diag(2,1,1), q = (-2, 3, 4): u_T = q_T + r_T = (3, 4) (1 - mu / 5)
    const Vector r = run(Eigen::Vector3d(-2, 3, 4));
    CHECK((r - Eigen::Vector3d(1, -0.3, -0.4)).norm() <= 1e-12);
  }
}

TEST_CASE("Newton: two coupled contacts, one sticking and one sliding", "[newton][closed-form]") {
  // normals coupled by [[2, 1], [1, 2]], tangents identity: with q_N = (-3, -3)
  // r_N = (1, 1), u_N = 0; contact 0 sticks (q_T = (0.1, 0)), contact 1 slides
  // (q_T = (0, 2), mu = 0.5): r_T = (0, -0.5), u_T = (0, 1.5).
  DenseMatrix W = DenseMatrix::Identity(6, 6);
  W(0, 0) = W(3, 3) = 2;
  W(0, 3) = W(3, 0) = 1;
  Vector q(6);
  q << -3, 0.1, 0, -3, 0, 2;
  const LocalProblem p = make_local(3, W, q, Vector::Constant(2, 0.5));
  Vector expected(6);
  expected << 1, -0.1, 0, 1, 0, -0.5;
  NewtonSettings s;
  s.tol = 1e-12;
  SolverInfo info;
  CHECK((solve_local<AlartCurnierFunction, Coulomb3D>(p, s, &info) - expected).norm() <= 1e-12);
  CHECK(info.converged());
  CHECK((solve_local<FischerBurmeisterFunction, Coulomb3D, SparseStorage<3>>(p, s, &info) - expected).norm() <= 1e-11);
  CHECK(info.converged());
  CHECK((solve_local<NaturalMapFunction, Coulomb3D, BlockSparseStorage<3>>(p, s, &info) - expected).norm() <= 1e-12);
  CHECK(info.converged());
}

TEST_CASE("Newton: 2D and frictionless cones through the same template", "[newton][closed-form]") {
  NewtonSettings s;
  s.tol = 1e-12;
  SolverInfo info;
  SECTION("2D slide: W = I, q = (-1, 2), mu = 0.5 -> r = (1, -0.5)") {
    const LocalProblem p = make_local(2, DenseMatrix::Identity(2, 2), Eigen::Vector2d(-1, 2), Vector::Constant(1, 0.5));
    CHECK((solve_local<AlartCurnierFunction, Coulomb2D>(p, s, &info) - Eigen::Vector2d(1, -0.5)).norm() <= 1e-12);
    CHECK(info.converged());
    CHECK((solve_local<FischerBurmeisterFunction, Coulomb2D>(p, s, &info) - Eigen::Vector2d(1, -0.5)).norm() <= 1e-10);
    CHECK(info.converged());
  }
  SECTION("frictionless LCP: W = [[2, 1], [1, 2]], q = (-3, 1) -> r = (1.5, 0)") {
    DenseMatrix W(2, 2);
    W << 2, 1, 1, 2;
    const LocalProblem p = make_local(1, W, Eigen::Vector2d(-3, 1), Vector::Zero(2));
    CHECK((solve_local<AlartCurnierFunction, Frictionless>(p, s, &info) - Eigen::Vector2d(1.5, 0)).norm() <= 1e-12);
    CHECK(info.converged());
    CHECK((solve_local<NaturalMapFunction, Frictionless, SparseStorage<1>>(p, s, &info) - Eigen::Vector2d(1.5, 0)).norm() <= 1e-12);
    CHECK(info.converged());
  }
}

TEST_CASE("Newton: every FCLIB problem to 1e-8, hybrid and plain", "[newton][fclib]") {
  std::vector<std::pair<std::string, LocalProblem>> problems;
  for (const auto& f : fcsolve_test::fclib_files("local")) problems.emplace_back(stem(f), fclib::read_local(f));
  for (const auto& f : fcsolve_test::fclib_files("global"))
    problems.emplace_back(stem(f), GlobalReduction<DefaultBackend>(fclib::read_global(f)).local());
  REQUIRE(problems.size() >= 5);
  for (const auto& [name, p] : problems) {
    INFO(name);
    NewtonSettings hybrid;
    hybrid.hybrid = true;
    hybrid.stall_window = 20;
    SolverInfo info;
    Vector r = solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>>(p, hybrid, &info);
    CHECK(info.status == Status::Converged);
    CHECK(local_error(p, r) <= 1e-8);
    // the plain formulations solve them too (measured: all 42 shared problems)
    r = solve_local<JeanMoreauFunction, Coulomb3D, SparseStorage<3>>(p, {}, &info);
    CHECK(local_error(p, r) <= 1e-8);
    r = solve_local<NaturalMapFunction, Coulomb3D, SparseStorage<3>>(p, {}, &info);
    CHECK(local_error(p, r) <= 1e-8);
    r = solve_local<FischerBurmeisterFunction, Coulomb3D, SparseStorage<3>>(p, {}, &info);
    CHECK(local_error(p, r) <= 1e-8);
  }
}

TEST_CASE("GlobalNewton: every global problem in (v, r); 1e-12 and superlinear on full rank",
          "[newton][global][fclib]") {
  int orders_measured = 0;
  for (const auto& f : fcsolve_test::fclib_files("global")) {
    const std::string name = stem(f);
    INFO(name);
    const GlobalProblem p = fclib::read_global(f);
    const bool full_rank = kFullRankGlobal.count(name) > 0;
    NewtonSettings s;
    s.tol = full_rank ? 1e-12 : 1e-8;
    s.record_history = true;
    GlobalNewton<AlartCurnierFunction, Coulomb3D> nsn(s);
    nsn.compute(p);
    Vector r = Vector::Zero(p.size()), v(p.num_dofs());
    nsn.solve(r, v);
    const GlobalErrorReport rep =
        global_error_report(p, GlobalReduction<DefaultBackend>(p, false).free_velocity_norm(), r, v);
    CHECK(nsn.info().status == Status::Converged);
    CHECK(rep.error <= s.tol);
    CHECK(nsn.info().error == Approx(rep.error).epsilon(1e-8).margin(1e-300));
    if (full_rank) {
      INFO("errors: " << Eigen::Map<const Vector>(nsn.info().history.data(), Index(nsn.info().history.size())).transpose());
      if (const auto order = observed_order(nsn.info().history)) {
        ++orders_measured;
        CHECK(*order >= 1.5);  // quadratic in practice
      }
    }
  }
  CHECK(orders_measured >= 2);  // bundled: Box_Stacks-i0035, CubeH8, GFC3D_Example1, LMGC_...
}

TEST_CASE("Newton: superlinear local convergence on a full-rank reduced problem", "[newton][fclib]") {
  const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("LMGC_GlobalFrictionContactProblem00046.hdf5"));
  const LocalProblem p = GlobalReduction<DefaultBackend>(g).local();
  NewtonSettings s;
  s.tol = 1e-14;
  s.record_history = true;
  SolverInfo info;
  solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>>(p, s, &info);
  INFO("errors: " << Eigen::Map<const Vector>(info.history.data(), Index(info.history.size())).transpose());
  CHECK(info.error <= 1e-12);
  REQUIRE(observed_order(info.history).has_value());
  CHECK(*observed_order(info.history) >= 1.5);
  solve_local<FischerBurmeisterFunction, Coulomb3D, SparseStorage<3>>(p, s, &info);
  CHECK(info.error <= 1e-12);
  REQUIRE(observed_order(info.history).has_value());
  CHECK(*observed_order(info.history) >= 1.5);
}

TEST_CASE("Newton: failures are clean statuses, never NaN, never a false convergence",
          "[newton][failure]") {
  SECTION("no solution: W = 0 and q_N < 0 (u = q whatever r)") {
    const LocalProblem p = make_local(3, DenseMatrix::Zero(6, 6),
                                      (Vector(6) << -1, 0.2, 0, -0.5, 0, 0).finished(), Vector::Constant(2, 0.3));
    for (bool hybrid : {false, true}) {
      NewtonSettings s;
      s.hybrid = hybrid;
      s.max_iter = 300;
      SolverInfo info;
      const Vector r = solve_local<AlartCurnierFunction, Coulomb3D>(p, s, &info);
      CHECK(info.status != Status::Converged);
      CHECK(std::isfinite(info.error));
      CHECK(info.error > 1e-3);
      CHECK(r.allFinite());
      solve_local<FischerBurmeisterFunction, Coulomb3D>(p, s, &info);
      CHECK(info.status != Status::Converged);
      CHECK(std::isfinite(info.error));
    }
  }
  SECTION("a rank-deficient problem with a too small budget") {
    const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
    NewtonSettings s;
    s.max_iter = 3;
    s.levenberg_marquardt = 0;  // plain Newton on a singular J
    SolverInfo info;
    const Vector r = solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>>(p, s, &info);
    CHECK((info.status == Status::MaxIterations || info.status == Status::Stalled));
    CHECK(r.allFinite());
    CHECK(info.error > s.tol);
    s.max_iter = 1000;
    s.stall_window = 5;
    s.line_search_memory = 1;
    s.nonmonotone = false;
    solve_local<NaturalMapFunction, Coulomb3D, SparseStorage<3>>(p, s, &info);
    CHECK(info.status != Status::NumericalError);
    if (info.status != Status::Converged) CHECK(info.error > s.tol);
  }
}

TEST_CASE("Newton: storages, linear solvers, line searches and rho strategies", "[newton][policies]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("BoxesStack1-i100000-32.hdf5"));
  SolverInfo info;
  SECTION("storage and linear-solver policies") {
    CHECK(local_error(p, solve_local<AlartCurnierFunction, Coulomb3D, DenseStorage<3>>(p, {}, &info)) <= 1e-8);
    CHECK(local_error(p, solve_local<AlartCurnierFunction, Coulomb3D, BlockSparseStorage<3>>(p, {}, &info)) <= 1e-8);
    CHECK(local_error(p, solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>,
                                     SparseNewtonLinearSolver<EigenBackend>>(p, {}, &info)) <= 1e-8);
    CHECK(local_error(p, solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>,
                                     SparseNewtonLinearSolver<SuiteSparseBackend>>(p, {}, &info)) <= 1e-8);
  }
  SECTION("line searches and rho strategies") {
    for (LineSearch ls : {LineSearch::GoldsteinPrice, LineSearch::Armijo, LineSearch::None})
      for (RhoStrategy rho : {RhoStrategy::SplitSpectralNorm, RhoStrategy::SpectralNorm, RhoStrategy::Adaptive}) {
        NewtonSettings s;
        s.line_search = ls;
        s.rho_strategy = rho;
        INFO("line search " << int(ls) << " rho " << int(rho));
        CHECK(local_error(p, solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>>(p, s, &info)) <= 1e-8);
      }
  }
}

#ifdef FCSOLVE_WITH_LAPACK
TEST_CASE("Newton: a half-full J is factorised dense (LAPACK), as the sparse LU would", "[newton][policies]") {
  SECTION("the linear solver on full and singular matrices held sparse") {
    const int n = 40;
    DenseMatrix A = DenseMatrix::Random(n, n);
    A.diagonal().array() += 3.0;
    const Vector b = Vector::LinSpaced(n, -1.0, 2.0);
    SparseNewtonLinearSolver<SuiteSparseBackend> dense, sparse;
    const SparseMatrix J = A.sparseView();
    REQUIRE(dense.factorize(J));
    Vector x(n);
    dense.solve(b, x);
    CHECK((A * x - b).norm() <= 1e-12 * b.norm() * A.norm());
    // a tridiagonal matrix stays with UMFPACK and gives the same x
    DenseMatrix T = DenseMatrix::Zero(n, n);
    T.diagonal() = A.diagonal();
    T.diagonal(1) = A.diagonal(1);
    T.diagonal(-1) = A.diagonal(-1);
    Vector y(n), z(n);
    const SparseMatrix Jt = T.sparseView();  // UMFPACK reads J until solve(): kept alive
    REQUIRE(sparse.factorize(Jt));
    sparse.solve(b, y);
    REQUIRE(dense.factorize(Jt));  // still the dense path: decided at analysis
    dense.solve(b, z);
    CHECK((y - z).norm() <= 1e-10 * y.norm());
    // a zero column: singular, reported as a failed factorisation
    DenseMatrix S = A;
    S.col(7).setZero();
    dense.reset();
    CHECK_FALSE(dense.factorize(SparseMatrix(S.sparseView())));
  }
  SECTION("Newton on a full W held sparse: same steps as Eigen's sparse LU") {
    const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"));
    SolverInfo lapack_info, eigen_info;
    const Vector r1 = solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>,
                                  SparseNewtonLinearSolver<SuiteSparseBackend>>(p, {}, &lapack_info);
    const Vector r2 = solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>,
                                  SparseNewtonLinearSolver<EigenBackend>>(p, {}, &eigen_info);
    CHECK(lapack_info.converged());
    CHECK(local_error(p, r1) <= 1e-8);
    CHECK(lapack_info.iterations == eigen_info.iterations);
    CHECK((r1 - r2).norm() <= 1e-8 * (1 + r2.norm()));
  }
}
#endif

#ifdef FCSOLVE_WITH_KLU
namespace {
/// An elastic body's stiffness pattern: a g^3 grid of nodes, 3 dofs each,
/// every node coupled to its 26 neighbours (diagonally dominant values).
SparseMatrix grid_stiffness(int g) {
  const int dofs = 3;
  std::vector<Eigen::Triplet<double>> t;
  const auto node = [g](int i, int j, int k) { return (i * g + j) * g + k; };
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j)
      for (int k = 0; k < g; ++k)
        for (int di = -1; di <= 1; ++di)
          for (int dj = -1; dj <= 1; ++dj)
            for (int dk = -1; dk <= 1; ++dk) {
              const int a = i + di, b = j + dj, c = k + dk;
              if (a < 0 || b < 0 || c < 0 || a >= g || b >= g || c >= g) continue;
              const bool self = !di && !dj && !dk;
              for (int p = 0; p < dofs; ++p)
                for (int q = 0; q < dofs; ++q)
                  t.emplace_back(node(i, j, k) * dofs + p, node(a, b, c) * dofs + q,
                                 self ? (p == q ? 30.0 : 1.0) : -0.1 * (1 + p));
            }
  const int n = g * g * g * dofs;
  SparseMatrix J(n, n);
  J.setFromTriplets(t.begin(), t.end());
  J.makeCompressed();
  return J;
}
}  // namespace

TEST_CASE("Newton: KLU refactorises J with its first pivot order and checks every solve", "[newton][policies]") {
  SECTION("the pattern decides the factorisation") {
    const int n = 40;
    DenseMatrix T = DenseMatrix::Zero(n, n);
    T.diagonal().setConstant(4.0);
    T.diagonal(1).setConstant(-1.0);
    T.diagonal(-1).setConstant(-1.5);
    const SparseMatrix tridiagonal = T.sparseView();
    SparseNewtonLinearSolver<SuiteSparseBackend> s;
    REQUIRE(s.factorize(tridiagonal));
    CHECK(std::string(s.path()) == "pattern");  // no fill: a left-looking LU
    const Vector b = Vector::LinSpaced(n, -1.0, 2.0);
    Vector x(n);
    s.solve(b, x);
    CHECK((T * x - b).norm() <= 1e-13 * b.norm());
    // an elastic body's stiffness fills in dense fronts: UMFPACK
    const SparseMatrix K = grid_stiffness(8);
    s.reset();
    REQUIRE(s.factorize(K));
    CHECK(std::string(s.path()) == "general");
    const Vector c = Vector::LinSpaced(K.rows(), 1.0, -3.0);
    Vector y(K.rows());
    s.solve(c, y);
    CHECK((K * y - c).norm() <= 1e-12 * c.norm());
#ifdef FCSOLVE_WITH_LAPACK
    DenseMatrix A = DenseMatrix::Random(n, n);
    A.diagonal().array() += 3.0;
    s.reset();
    REQUIRE(s.factorize(SparseMatrix(A.sparseView())));
    CHECK(std::string(s.path()) == "dense");
#endif
  }
  SECTION("a pivot order gone bad is caught by the solve's backward error") {
    // [[a, 1, 2], [3, 1, 1], [1, 2, 1]]; with a = 1 KLU keeps the diagonal
    // pivots. With a = 1e-14, reusing that order divides by 1e-14 (growth
    // 1e14): the solve's backward error is ~1e-3 and still ~1e-5 after a
    // refinement step, so the solve must factorise afresh with partial
    // pivoting (a = 1e-18 would not do: the reused order meets an exact
    // zero pivot, and the refactorisation reports it).
    const auto matrix = [](double a) {
      DenseMatrix A(3, 3);
      A << a, 1.0, 2.0, 3.0, 1.0, 1.0, 1.0, 2.0, 1.0;
      return A;
    };
    const DenseMatrix A = matrix(1.0);
    KluPatternLU lu;
    const SparseMatrix J1 = A.sparseView();
    REQUIRE(lu.factorize(J1));
    const Vector b = (Vector(3) << 1.0, 2.0, 3.0).finished();
    Vector x(3);
    lu.solve(b, x);
    CHECK((A * x - b).norm() <= 1e-14 * b.norm());
    CHECK(lu.fresh_factorisations() == 1);
    CHECK(lu.pivoted_factorisations() == 0);
    const DenseMatrix B = matrix(1e-14);
    const SparseMatrix J2 = B.sparseView(1.0, 0.0);  // keep the tiny entry: same pattern
    REQUIRE(J2.nonZeros() == 9);
    REQUIRE(lu.factorize(J2));
    lu.solve(b, x);
    CHECK((B * x - b).norm() <= 1e-14 * b.norm());
    CHECK(lu.fresh_factorisations() == 2);
    CHECK(lu.pivoted_factorisations() == 1);
    // a matrix of the pattern that suits the new pivot order (rows 2, 1, 3)
    // is refactorised, not factorised
    const DenseMatrix C = matrix(2.0);
    const SparseMatrix J3 = C.sparseView();
    REQUIRE(lu.factorize(J3));
    lu.solve(b, x);
    CHECK((C * x - b).norm() <= 1e-14 * b.norm());
    CHECK(lu.fresh_factorisations() == 2);
  }
  SECTION("a fresh factorisation keeps AMD's diagonal pivots where they are not tiny") {
    // A block arrow, the shape of a Newton matrix whose contact rows have
    // small pivots: 200 unknowns with diagonal 1e-4, each coupled to two of
    // 20 border unknowns (diagonal 1). Every small pivot is below 1e-3 of
    // its column, so KLU's default pivoting swaps border rows up and adds
    // half again to the factors AMD predicted; the diagonal pivots fill
    // only what AMD predicted, and the solve (checked, refined once here:
    // growth 1e4) is accurate.
    const int n = 200, k = 20;
    DenseMatrix A = DenseMatrix::Zero(n + k, n + k);
    A.diagonal().head(n).setConstant(1e-4);
    A.diagonal().tail(k).setOnes();
    for (int i = 0; i < n; ++i)
      for (const int j : {i % k, (7 * i + 3 + i / k) % k}) A(i, n + j) = A(n + j, i) = 1.0;
    const SparseMatrix J = A.sparseView();
    KluPatternLU lu;
    REQUIRE(lu.factorize(J));
    const Vector b = Vector::LinSpaced(n + k, 1.0, -2.0);
    Vector x(n + k);
    lu.solve(b, x);
    const double backward = (A * x - b).lpNorm<Eigen::Infinity>() /
                            (A.cwiseAbs().rowwise().sum().maxCoeff() * x.lpNorm<Eigen::Infinity>() +
                             b.lpNorm<Eigen::Infinity>());
    CHECK(backward <= kRefactorBackwardError);
    CHECK(lu.fill_over_prediction() <= 1.0);
    CHECK(lu.pivoted_factorisations() == 0);
    // the case is real: KLU with its default pivot tolerance fills it
    klu_common common;
    klu_defaults(&common);
    REQUIRE(common.tol == kPartialPivotTolerance);
    SparseMatrix K = J;
    klu_symbolic* symbolic = klu_analyze(n + k, K.outerIndexPtr(), K.innerIndexPtr(), &common);
    REQUIRE(symbolic);
    klu_numeric* numeric = klu_factor(K.outerIndexPtr(), K.innerIndexPtr(), K.valuePtr(), symbolic, &common);
    REQUIRE(numeric);
    CHECK(common.noffdiag > 0);
    CHECK(double(numeric->lnz + numeric->unz) > 1.5 * (symbolic->lnz + symbolic->unz));
    klu_free_numeric(&numeric, &common);
    klu_free_symbolic(&symbolic, &common);
  }
  SECTION("a singular J is reported, and the next one factorised afresh") {
    DenseMatrix A = DenseMatrix::Zero(3, 3);
    A << 2, 1, 0, 1, 2, 1, 0, 1, 2;
    const SparseMatrix J1 = A.sparseView();
    KluPatternLU lu;
    REQUIRE(lu.factorize(J1));
    DenseMatrix S = A;
    S.row(1) = S.row(0) + S.row(2);  // same pattern, rank 2
    SparseMatrix J2 = A.sparseView();
    for (Index j = 0; j < J2.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(J2, j); it; ++it) it.valueRef() = S(it.row(), j);
    CHECK_FALSE(lu.factorize(J2));
    REQUIRE(lu.factorize(J1));
    const Vector b = Vector::Ones(3);
    Vector x(3);
    lu.solve(b, x);
    CHECK((A * x - b).norm() <= 1e-14);
  }
  SECTION("Newton takes the same steps with KLU as with Eigen's sparse LU") {
    const LocalProblem p = fclib::read_local(fcsolve_test::bundled("BoxesStack1-i100000-32.hdf5"));
    SolverInfo klu_info, eigen_info;
    const Vector r1 = solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>,
                                  SparseNewtonLinearSolver<SuiteSparseBackend>>(p, {}, &klu_info);
    const Vector r2 = solve_local<AlartCurnierFunction, Coulomb3D, SparseStorage<3>,
                                  SparseNewtonLinearSolver<EigenBackend>>(p, {}, &eigen_info);
    CHECK(klu_info.converged());
    CHECK(local_error(p, r1) <= 1e-8);
    CHECK(klu_info.iterations == eigen_info.iterations);
  }
}
#endif

TEST_CASE("Newton: warm start, callback, history and bad input", "[newton][api]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Confeti-ex03-Fc3D-SBM.hdf5"));
  Newton<AlartCurnierFunction, Coulomb3D> nsn;
  nsn.settings().record_history = true;
  Vector r = Vector::Zero(p.size()), u(p.size());
  CHECK_THROWS_AS(nsn.solve(r, u), UsageError);
  nsn.compute(p);
  REQUIRE(nsn.solve(r, u).converged());
  const int cold = nsn.info().iterations;
  CHECK(int(nsn.info().history.size()) == cold);
  CHECK(nsn.counters().factorisations >= cold);
  SECTION("a converged warm start costs no iteration; a perturbed one fewer than cold") {
    nsn.solve(r, u);
    CHECK(nsn.info().converged());
    CHECK(nsn.info().iterations == 0);
    r *= 1.01;
    nsn.solve(r, u);
    CHECK(nsn.info().converged());
    CHECK(nsn.info().iterations < cold);
  }
  SECTION("the callback stops the solve") {
    nsn.settings().callback = [](const IterationInfo& it) { return it.iteration >= 2; };
    r.setZero();
    nsn.solve(r, u);
    CHECK(nsn.info().status == Status::Stopped);
    CHECK(nsn.info().iterations == 2);
  }
  SECTION("bad input is a typed exception") {
    Vector short_r = Vector::Zero(3);
    CHECK_THROWS_AS(nsn.solve(short_r, u), InvalidProblem);
    Vector bad = Vector::Zero(p.size());
    bad[0] = std::nan("");
    CHECK_THROWS_AS(nsn.solve(bad, u), InvalidProblem);
    const LocalProblem two_d = make_local(2, DenseMatrix::Identity(2, 2), Eigen::Vector2d(-1, 0), Vector::Constant(1, 0.3));
    CHECK_THROWS_AS(nsn.compute(two_d), InvalidProblem);
    GlobalProblem g = fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"));
    g.G = SparseMatrix(g.num_dofs(), 1);
    g.G.insert(0, 0) = 1;
    g.G.makeCompressed();
    g.b = Vector::Zero(1);
    GlobalNewton<AlartCurnierFunction, Coulomb3D> global;
    CHECK_THROWS_AS(global.compute(g), UsageError);
  }
}

TEST_CASE("Newton catalogue entries solve through the registry", "[newton][catalogue]") {
  std::set<std::string> names;
  for (const auto& e : fcsolve_test::catalogue_entries())
    if (e.family == "newton") names.insert(e.name);
  for (const char* n : {"nsn-ac", "nsn-jm", "nsn-nm", "nsn-fb", "nsn-ac-hybrid", "nsn-ac-global",
                        "nsn-jm-global", "nsn-nm-global", "nsn-fb-global"})
    CHECK(names.count(n) == 1);
  const LocalProblem local = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  const GlobalProblem global = fclib::read_global(fcsolve_test::bundled("Box_Stacks-i0035-31-0.hdf5"));
  for (const char* n : {"nsn-ac", "nsn-jm", "nsn-nm", "nsn-fb", "nsn-ac-hybrid"}) {
    INFO(n);
    const auto& e = fcsolve_test::catalogue_find(n);
    registry::SolveRequest req = registry::make_request(e);
    const auto out = registry::solve(local, e, req);
    CHECK(out.info.converged());
    CHECK(local_error(local, out.r) <= 1e-8);
    const auto g = registry::solve(GlobalProblemView(global), e, req);  // by reduction
    CHECK(g.info.converged());
  }
  for (const char* n : {"nsn-ac-global", "nsn-fb-global"}) {
    INFO(n);
    const auto& e = fcsolve_test::catalogue_find(n);
    registry::SolveRequest req = registry::make_request(e);
    req.settings.set_text("line_search", "armijo");
    const auto out = registry::solve(GlobalProblemView(global), e, req);
    CHECK(out.info.converged());
    CHECK(out.v.size() == global.num_dofs());
    CHECK_THROWS_AS(registry::solve(local, e, req), UsageError);  // global-only entry
  }
  SECTION("bilateral constraints: the global entries go through the reduction") {
    GlobalProblem g = fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"));
    g.G = SparseMatrix(g.num_dofs(), 1);
    g.G.insert(1, 0) = 1;  // v_1 = 0
    g.G.makeCompressed();
    g.b = Vector::Zero(1);
    const auto& e = fcsolve_test::catalogue_find("nsn-ac-global");
    const auto out = registry::solve(GlobalProblemView(g), e, registry::make_request(e));
    CHECK(out.info.converged());
    CHECK(std::abs(out.v[1]) <= 1e-12);
    CHECK(out.lambda.size() == 1);
  }
  registry::SolveRequest req = registry::make_request(fcsolve_test::catalogue_find("nsn-ac"));
  CHECK_THROWS_AS(req.settings.set_text("rho_strategy", "magic"), UsageError);
}

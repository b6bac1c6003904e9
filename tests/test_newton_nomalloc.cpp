// Proves that the Newton iterations (also inside the proximal point
// method, ppa.hpp) allocate nothing outside the
// factorisation of the Newton matrix: this file is compiled with
// EIGEN_RUNTIME_NO_MALLOC and an eigen_assert that throws, so any Eigen heap
// allocation between FCSOLVE_NO_MALLOC_BEGIN/END (Jacobian assembly, line
// search, velocity and G updates, error, fallback sweeps) fails the test, in
// release builds too.
#include "throwing_eigen_assert.hpp"  // first: before Eigen

#include "test_support.hpp"

#include <fcsolve/newton.hpp>
#include <fcsolve/ppa.hpp>

#include <catch2/catch.hpp>

using namespace fcsolve;

TEST_CASE("Newton iterations allocate nothing outside the factorisation", "[newton][nomalloc]") {
  const LocalProblem boxes = fclib::read_local(fcsolve_test::bundled("BoxesStack1-i100000-32.hdf5"));
  const LocalProblem rover = fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"));
  Vector r, u;
  SECTION("reduced form, sparse storage, AC and the hybrid's Gauss-Seidel sweeps") {
    Newton<AlartCurnierFunction, Coulomb3D, SparseStorage<3>> nsn;
    nsn.compute(boxes);
    r = Vector::Zero(boxes.size());
    u.resize(boxes.size());
    CHECK_NOTHROW(nsn.solve(r, u));
    CHECK(nsn.info().converged());
    // a crippled Newton stalls at once, so the sweeps run
    nsn.settings().hybrid = true;
    nsn.settings().stall_window = 2;
    nsn.settings().levenberg_marquardt = 0;
    nsn.settings().line_search_memory = 1;
    nsn.settings().nonmonotone = false;
    nsn.settings().max_iter = 200;
    r.setZero();
    CHECK_NOTHROW(nsn.solve(r, u));
    CHECK(nsn.counters().sweeps > 0);
  }
  SECTION("reduced form, dense storage, Fischer-Burmeister") {
    Newton<FischerBurmeisterFunction, Coulomb3D, DenseStorage<3>> nsn;
    nsn.compute(rover);
    r = Vector::Zero(rover.size());
    u.resize(rover.size());
    CHECK_NOTHROW(nsn.solve(r, u));
    CHECK(nsn.info().converged());
  }
  SECTION("global form") {
    const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("Box_Stacks-i0035-31-0.hdf5"));
    GlobalNewton<NaturalMapFunction, Coulomb3D> nsn;
    nsn.compute(g);
    r = Vector::Zero(g.size());
    Vector v(g.num_dofs());
    CHECK_NOTHROW(nsn.solve(r, v));
    CHECK(nsn.info().converged());
    // with a contact compliance (ppa-global's subproblem)
    nsn.set_compliance(nsn.lumped_diagonal_mean());
    r.setZero();
    CHECK_NOTHROW(nsn.solve(r, v));
    CHECK(nsn.info().converged());
  }
}

TEST_CASE("ppa: the outer updates and the inner Newton iterations allocate nothing",
          "[ppa][nomalloc]") {
  // the inner solver's compute() or set_compliance() (once per subproblem)
  // may allocate; the outer updates (alpha, shifted q or w, error, step) and
  // the inner iterations run between FCSOLVE_NO_MALLOC_BEGIN/END
  auto check = [](auto& ppa, const auto& problem, Vector& r, Vector& second) {
    ppa.compute(problem);
    r = Vector::Zero(problem.size());
    CHECK_NOTHROW(ppa.solve(r, second));
    CHECK(ppa.info().converged());
    CHECK(ppa.info().iterations > 1);
  };
  Vector r, second;
  SECTION("reduced form") {
    const LocalProblem boxes = fclib::read_local(fcsolve_test::bundled("BoxesStack1-i100000-32.hdf5"));
    ProximalPoint<Coulomb3D> ppa;
    second.resize(boxes.size());
    check(ppa, boxes, r, second);
  }
  SECTION("global form (ppa-global: w - alpha r_k and a contact compliance)") {
    const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("Box_Stacks-i0035-31-0.hdf5"));
    ProximalPointGlobal<Coulomb3D> ppa;
    second.resize(g.num_dofs());
    check(ppa, g, r, second);
  }
}

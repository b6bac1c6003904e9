// Proves that the NSGS sweep allocates nothing: this file is compiled with
// EIGEN_RUNTIME_NO_MALLOC and an eigen_assert that throws, so any Eigen heap
// allocation between FCSOLVE_NO_MALLOC_BEGIN/END (the sweeps and the error
// evaluations of Nsgs::solve) fails the test, in release builds too.
#include "throwing_eigen_assert.hpp"  // first: before Eigen

#include "test_support.hpp"

#include <fcsolve/nsgs.hpp>

#include <catch2/catch.hpp>

using namespace fcsolve;

namespace {

template <class Storage, class Local>
void solve_without_allocation(const LocalProblem& p, ContactOrdering ordering, double omega) {
  Nsgs<Coulomb3D, Storage, Local> nsgs;
  nsgs.settings().max_iter = 300;
  nsgs.settings().ordering = ordering;
  nsgs.settings().omega = omega;
  nsgs.settings().freezing = 5;
  nsgs.settings().threads = 2;  // used by the coloured ordering only
  nsgs.compute(p);
  Vector r = Vector::Zero(p.size()), u(p.size());
  REQUIRE_NOTHROW(nsgs.solve(r, u));
  CHECK(nsgs.info().iterations > 0);
  CHECK(nsgs.info().error == Approx(local_error(p, r)).epsilon(1e-6));
}

}  // namespace

TEST_CASE("the no-malloc guard is active in this build", "[nsgs][nomalloc]") {
  FCSOLVE_NO_MALLOC_BEGIN();
  CHECK_THROWS_AS(Vector(1000), std::logic_error);
  FCSOLVE_NO_MALLOC_END();
  CHECK_NOTHROW(Vector(1000));
}

TEST_CASE("nsgs sweeps do not allocate", "[nsgs][nomalloc]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  const LocalProblem small = fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"));
  using E = local::Enumerative<Coulomb3D>;
  using P = local::Projection<Coulomb3D>;
  using PI = local::ProjectionIterative<Coulomb3D>;
  for (auto o : {ContactOrdering::Natural, ContactOrdering::ShuffledEachSweep,
                 ContactOrdering::Coloured, ContactOrdering::LoadAscending}) {
    solve_without_allocation<BlockSparseStorage<3>, E>(p, o, 1.0);
    solve_without_allocation<SparseStorage<3>, E>(p, o, 0.9);
    solve_without_allocation<DenseStorage<3>, E>(small, o, 1.1);
    solve_without_allocation<BlockSparseStorage<3>, P>(p, o, 1.0);
    solve_without_allocation<BlockSparseStorage<3>, PI>(p, o, 1.0);
    solve_without_allocation<BlockSparseStorage<3>, local::AlartCurnierNewton<Coulomb3D>>(p, o, 1.0);
    solve_without_allocation<BlockSparseStorage<3>, local::FischerBurmeisterNewton<Coulomb3D>>(p, o, 1.0);
    solve_without_allocation<BlockSparseStorage<3>, local::Hybrid<Coulomb3D>>(p, o, 1.0);
  }
  E::Settings reference;  // the full enumeration (companion matrix) too
  reference.newton_first = false;
  Nsgs<Coulomb3D, BlockSparseStorage<3>, E> nsgs;
  nsgs.settings().local = reference;
  nsgs.settings().max_iter = 20;
  nsgs.compute(p);
  Vector r = Vector::Zero(p.size()), u(p.size());
  REQUIRE_NOTHROW(nsgs.solve(r, u));
}

TEST_CASE("nsgs extrapolation: fewer sweeps, the same quality, no allocation", "[nsgs][nomalloc]") {
  // Rover1039: 4 coupled contacts whose sweeps shrink the change by a steady
  // factor, where the Aitken step is taken (19 sweeps without it, 14 with).
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"));
  const auto sweeps = [&](auto storage, ContactOrdering ordering, bool extrapolate) {
    Nsgs<Coulomb3D, decltype(storage)> nsgs;
    nsgs.settings().ordering = ordering;
    nsgs.settings().extrapolate = extrapolate;
    nsgs.compute(p);
    Vector r = Vector::Zero(p.size()), u(p.size());
    REQUIRE_NOTHROW(nsgs.solve(r, u));
    REQUIRE(nsgs.info().converged());
    CHECK(local_error(p, r) <= nsgs.settings().tol);
    CHECK(nsgs.info().error == Approx(local_error(p, r)).epsilon(1e-6));
    return nsgs.info().iterations;
  };
  for (auto o : {ContactOrdering::Natural, ContactOrdering::Coloured}) {
    CHECK(sweeps(DenseStorage<3>(), o, true) < sweeps(DenseStorage<3>(), o, false));
    // u kept by column updates, and the coloured slot layout, follow the step
    CHECK(sweeps(SparseStorage<3>(), o, true) < sweeps(SparseStorage<3>(), o, false));
    CHECK(sweeps(BlockSparseStorage<3>(), o, true) < sweeps(BlockSparseStorage<3>(), o, false));
  }
}

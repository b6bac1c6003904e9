// The coloured (parallel) NSGS sweep: the colouring is valid, the sweep
// reaches tol on every bundled FCLIB local problem (independent error), on
// 2D and frictionless problems, gives bitwise the same iterates for any
// number of threads, and keeps the warm start, budgets and catalogue entry.
#include "test_support.hpp"

#include <fcsolve/problem/error.hpp>
#include <fcsolve/nsgs.hpp>
#include "test_catalogue.hpp"

#include <catch2/catch.hpp>

#include <random>
#include <set>
#include <utility>

using namespace fcsolve;

namespace {

using Local3 = local::Enumerative<Coulomb3D>;
template <class Storage>
using Nsgs3 = Nsgs<Coulomb3D, Storage, Local3>;

/// Contacts coupled along random edges (about `degree` per contact): W is
/// symmetric with random off-diagonal blocks and a diagonal that dominates
/// them (positive definite by Gershgorin), q pushes into the contacts.
LocalProblem random_graph_problem(int d, Index nc, double degree, double mu, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> entry(-0.3, 0.3);
  std::uniform_int_distribution<Index> contact(0, nc - 1);
  std::vector<Eigen::Triplet<double>> t;
  Vector row_sum = Vector::Zero(d * nc);
  for (Index e = 0; e < Index(degree * double(nc) / 2); ++e) {
    const Index a = contact(gen), b = contact(gen);
    if (a == b) continue;
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) {
        const double w = entry(gen);
        t.emplace_back(a * d + i, b * d + j, w);
        t.emplace_back(b * d + j, a * d + i, w);
        row_sum[a * d + i] += std::abs(w);
        row_sum[b * d + j] += std::abs(w);
      }
  }
  for (Index i = 0; i < d * nc; ++i) t.emplace_back(i, i, 1 + row_sum[i]);
  LocalProblem p;
  p.d = d;
  p.W.resize(d * nc, d * nc);
  p.W.setFromTriplets(t.begin(), t.end());  // sums repeated edges: still dominant
  p.W.makeCompressed();
  std::normal_distribution<double> normal;
  p.q.resize(d * nc);
  for (Index i = 0; i < d * nc; ++i) p.q[i] = normal(gen) - (i % d == 0 ? 0.5 : 0.0);
  p.mu = Vector::Constant(nc, mu);
  return p;
}

/// Checks the colouring against W itself: every contact once, and no
/// stored entry of W couples two contacts of one colour.
void check_colouring(const LocalProblem& p, const ContactColouring& c) {
  const Index nc = p.num_contacts();
  std::vector<Index> colour(static_cast<std::size_t>(nc), -1);
  REQUIRE(c.start.front() == 0);
  REQUIRE(c.start.back() == nc);
  for (Index k = 0; k < c.num_colours(); ++k) {
    CHECK(c.start[k] < c.start[k + 1]);  // no empty colour
    for (Index i = c.start[k]; i < c.start[k + 1]; ++i) {
      REQUIRE(colour[c.contacts[i]] == -1);
      colour[c.contacts[i]] = k;
    }
  }
  std::vector<std::set<Index>> neighbours(static_cast<std::size_t>(nc));
  for (Index j = 0; j < p.W.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(p.W, j); it; ++it) {
      const Index a = it.row() / p.d, b = j / p.d;
      if (a == b) continue;
      CHECK(colour[a] != colour[b]);
      neighbours[a].insert(b);
      neighbours[b].insert(a);
    }
  std::size_t max_degree = 0;
  for (const auto& n : neighbours) max_degree = std::max(max_degree, n.size());
  CHECK(c.num_colours() <= Index(max_degree) + 1);  // greedy's bound
}

template <class Solver>
Vector solve_from_zero(Solver& solver, const LocalProblem& p) {
  solver.compute(p);
  Vector r = Vector::Zero(p.size()), u(p.size());
  solver.solve(r, u);
  const Vector u_ref = p.W * r + p.q;
  CHECK((u - u_ref).norm() <= 1e-10 * std::max(1.0, u_ref.norm()));
  return r;
}

template <class Settings>
void set_coloured(Settings& s, int threads) {
  s.ordering = ContactOrdering::Coloured;
  s.threads = threads;
}

}  // namespace

TEST_CASE("the contact colouring is valid", "[nsgs][coloured]") {
  for (const auto& f : fcsolve_test::bundled_files("local")) {
    INFO(f);
    const LocalProblem p = fclib::read_local(f);
    check_colouring(p, colour_contacts(LocalProblemView(p).W, p.d));
  }
  for (int d : {1, 2, 3}) {
    const LocalProblem p = random_graph_problem(d, 300, 6, 0.3, unsigned(d));
    const ContactColouring c = colour_contacts(LocalProblemView(p).W, d);
    check_colouring(p, c);
    CHECK(c.num_colours() >= 3);  // a random graph of degree ~6 is not bipartite
  }
  SECTION("a block-diagonal W is one colour") {
    LocalProblem p = random_graph_problem(3, 10, 0, 0.3, 5);
    CHECK(colour_contacts(LocalProblemView(p).W, 3).num_colours() == 1);
  }
}

TEST_CASE("coloured nsgs reaches tol on every bundled local problem (independent error)",
          "[nsgs][coloured][fclib]") {
  for (const auto& f : fcsolve_test::bundled_files("local")) {
    INFO(f);
    const LocalProblem p = fclib::read_local(f);
    Nsgs3<BlockSparseStorage<3>> nsgs;
    set_coloured(nsgs.settings(), 2);
    nsgs.settings().tol = 1e-6;
    nsgs.settings().max_iter = 40000;
    const Vector r = solve_from_zero(nsgs, p);
    const double error = local_error(p, r);
    CHECK(error == Approx(nsgs.info().error).epsilon(1e-6));
    if (nsgs.info().converged()) CHECK(error <= 1e-6);  // never a false claim
    if (f.find("BoxesStack") != std::string::npos)
      CHECK(error <= 1e-4);  // rigid stacks: ~1e5 sweeps to 1e-6 (test_nsgs.cpp)
    else
      CHECK(nsgs.info().converged());
  }
}

TEST_CASE("coloured nsgs gives the same iterates for any number of threads",
          "[nsgs][coloured]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  const auto run = [&](auto solver, int threads, int freezing, double omega, int max_iter) {
    set_coloured(solver.settings(), threads);
    solver.settings().freezing = freezing;
    solver.settings().omega = omega;
    solver.settings().tol = max_iter < 1000 ? 1e-300 : 1e-8;  // a fixed number of sweeps, or tol
    solver.settings().max_iter = max_iter;
    const Vector r = solve_from_zero(solver, p);
    return std::make_pair(r, solver.info());
  };
  for (const auto& [freezing, omega] : {std::pair{0, 1.0}, std::pair{10, 1.3}}) {
    INFO("freezing " << freezing << ", omega " << omega);
    const auto [r1, info1] = run(Nsgs3<BlockSparseStorage<3>>(), 1, freezing, omega, 60);
    for (int threads : {2, 3}) {
      const auto [r, info] = run(Nsgs3<BlockSparseStorage<3>>(), threads, freezing, omega, 60);
      CHECK(r == r1);  // bitwise
      CHECK(info.error == info1.error);
    }
    // column updates of u: the same iterates up to the order of the sums
    const auto [rs, infos] = run(Nsgs3<SparseStorage<3>>(), 2, freezing, omega, 60);
    CHECK((rs - r1).norm() <= 1e-10 * r1.norm());
    // to convergence: the same number of sweeps
    const auto [c1, cinfo1] = run(Nsgs3<BlockSparseStorage<3>>(), 1, freezing, omega, 100000);
    const auto [c2, cinfo2] = run(Nsgs3<BlockSparseStorage<3>>(), 2, freezing, omega, 100000);
    REQUIRE(cinfo1.converged());
    CHECK(c1 == c2);
    CHECK(cinfo1.iterations == cinfo2.iterations);
    CHECK(local_error(p, c2) <= 1e-8);
  }
  SECTION("dense storage runs the colours serially, with the same iterates") {
    const LocalProblem small = random_graph_problem(3, 14, 4, 0.5, 9);
    Nsgs3<DenseStorage<3>> dense;
    Nsgs3<BlockSparseStorage<3>> block;
    for (auto* s : {&dense.settings(), &block.settings()}) {
      set_coloured(*s, 2);
      s->tol = 1e-300;
      s->max_iter = 30;
    }
    const Vector rd = solve_from_zero(dense, small), rb = solve_from_zero(block, small);
    CHECK((rd - rb).norm() <= 1e-12 * rb.norm());
  }
}

TEST_CASE("natural ordering ignores threads", "[nsgs][coloured]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  Nsgs3<BlockSparseStorage<3>> one, two;
  two.settings().threads = 2;
  const Vector r1 = solve_from_zero(one, p), r2 = solve_from_zero(two, p);
  CHECK(r1 == r2);
  CHECK(one.info().iterations == two.info().iterations);
}

TEST_CASE("coloured nsgs on 2D and frictionless problems", "[nsgs][coloured]") {
  // Solves p with 2 threads to the default tol; returns r and the colouring's size.
  const auto solve_to_tol = [](auto nsgs, const LocalProblem& p) {
    set_coloured(nsgs.settings(), 2);
    const Vector r = solve_from_zero(nsgs, p);
    REQUIRE(nsgs.info().converged());
    CHECK(local_error(p, r) <= 1e-8);
    return std::make_pair(r, nsgs.colouring().num_colours());
  };
  SECTION("2D Coulomb") {
    const LocalProblem p = random_graph_problem(2, 200, 5, 0.4, 11);
    const auto [r, colours] =
        solve_to_tol(Nsgs<Coulomb2D, BlockSparseStorage<2>, local::Enumerative<Coulomb2D>>(), p);
    CHECK(colours >= 3);
  }
  SECTION("frictionless (an LCP)") {
    const LocalProblem p = random_graph_problem(1, 300, 5, 0.0, 12);
    const auto [r, colours] =
        solve_to_tol(Nsgs<Frictionless, BlockSparseStorage<1>, local::Projection<Frictionless>>(), p);
    CHECK(r.minCoeff() >= 0);
    CHECK(colours >= 3);
  }
}

TEST_CASE("coloured nsgs: warm start, budgets, stall and the catalogue", "[nsgs][coloured]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  Nsgs3<BlockSparseStorage<3>> nsgs;
  set_coloured(nsgs.settings(), 2);
  nsgs.settings().tol = 1e-8;
  nsgs.settings().max_iter = 100000;
  nsgs.compute(p);
  Vector r = Vector::Zero(p.size()), u(p.size());
  SECTION("warm start from a solution: at most 2 sweeps") {
    nsgs.solve(r, u);
    REQUIRE(nsgs.info().converged());
    nsgs.solve(r, u);
    CHECK(nsgs.info().converged());
    CHECK(nsgs.info().iterations <= 2);
    CHECK(local_error(p, r) <= 1e-8);
  }
  SECTION("time budget") {
    nsgs.settings().max_time = 0;
    nsgs.solve(r, u);
    CHECK(nsgs.info().status == Status::TimeLimit);
    CHECK(nsgs.info().iterations == 1);
    CHECK(nsgs.info().error == Approx(local_error(p, r)).epsilon(1e-10));
  }
  SECTION("no progress: the colours are reshuffled, reproducibly") {
    nsgs.settings().stall_sweeps = 1;
    nsgs.settings().error_every = 1;
    nsgs.settings().max_iter = 200;
    Vector r2 = r;
    nsgs.solve(r, u);
    CHECK(nsgs.info().message.find("colours reshuffled") != std::string::npos);
    nsgs.settings().threads = 1;
    nsgs.solve(r2, u);
    CHECK(r == r2);
  }
  SECTION("the catalogue's nsgs entry") {
    const LocalProblem q = fclib::read_local(fcsolve_test::bundled("OneObject-i1028-138.hdf5"));
    registry::SolveRequest req = registry::make_request(fcsolve_test::catalogue_find("nsgs"));
    req.common.tol = 1e-7;
    req.settings.set_text("ordering", "coloured");
    req.settings.set_text("threads", "2");
    const registry::SolveOutcome out = fcsolve_test::solve_named(LocalProblemView(q), "nsgs", req);
    CHECK(out.info.converged());
    CHECK(local_error(q, out.r) <= 1e-7);
  }
  SECTION("threads < 1 is a usage error") {
    nsgs.settings().threads = 0;
    CHECK_THROWS_AS(nsgs.solve(r, u), UsageError);
  }
}

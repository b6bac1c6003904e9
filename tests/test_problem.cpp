// Problem model: views do not copy, validation rejects each malformed input
// with an InvalidProblem naming the field, asymmetry is measured not assumed.
#include "test_support.hpp"

#include <fcsolve/problem/summary.hpp>
#include <fcsolve/problem/validate.hpp>

#include <catch2/catch.hpp>

#include <limits>

using namespace fcsolve;

namespace {

LocalProblem two_contacts() {
  LocalProblem p;
  p.d = 3;
  DenseMatrix W = DenseMatrix::Identity(6, 6) * 2.0;
  W(0, 3) = W(3, 0) = 0.5;
  p.W = W.sparseView();
  p.W.makeCompressed();
  p.q = Vector::LinSpaced(6, -1, 1);
  p.mu = Vector::Constant(2, 0.3);
  return p;
}

GlobalProblem small_global() {
  GlobalProblem g;
  g.d = 3;
  g.M = DenseMatrix(DenseMatrix::Identity(4, 4) * 3.0).sparseView();
  DenseMatrix H = DenseMatrix::Zero(4, 3);
  H.topRows(3) = DenseMatrix::Identity(3, 3);
  H(3, 0) = 1.0;
  g.H = H.sparseView();
  g.f = Vector::Constant(4, -1.0);
  g.w = Vector::Zero(3);
  g.mu = Vector::Constant(1, 0.5);
  g.M.makeCompressed();
  g.H.makeCompressed();
  return g;
}

/// Runs validate() and returns the field named by the InvalidProblem.
template <class P>
std::string rejected_field(const P& p) {
  try {
    validate(p);
  } catch (const InvalidProblem& e) {
    return e.field();
  }
  return "<accepted>";
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

}  // namespace

TEST_CASE("a view maps the problem's arrays without copying", "[problem]") {
  const LocalProblem p = two_contacts();
  const LocalProblemView v(p);
  CHECK(v.W.valuePtr() == p.W.valuePtr());
  CHECK(v.q.data() == p.q.data());
  CHECK(v.mu.data() == p.mu.data());
  CHECK(v.num_contacts() == 2);
  const GlobalProblem g = small_global();
  const GlobalProblemView gv(g);
  CHECK(gv.M.valuePtr() == g.M.valuePtr());
  CHECK(gv.f.data() == g.f.data());
  CHECK_FALSE(gv.has_bilateral());
}

TEST_CASE("valid problems pass validation", "[problem]") {
  CHECK(rejected_field(two_contacts()) == "<accepted>");
  CHECK(rejected_field(small_global()) == "<accepted>");
}

TEST_CASE("local validation: one case per rejected input", "[problem][bad-input]") {
  LocalProblem p = two_contacts();
  SECTION("contact dimension") { p.d = 4; CHECK(rejected_field(p) == "spacedim"); }
  SECTION("empty problem") {
    p.q.resize(0);
    p.mu.resize(0);
    p.W.resize(0, 0);
    p.W.makeCompressed();
    CHECK(rejected_field(p) == "W");  // the matrix sets the size
  }
  SECTION("m not a multiple of d") { p.q.resize(5); CHECK(rejected_field(p) == "q"); }
  SECTION("mu size") { p.mu.resize(3); p.mu.setConstant(0.1); CHECK(rejected_field(p) == "mu"); }
  SECTION("W shape") {
    p.W.conservativeResize(6, 5);
    p.W.makeCompressed();
    CHECK(rejected_field(p) == "W");
  }
  SECTION("NaN in W") { p.W.coeffRef(1, 1) = kNaN; CHECK(rejected_field(p) == "W"); }
  SECTION("Inf in q") { p.q[2] = kInf; CHECK(rejected_field(p) == "q"); }
  SECTION("NaN in mu") { p.mu[1] = kNaN; CHECK(rejected_field(p) == "mu"); }
  SECTION("negative mu") { p.mu[0] = -0.1; CHECK(rejected_field(p) == "mu"); }
  SECTION("uncompressed W") {
    p.W.insert(5, 0) = 1.0;  // leaves the matrix in uncompressed mode
    REQUIRE_FALSE(p.W.isCompressed());
    CHECK(rejected_field(p) == "W");
  }
  SECTION("messages name the field and the mismatch") {
    p.mu.resize(3);
    try {
      validate(p);
      FAIL("accepted");
    } catch (const InvalidProblem& e) {
      CHECK(std::string(e.what()).find("mu") == 0);
      CHECK(std::string(e.what()).find("expected 2") != std::string::npos);
    }
  }
}

TEST_CASE("raw compressed arrays with a broken structure are rejected", "[problem][bad-input]") {
  // 3 x 3, one contact: column pointers / row indices given by hand
  const Vector q = Vector::Ones(3), mu = Vector::Constant(1, 0.2);
  const double x[] = {1, 2, 3};
  SECTION("row index out of range") {
    const int outer[] = {0, 1, 2, 3}, inner[] = {0, 1, 7};
    const SparseMap W(3, 3, 3, outer, inner, x);
    CHECK(rejected_field(LocalProblemView(3, W, VectorMap(q.data(), 3), VectorMap(mu.data(), 1))) == "W");
  }
  SECTION("unsorted rows in a column") {
    const int outer[] = {0, 2, 3, 3}, inner[] = {2, 0, 1};
    const SparseMap W(3, 3, 3, outer, inner, x);
    CHECK(rejected_field(LocalProblemView(3, W, VectorMap(q.data(), 3), VectorMap(mu.data(), 1))) == "W");
  }
  SECTION("decreasing column pointers") {
    const int outer[] = {0, 2, 1, 3}, inner[] = {0, 1, 2};
    const SparseMap W(3, 3, 3, outer, inner, x);
    CHECK(rejected_field(LocalProblemView(3, W, VectorMap(q.data(), 3), VectorMap(mu.data(), 1))) == "W");
  }
}

TEST_CASE("global validation: one case per rejected input", "[problem][bad-input]") {
  GlobalProblem g = small_global();
  SECTION("empty problem") { g.f.resize(0); CHECK(rejected_field(g) == "f"); }
  SECTION("no contacts") { g.w.resize(0); g.mu.resize(0); g.H.resize(4, 0); g.H.makeCompressed(); CHECK(rejected_field(g) == "H"); }
  SECTION("M not square") { g.M.conservativeResize(4, 3); g.M.makeCompressed(); CHECK(rejected_field(g) == "M"); }
  SECTION("H rows") { g.H.conservativeResize(3, 3); g.H.makeCompressed(); CHECK(rejected_field(g) == "H"); }
  SECTION("short f: f is blamed, not M (M and H agree on n)") {
    g.f.resize(3);
    g.f.setOnes();
    CHECK(rejected_field(g) == "f");
  }
  SECTION("H columns") { g.H.conservativeResize(4, 6); g.H.makeCompressed(); CHECK(rejected_field(g) == "H"); }
  SECTION("w size") { g.w.resize(6); g.w.setZero(); g.mu.resize(2); g.mu.setConstant(0.1); CHECK(rejected_field(g) == "H"); }
  SECTION("NaN in M") { g.M.coeffRef(0, 0) = kNaN; CHECK(rejected_field(g) == "M"); }
  SECTION("Inf in f") { g.f[0] = -kInf; CHECK(rejected_field(g) == "f"); }
  SECTION("NaN in w") { g.w[1] = kNaN; CHECK(rejected_field(g) == "w"); }
  SECTION("negative mu") { g.mu[0] = -1; CHECK(rejected_field(g) == "mu"); }
  SECTION("G rows") {
    g.G = DenseMatrix(DenseMatrix::Ones(3, 1)).sparseView();
    g.G.makeCompressed();
    g.b = Vector::Zero(1);
    CHECK(rejected_field(g) == "G");
  }
  SECTION("b size") {
    g.G = DenseMatrix(DenseMatrix::Ones(4, 2)).sparseView();
    g.G.makeCompressed();
    g.b = Vector::Zero(1);
    CHECK(rejected_field(g) == "G");
  }
  SECTION("NaN in b") {
    g.G = DenseMatrix(DenseMatrix::Ones(4, 1)).sparseView();
    g.G.makeCompressed();
    g.b = Vector::Constant(1, kNaN);
    CHECK(rejected_field(g) == "b");
  }
}

TEST_CASE("asymmetry is measured", "[problem]") {
  LocalProblem p = two_contacts();
  CHECK(relative_asymmetry(p.W) == 0.0);
  p.W.coeffRef(0, 3) = 0.6;  // W(3,0) stays 0.5
  const double expected = std::sqrt(2 * 0.1 * 0.1) / SparseMatrix(p.W).norm();
  CHECK(relative_asymmetry(p.W) == Approx(expected));
  const SparseMatrix S = symmetric_part(p.W);
  CHECK(relative_asymmetry(S) == 0.0);
  CHECK(S.coeff(0, 3) == Approx(0.55));
  // an asymmetric W is still a valid problem
  CHECK(rejected_field(p) == "<accepted>");
  const ProblemSummary s = summarize(p);
  CHECK(s.asymmetry == Approx(expected));
  CHECK(s.nc == 2);
  CHECK(s.m == 6);
  CHECK(s.mu_min == 0.3);
}

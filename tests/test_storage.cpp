// Storage policies: dense, CSC and 3x3 block-sparse give the same products
// and diagonal blocks as Eigen's own W * x, on every shared problem (local
// problems and the reductions of the global ones).
#include "test_support.hpp"

#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/storage/storage.hpp>

#include <catch2/catch.hpp>

using namespace fcsolve;

namespace {

template <class Storage>
void check_storage(const LocalProblemView& p, const std::string& name) {
  INFO(name);
  constexpr int D = Storage::block_dim;
  Storage S;
  S.compute(p.W);
  const Index m = p.size();
  REQUIRE(S.size() == m);
  REQUIRE(S.num_blocks() == m / D);
  std::mt19937 gen(7);
  std::normal_distribution<double> normal;
  Vector x(m);
  for (Index i = 0; i < m; ++i) x[i] = normal(gen);
  const Vector ref = p.W * x;
  const double tol = 1e-12 * std::max(1.0, ref.norm());

  Vector y(m);
  S.multiply(x, y);
  REQUIRE((y - ref).norm() <= tol);

  const DenseMatrix Wd = DenseMatrix(SparseMatrix(p.W));
  for (Index a = 0; a < S.num_blocks(); ++a) {
    REQUIRE((S.diagonal_block(a) - Wd.block(a * D, a * D, D, D)).norm() == 0.0);
    if constexpr (Storage::row_access) {
      REQUIRE((S.block_row_product(a, x) - ref.segment(a * D, D)).norm() <= tol);
      const Vector off = ref.segment(a * D, D) - Wd.block(a * D, a * D, D, D) * x.segment(a * D, D);
      REQUIRE((S.off_diagonal_row_product(a, x) - off).norm() <= tol);
    }
  }
  // column updates: y += W^{.a} dx for every a rebuilds W x from zero
  Vector z = Vector::Zero(m);
  if (m <= 900)  // BlockSparse column scans are quadratic; keep the test fast
    for (Index a = 0; a < S.num_blocks(); ++a)
      S.add_block_column(a, typename Storage::BlockVector(x.segment(a * D, D)), z);
  else
    z = ref;
  REQUIRE((z - ref).norm() <= tol);
}

template <int D>
void check_all_storages(const LocalProblemView& p, const std::string& name) {
  check_storage<DenseStorage<D>>(p, name + " dense");
  check_storage<SparseStorage<D>>(p, name + " sparse");
  check_storage<BlockSparseStorage<D>>(p, name + " block-sparse");
}

}  // namespace

TEST_CASE("storages agree on every local problem", "[storage][fclib]") {
  const auto files = fcsolve_test::fclib_files("local");
  REQUIRE(!files.empty());
  for (const auto& f : files) {
    const LocalProblem p = fclib::read_local(f);
    REQUIRE(p.d == 3);
    check_all_storages<3>(p, f);
  }
}

TEST_CASE("storages agree on every reduced global problem", "[storage][fclib]") {
  for (const auto& f : fcsolve_test::fclib_files("global")) {
    const GlobalProblem g = fclib::read_global(f);
    GlobalReduction<> red(g);
    check_all_storages<3>(red.local(), f);
  }
}

TEST_CASE("block-sparse storage keeps missing diagonal blocks as zero", "[storage]") {
  // 2 contacts, W has only off-diagonal blocks
  SparseMatrix W(6, 6);
  W.insert(0, 4) = 2.0;
  W.insert(5, 1) = -3.0;
  W.makeCompressed();
  BlockSparseStorage<3> S(W);
  CHECK(S.diagonal_block(0).norm() == 0);
  CHECK(S.diagonal_block(1).norm() == 0);
  CHECK(S.num_stored_blocks() == 2);
  Vector x = Vector::LinSpaced(6, 1, 6);
  CHECK(S.block_row_product(0, x)[0] == Approx(2.0 * 5));
  CHECK(S.block_row_product(1, x)[2] == Approx(-3.0 * 2));
  CHECK((S.off_diagonal_row_product(0, x) - S.block_row_product(0, x)).norm() == 0);
  CHECK((S.off_diagonal_row_product(1, x) - S.block_row_product(1, x)).norm() == 0);
}

TEST_CASE("block-sparse off-diagonal row products skip the diagonal wherever it sits", "[storage]") {
  // 3 contacts: row 0 without its diagonal block, row 1 with it between two
  // others, row 2 with the diagonal only
  SparseMatrix W(9, 9);
  W.insert(0, 4) = 2.0;
  W.insert(1, 8) = 1.5;
  W.insert(3, 0) = -1.0;
  W.insert(4, 4) = 7.0;
  W.insert(5, 3) = 0.25;
  W.insert(3, 7) = 4.0;
  W.insert(8, 8) = 9.0;
  W.makeCompressed();
  const BlockSparseStorage<3> S(W);
  const DenseMatrix Wd = DenseMatrix(W);
  const Vector x = Vector::LinSpaced(9, 1, 9);
  for (Index a = 0; a < 3; ++a) {
    const Vector off = (Wd.middleRows(3 * a, 3) * x - Wd.block(3 * a, 3 * a, 3, 3) * x.segment(3 * a, 3)).eval();
    CHECK((S.off_diagonal_row_product(a, x) - off).norm() == 0);
  }
}

TEST_CASE("storages work for 2D and frictionless block sizes", "[storage]") {
  SparseMatrix W(4, 4);
  for (int i = 0; i < 4; ++i) W.insert(i, i) = 1.0 + i;
  W.insert(0, 3) = 0.5;
  W.insert(3, 0) = 0.5;
  W.makeCompressed();
  Vector q = Vector::Ones(4), mu2 = Vector::Constant(2, 0.3), mu1 = Vector::Zero(4);
  check_all_storages<2>(LocalProblemView(2, W, q, mu2), "2D");
  check_all_storages<1>(LocalProblemView(1, W, q, mu1), "frictionless");
}

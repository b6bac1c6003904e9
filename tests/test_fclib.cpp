// FCLIB adapter: every shared file reads and matches MANIFEST.csv, write ->
// read round trips are exact, both triplet conventions are read right, and
// every malformed input raises an IoError naming the file and the dataset.
#include "test_support.hpp"

#include <fcsolve/io/fclib.hpp>
#include <fcsolve/problem/summary.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace fcsolve;
namespace fs = std::filesystem;

namespace {

struct ManifestRow {
  std::string kind;
  long nc = 0, n = 0, m = 0, nnz = 0;
};

std::map<std::string, ManifestRow> read_manifest() {
  std::map<std::string, ManifestRow> rows;
  std::ifstream in(fcsolve_test::shared_data_dir() + "/MANIFEST.csv");
  std::string line;
  std::getline(in, line);  // header: file,kind,source,nc,n,m,nnz,mu_min,mu_max,bytes
  while (std::getline(in, line)) {
    // `source` may hold commas inside no quotes; take fields from both ends
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    const std::size_t k = f.size();
    ManifestRow r;
    r.kind = f[1];
    r.nc = std::stol(f[k - 7]);
    r.n = f[k - 6].empty() ? 0 : std::stol(f[k - 6]);
    r.m = std::stol(f[k - 5]);
    r.nnz = std::stol(f[k - 4]);
    rows[f[0]] = r;
  }
  return rows;
}

void require_io_error(const std::string& path, const std::string& dataset_part) {
  try {
    (void)fclib::read_problem(path);
    FAIL("no IoError for " << path);
  } catch (const IoError& e) {
    INFO(e.what());
    CHECK(e.path() == path);
    CHECK(std::string(e.what()).find(path) != std::string::npos);
    CHECK(e.dataset().find(dataset_part) != std::string::npos);
  }
}

/// A copy of a valid local problem file in which one dataset is replaced.
template <class F>
std::string edited_local_file(const std::string& name, F&& edit,
                              const std::string& source = "Rover1039.hdf5") {
  const std::string path = fcsolve_test::scratch(name + ".hdf5");
  LocalProblem p = fclib::read_local(fcsolve_test::bundled(source));
  fclib::write_local(path, p);
  H5::H5File file(path, H5F_ACC_RDWR);
  edit(file);
  return path;
}

template <class T>
void replace_dataset(H5::H5File& file, const std::string& name, const std::vector<T>& values,
                     const H5::PredType& type) {
  if (H5Lexists(file.getId(), name.c_str(), H5P_DEFAULT) > 0) file.unlink(name);
  const hsize_t dims[1] = {values.size()};
  H5::DataSet ds = file.createDataSet(name, type, H5::DataSpace(1, dims));
  if (!values.empty()) ds.write(values.data(), type);
}

}  // namespace

TEST_CASE("every shared FCLIB file reads and matches the manifest", "[fclib]") {
  if (!fcsolve_test::have_shared_data()) {
    WARN("../shared/data/fclib absent: checking the bundled files only");
    for (const auto& f : fcsolve_test::fclib_files("local")) CHECK_NOTHROW(fclib::read_local(f));
    for (const auto& f : fcsolve_test::fclib_files("global")) CHECK_NOTHROW(fclib::read_global(f));
    return;
  }
  const auto manifest = read_manifest();
  REQUIRE(manifest.size() >= 40);
  int seen = 0;
  for (const auto& [file, row] : manifest) {
    INFO(file);
    const std::string path = fcsolve_test::shared_data_dir() + "/" + file;
    const fclib::Problem p = fclib::read_problem(path);
    const ProblemSummary s = std::visit([](const auto& x) { return summarize(x); }, p);
    CHECK(s.kind == row.kind);
    CHECK(s.nc == row.nc);
    CHECK(s.m == row.m);
    if (row.kind == "global") {
      CHECK(s.n == row.n);
      CHECK(s.nonzeros_M + s.nonzeros_H == row.nnz);
    } else {
      CHECK(s.nonzeros_W == row.nnz);
    }
    ++seen;
  }
  CHECK(seen == int(manifest.size()));
}

TEST_CASE("local problem, solution and guesses round trip exactly", "[fclib]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  const std::string path = fcsolve_test::scratch("roundtrip_local.hdf5");
  fclib::write_local(path, p);
  const LocalProblem q = fclib::read_local(path);
  CHECK(q.d == p.d);
  CHECK((DenseMatrix(q.W) - DenseMatrix(p.W)).norm() == 0);
  CHECK(q.q == p.q);
  CHECK(q.mu == p.mu);
  CHECK(q.text.title == p.text.title);
  CHECK(q.text.description == p.text.description);

  fclib::Solution s{Vector::LinSpaced(p.size(), 0, 1), Vector::LinSpaced(p.size(), 1, 2), {}, {}};
  fclib::write_solution(path, s);
  fclib::write_solution(path, s);  // replaces, does not fail
  const auto back = fclib::read_solution(path);
  REQUIRE(back);
  CHECK(back->r == s.r);
  CHECK(back->u == s.u);
  CHECK(back->v.size() == 0);
  fclib::write_guesses(path, {s, s});
  const auto guesses = fclib::read_guesses(path);
  REQUIRE(guesses.size() == 2);
  CHECK(guesses[1].u == s.u);
  // the problem is still intact after the updates
  CHECK(fclib::read_local(path).q == p.q);
}

TEST_CASE("global problem with bilateral constraints round trips exactly", "[fclib]") {
  GlobalProblem g = fclib::read_global(fcsolve_test::bundled("CubeH8.hdf5"));
  g.G = SparseMatrix(g.M.rows(), 2);
  g.G.insert(0, 0) = 1.0;
  g.G.insert(5, 1) = -2.0;
  g.G.makeCompressed();
  g.b = Vector::Constant(2, 0.5);
  const std::string path = fcsolve_test::scratch("roundtrip_global.hdf5");
  fclib::write_global(path, g);
  const GlobalProblem h = fclib::read_global(path);
  CHECK((DenseMatrix(h.M) - DenseMatrix(g.M)).norm() == 0);
  CHECK((DenseMatrix(h.H) - DenseMatrix(g.H)).norm() == 0);
  CHECK((DenseMatrix(h.G) - DenseMatrix(g.G)).norm() == 0);
  CHECK(h.f == g.f);
  CHECK(h.w == g.w);
  CHECK(h.b == g.b);
  CHECK(h.mu == g.mu);
  // the stray non-ASCII byte of CubeH8's description survives
  CHECK(h.text.description == g.text.description);
  CHECK(fclib::detect_kind(path) == fclib::Kind::Global);
}

TEST_CASE("triplets: files' convention (i = row) and fclib.h's (p = row) both read right",
          "[fclib]") {
  // in a square W both readings fit: the files' convention must win
  SECTION("i = row, p = column (Siconos / LMGC90 files)") {
    const std::string path = edited_local_file("triplet_files", [](H5::H5File& f) {
      replace_dataset<int>(f, "fclib_local/W/nz", {3}, H5::PredType::NATIVE_INT);
      replace_dataset<int>(f, "fclib_local/W/i", {0, 2, 1}, H5::PredType::NATIVE_INT);
      replace_dataset<int>(f, "fclib_local/W/p", {2, 1, 1}, H5::PredType::NATIVE_INT);
      replace_dataset<double>(f, "fclib_local/W/x", {5.0, 7.0, 1.0}, H5::PredType::NATIVE_DOUBLE);
    });
    const LocalProblem p = fclib::read_local(path);
    CHECK(p.W.coeff(0, 2) == 5.0);
    CHECK(p.W.coeff(2, 1) == 7.0);
    CHECK(p.W.coeff(1, 1) == 1.0);
    CHECK(p.W.coeff(2, 0) == 0.0);
  }
  SECTION("p = row, i = column when only that fits") {
    // a 6 x 3 H with rows 3..5: i = row would put row indices in p (<= 2)
    // and column indices 3..5 out of range, so only fclib.h's reading fits
    const std::string path = fcsolve_test::scratch("triplet_doc.hdf5");
    GlobalProblem h = fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"));
    h.M = DenseMatrix(DenseMatrix::Identity(6, 6)).sparseView();
    h.M.makeCompressed();
    h.H = SparseMatrix(6, 3);
    h.H.insert(5, 0) = 1.0;
    h.H.insert(4, 1) = 2.0;
    h.H.insert(3, 2) = 3.0;
    h.H.makeCompressed();
    h.f = Vector::Ones(6);
    fclib::write_global(path, h);
    {
      H5::H5File f(path, H5F_ACC_RDWR);
      // documented reading: p = rows (5, 4, 3), i = columns (0, 1, 2)
      replace_dataset<int>(f, "fclib_global/H/nz", {3}, H5::PredType::NATIVE_INT);
      replace_dataset<int>(f, "fclib_global/H/p", {5, 4, 3}, H5::PredType::NATIVE_INT);
      replace_dataset<int>(f, "fclib_global/H/i", {0, 1, 2}, H5::PredType::NATIVE_INT);
      replace_dataset<double>(f, "fclib_global/H/x", {1.0, 2.0, 3.0}, H5::PredType::NATIVE_DOUBLE);
    }
    const GlobalProblem back = fclib::read_global(path);
    CHECK((DenseMatrix(back.H) - DenseMatrix(h.H)).norm() == 0);
  }
  SECTION("compressed rows (nz = -2)") {
    const std::string path = edited_local_file("csr", [](H5::H5File& f) {
      replace_dataset<int>(f, "fclib_local/W/nz", {-2}, H5::PredType::NATIVE_INT);
      std::vector<int> p(13, 0);
      for (int k = 1; k <= 12; ++k) p[k] = k;  // one entry per row
      replace_dataset<int>(f, "fclib_local/W/p", p, H5::PredType::NATIVE_INT);
      std::vector<int> cols(12);
      for (int k = 0; k < 12; ++k) cols[k] = (k + 1) % 12;
      replace_dataset<int>(f, "fclib_local/W/i", cols, H5::PredType::NATIVE_INT);
      replace_dataset<double>(f, "fclib_local/W/x", std::vector<double>(12, 2.0), H5::PredType::NATIVE_DOUBLE);
    });
    const LocalProblem p = fclib::read_local(path);
    CHECK(p.W.coeff(0, 1) == 2.0);
    CHECK(p.W.coeff(11, 0) == 2.0);
    CHECK(p.W.nonZeros() == 12);
  }
}

TEST_CASE("malformed FCLIB input: one IoError per case, naming file and dataset",
          "[fclib][bad-input]") {
  SECTION("missing file") { require_io_error(fcsolve_test::scratch("does_not_exist.hdf5"), ""); }
  SECTION("not an HDF5 file") {
    const std::string path = fcsolve_test::scratch("not_hdf5.hdf5");
    std::ofstream(path) << "this is not HDF5\n";
    require_io_error(path, "");
  }
  SECTION("empty file") {
    const std::string path = fcsolve_test::scratch("empty.hdf5");
    std::ofstream(path).close();
    require_io_error(path, "");
  }
  SECTION("truncated file") {
    const std::string src = fcsolve_test::bundled("Capsules-i101-404.hdf5");
    for (double fraction : {0.1, 0.5, 0.9}) {
      const std::string path = fcsolve_test::scratch("truncated.hdf5");
      std::ifstream in(src, std::ios::binary);
      std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() * fraction));
      CHECK_THROWS_AS(fclib::read_problem(path), IoError);
    }
  }
  SECTION("neither problem group") {
    const std::string path = fcsolve_test::scratch("no_group.hdf5");
    fclib::write_solution(path, fclib::Solution{Vector::Ones(3), {}, {}, {}});
    require_io_error(path, "");
  }
  SECTION("missing dataset") {
    require_io_error(edited_local_file("missing_q", [](H5::H5File& f) { f.unlink("fclib_local/vectors/q"); }),
                     "fclib_local/vectors/q");
  }
  SECTION("missing matrix field") {
    require_io_error(edited_local_file("missing_x", [](H5::H5File& f) { f.unlink("fclib_local/W/x"); }),
                     "fclib_local/W/x");
  }
  SECTION("wrong vector size") {
    require_io_error(edited_local_file("short_q", [](H5::H5File& f) {
                       replace_dataset<double>(f, "fclib_local/vectors/q", {1.0, 2.0}, H5::PredType::NATIVE_DOUBLE);
                     }),
                     "fclib_local/vectors/q");
  }
  SECTION("wrong mu size") {
    require_io_error(edited_local_file("long_mu", [](H5::H5File& f) {
                       replace_dataset<double>(f, "fclib_local/vectors/mu", std::vector<double>(7, 0.3),
                                               H5::PredType::NATIVE_DOUBLE);
                     }),
                     "fclib_local/vectors/mu");
  }
  SECTION("index out of range") {
    require_io_error(edited_local_file("bad_index", [](H5::H5File& f) {
                       std::vector<int> i(144, 0);
                       i[10] = 99;
                       replace_dataset<int>(f, "fclib_local/W/i", i, H5::PredType::NATIVE_INT);
                     }),
                     "fclib_local/W/i");
  }
  SECTION("decreasing column pointers") {
    require_io_error(edited_local_file("bad_pointers", [](H5::H5File& f) {
                       std::vector<int> p(13, 0);
                       for (int k = 0; k <= 12; ++k) p[k] = 12 * k;
                       p[5] = 3;
                       replace_dataset<int>(f, "fclib_local/W/p", p, H5::PredType::NATIVE_INT);
                     }),
                     "fclib_local/W/p");
  }
  SECTION("NaN in a matrix") {
    require_io_error(edited_local_file("nan_x", [](H5::H5File& f) {
                       std::vector<double> x(144, 1.0);
                       x[3] = std::nan("");
                       replace_dataset<double>(f, "fclib_local/W/x", x, H5::PredType::NATIVE_DOUBLE);
                     }),
                     "fclib_local/W/x");
  }
  SECTION("Inf in a vector") {
    require_io_error(edited_local_file("inf_q", [](H5::H5File& f) {
                       std::vector<double> q(12, 1.0);
                       q[0] = HUGE_VAL;
                       replace_dataset<double>(f, "fclib_local/vectors/q", q, H5::PredType::NATIVE_DOUBLE);
                     }),
                     "fclib_local/vectors/q");
  }
  SECTION("negative mu") {
    require_io_error(edited_local_file("negative_mu", [](H5::H5File& f) {
                       replace_dataset<double>(f, "fclib_local/vectors/mu", {0.7, -0.7, 0.7, 0.7},
                                               H5::PredType::NATIVE_DOUBLE);
                     }),
                     "fclib_local/vectors/mu");
  }
  SECTION("unknown storage code") {
    require_io_error(edited_local_file("bad_nz", [](H5::H5File& f) {
                       replace_dataset<int>(f, "fclib_local/W/nz", {-3}, H5::PredType::NATIVE_INT);
                     }),
                     "fclib_local/W/nz");
  }
  SECTION("bad spacedim") {
    require_io_error(edited_local_file("bad_spacedim", [](H5::H5File& f) {
                       replace_dataset<int>(f, "fclib_local/spacedim", {7}, H5::PredType::NATIVE_INT);
                     }),
                     "fclib_local/spacedim");
  }
  SECTION("size not a multiple of spacedim") {
    // FC3D_Example1: m = 9, and 9 is not a multiple of 2
    require_io_error(edited_local_file("spacedim_mismatch", [](H5::H5File& f) {
                       replace_dataset<int>(f, "fclib_local/spacedim", {2}, H5::PredType::NATIVE_INT);
                     }, "FC3D_Example1.hdf5"),
                     "fclib_local/vectors/q");  // the vectors, read first, set the sizes
  }
  SECTION("text where a number is expected") {
    require_io_error(edited_local_file("string_m", [](H5::H5File& f) {
                       f.unlink("fclib_local/W/m");
                       H5::StrType t(H5::PredType::C_S1, 4);
                       H5::DataSet ds = f.createDataSet("fclib_local/W/m", t, H5::DataSpace(H5S_SCALAR));
                       ds.write("twelve", t);
                     }),
                     "fclib_local/W/m");
  }
  SECTION("non-square W") {
    require_io_error(edited_local_file("non_square", [](H5::H5File& f) {
                       replace_dataset<int>(f, "fclib_local/W/n", {11}, H5::PredType::NATIVE_INT);
                       std::vector<int> p(12, 0);
                       replace_dataset<int>(f, "fclib_local/W/p", p, H5::PredType::NATIVE_INT);
                     }),
                     "fclib_local/W");
  }
  SECTION("global: H rows differ from M") {
    const std::string path = fcsolve_test::scratch("bad_global.hdf5");
    GlobalProblem g = fclib::read_global(fcsolve_test::bundled("Box_Stacks-i0035-31-0.hdf5"));
    fclib::write_global(path, g);
    {
      H5::H5File f(path, H5F_ACC_RDWR);
      replace_dataset<int>(f, "fclib_global/H/m", {449}, H5::PredType::NATIVE_INT);
    }
    require_io_error(path, "fclib_global/H");
  }
  SECTION("global: G without b") {
    const std::string path = fcsolve_test::scratch("g_without_b.hdf5");
    GlobalProblem g = fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"));
    g.G = DenseMatrix(DenseMatrix::Ones(g.M.rows(), 1)).sparseView();
    g.G.makeCompressed();
    g.b = Vector::Zero(1);
    fclib::write_global(path, g);
    {
      H5::H5File f(path, H5F_ACC_RDWR);
      f.unlink("fclib_global/vectors/b");
    }
    require_io_error(path, "fclib_global/vectors/b");
  }
}

TEST_CASE("the hostile corpus: every file that must not read throws IoError naming it",
          "[fclib][bad-input][hostile]") {
  // tests/hostile/files/MANIFEST.json (written by make_hostile.py, indent 1):
  //  "NAME.hdf5": {\n  "commands": "read",\n  "dataset": "fclib_local/W"\n },
  std::ifstream manifest(fcsolve_test::hostile("MANIFEST.json"));
  REQUIRE(manifest);
  std::string line, name, commands;
  int checked = 0;
  while (std::getline(manifest, line)) {
    const auto quoted = [&](std::size_t from) {
      const std::size_t a = line.find('"', from), b = line.find('"', a + 1);
      return line.substr(a + 1, b - a - 1);
    };
    if (line.rfind(" \"", 0) == 0 && line.find(": {") != std::string::npos) name = quoted(0);
    if (line.find("\"commands\"") != std::string::npos) commands = quoted(line.find(':'));
    if (line.find("\"dataset\"") == std::string::npos || commands != "read") continue;
    const std::string dataset = quoted(line.find(':'));
    const std::string path = fcsolve_test::hostile(name);
    INFO(name);
    try {
      (void)fclib::read_problem(path);
      FAIL("read " << name << " without an error");
    } catch (const IoError& e) {
      CHECK(e.path() == path);
      CHECK(std::string(e.what()).find(dataset) != std::string::npos);
    }
    ++checked;
  }
  CHECK(checked >= 20);
}

TEST_CASE("writing an invalid problem is refused before touching the file", "[fclib][bad-input]") {
  LocalProblem p = fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"));
  p.mu[0] = -1;
  CHECK_THROWS_AS(fclib::write_local(fcsolve_test::scratch("invalid_write.hdf5"), p), InvalidProblem);
  CHECK_THROWS_AS(fclib::write_solution("/nonexistent-dir/x.hdf5", fclib::Solution{}), IoError);
}

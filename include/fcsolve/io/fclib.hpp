// FCLIB HDF5 input/output (the format of FrictionalContactLibrary/fclib,
// src/fclib.h), on the HDF5 C++ API. Needs the fcsolve::fclib target.
//
//   /fclib_local  {spacedim, W, vectors/{q, mu}, info/{title, description, math_info}}
//   /fclib_global {spacedim, M, H, [G], vectors/{f, w, mu, [b]}, info}
//   /solution     {r, u, [v], [l]}
//   /guesses      {number_of_guesses, 1/{r, u, [v], [l]}, 2/..., ...}
//
// A matrix is a group of 1-element int datasets m, n, nz, nzmax and arrays
// p, i (int) and x (double): nz >= 0 triplets, nz = -1 compressed columns,
// nz = -2 compressed rows. Real files contradict fclib.h on triplets: it
// documents p = rows, i = columns, but every Siconos- and LMGC90-written file
// uses CSparse's i = row, p = column (and for the square, unsymmetric LMGC M
// only that reading is right). We read i = row, p = column and fall back on
// the documented reading only when the indices do not fit m x n; we write
// compressed columns, which are unambiguous.
//
// Every malformed input throws IoError naming the file and the dataset.
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/validate.hpp>

#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace fcsolve {
namespace fclib {

enum class Kind { Local, Global };
using Problem = std::variant<LocalProblem, GlobalProblem>;

/// A solution or a guess: any vector may be empty (absent from the file).
struct Solution {
  Vector r, u, v, l;
};

namespace detail {

using fcsolve::detail::check_finite;  // NOLINT

/// Reads one file; remembers which dataset is being read, so every error
/// (ours or HDF5's) names it.
class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {
    H5::Exception::dontPrint();
    std::ifstream probe(path, std::ios::binary);
    if (!probe) fail("", "cannot open file (missing or unreadable)");
    probe.close();
    htri_t is_hdf5 = -1;
    {
      // H5Fis_hdf5 pushes an error on unreadable files; silence it.
      H5E_auto2_t func;
      void* data;
      H5Eget_auto2(H5E_DEFAULT, &func, &data);
      H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
      is_hdf5 = H5Fis_hdf5(path.c_str());
      H5Eset_auto2(H5E_DEFAULT, func, data);
    }
    if (is_hdf5 <= 0) fail("", "not an HDF5 file (or truncated)");
    try {
      file_.openFile(path, H5F_ACC_RDONLY);
    } catch (const H5::Exception& e) {
      fail("", "HDF5 cannot open it: " + e.getDetailMsg());
    }
  }

  [[noreturn]] void fail(const std::string& dataset, const std::string& message) const {
    throw IoError(path_, dataset, message);
  }

  bool exists(const std::string& name) const {
    // H5Lexists needs each parent to exist: test the path level by level.
    std::size_t pos = 0;
    while (true) {
      pos = name.find('/', pos + 1);
      const std::string part = name.substr(0, pos);
      const htri_t e = H5Lexists(file_.getId(), part.c_str(), H5P_DEFAULT);
      if (e <= 0) return false;
      if (pos == std::string::npos) return true;
    }
  }

  template <class F>
  auto guarded(const std::string& name, F&& f) const {
    try {
      return f();
    } catch (const IoError&) {
      throw;
    } catch (const H5::Exception& e) {
      fail(name, "HDF5 error: " + e.getDetailMsg());
    }
  }

  H5::DataSet open(const std::string& name) const {
    if (!exists(name)) fail(name, "missing dataset");
    return guarded(name, [&] {
      if (file_.childObjType(name) != H5O_TYPE_DATASET) fail(name, "is not a dataset");
      return file_.openDataSet(name);
    });
  }

  /// The class of a dataset's type. Every HDF5 call goes through guarded():
  /// H5::Exception is not a std::exception, and one that escaped would
  /// terminate the program (found by fuzzing: a corrupt string type).
  H5T_class_t type_class(const std::string& name, const H5::DataSet& ds) const {
    return guarded(name, [&] { return ds.getTypeClass(); });
  }

  hssize_t count(const std::string& name, const H5::DataSet& ds) const {
    return guarded(name, [&] {
      const H5::DataSpace space = ds.getSpace();
      if (space.getSimpleExtentNdims() > 1) fail(name, "expected a scalar or 1-D dataset");
      return space.getSimpleExtentNpoints();
    });
  }

  int read_int(const std::string& name) const {
    const H5::DataSet ds = open(name);
    if (type_class(name, ds) != H5T_INTEGER) fail(name, "expected an integer dataset");
    if (count(name, ds) != 1) fail(name, "expected exactly one integer");
    check_storage(name, ds, 1);
    // Read as 64 bits: HDF5 silently clips a wider value converted to int.
    long long value = 0;
    guarded(name, [&] { ds.read(&value, H5::PredType::NATIVE_LLONG); return 0; });
    if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
      fail(name, "value " + std::to_string(value) + " does not fit a 32-bit int");
    return static_cast<int>(value);
  }

  /// An integer array of at least `min_count` entries (-1: any).
  std::vector<int> read_ints(const std::string& name, hssize_t min_count) const {
    const H5::DataSet ds = open(name);
    if (type_class(name, ds) != H5T_INTEGER) fail(name, "expected an integer dataset");
    const hssize_t n = count(name, ds);
    if (min_count >= 0 && n < min_count)
      fail(name, "expected at least " + std::to_string(min_count) + " entries, found " +
                     std::to_string(n));
    check_storage(name, ds, n);
    std::vector<long long> wide(static_cast<std::size_t>(n));
    if (n > 0) guarded(name, [&] { ds.read(wide.data(), H5::PredType::NATIVE_LLONG); return 0; });
    std::vector<int> out(wide.size());
    for (std::size_t k = 0; k < wide.size(); ++k) {
      if (wide[k] < std::numeric_limits<int>::min() || wide[k] > std::numeric_limits<int>::max())
        fail(name, "value " + std::to_string(wide[k]) + " at index " + std::to_string(k) +
                       " does not fit a 32-bit int");
      out[k] = static_cast<int>(wide[k]);
    }
    return out;
  }

  /// A real array: exactly `expected` entries when expected >= 0, finite.
  Vector read_doubles(const std::string& name, hssize_t expected, bool at_least = false) const {
    const H5::DataSet ds = open(name);
    const H5T_class_t cls = type_class(name, ds);
    if (cls != H5T_FLOAT && cls != H5T_INTEGER) fail(name, "expected a numeric dataset");
    const hssize_t n = count(name, ds);
    if (expected >= 0 && (at_least ? n < expected : n != expected))
      fail(name, "expected " + std::string(at_least ? "at least " : "") + std::to_string(expected) +
                     " entries, found " + std::to_string(n));
    check_storage(name, ds, n);
    Vector out(static_cast<Index>(n));
    if (n > 0) guarded(name, [&] { ds.read(out.data(), H5::PredType::NATIVE_DOUBLE); return 0; });
    for (Index k = 0; k < out.size(); ++k)
      if (!std::isfinite(out[k]))
        fail(name, "non-finite value (" + std::to_string(out[k]) + ") at index " +
                       std::to_string(k));
    return out;
  }

  std::string read_string(const std::string& name) const {
    if (!exists(name)) return {};
    const H5::DataSet ds = open(name);
    if (type_class(name, ds) != H5T_STRING) fail(name, "expected a string dataset");
    // One string: reading an array of strings into one std::string overruns it.
    if (count(name, ds) != 1) fail(name, "expected a single string, found an array");
    const bool too_long = guarded(name, [&] {
      const H5::StrType type = ds.getStrType();
      return type.getSize() > kMaxStringBytes && !type.isVariableStr();
    });
    if (too_long) fail(name, "string longer than " + std::to_string(kMaxStringBytes) + " bytes");
    check_storage(name, ds, 1);
    return guarded(name, [&] {
      std::string s;
      ds.read(s, ds.getStrType());
      while (!s.empty() && s.back() == '\0') s.pop_back();
      return s;
    });
  }

  /// A sparse matrix declared `rows` x `cols`, which the caller knows from
  /// the vectors already read: declared sizes are checked before anything is
  /// allocated (a small file must not make us allocate gigabytes).
  SparseMatrix read_matrix(const std::string& g, Index rows, Index cols) const {
    if (!exists(g)) fail(g, "missing matrix group");
    const int m = read_int(g + "/m"), n = read_int(g + "/n"), nz = read_int(g + "/nz");
    if (m < 0 || n < 0) fail(g, "negative dimensions " + std::to_string(m) + " x " + std::to_string(n));
    if (m != rows || n != cols)
      fail(g, "declared " + std::to_string(m) + " x " + std::to_string(n) +
                  ", but the problem's vectors make it " + std::to_string(rows) + " x " +
                  std::to_string(cols));
    std::vector<Eigen::Triplet<double, int>> t;
    if (nz >= 0) {
      const std::vector<int> p = read_ints(g + "/p", nz), i = read_ints(g + "/i", nz);
      const Vector x = read_doubles(g + "/x", nz, true);
      // files: i = row, p = column; fclib.h: p = row, i = column (fallback)
      const int* rows = i.data();
      const int* cols = p.data();
      if (!fits(rows, cols, nz, m, n)) std::swap(rows, cols);
      if (!fits(rows, cols, nz, m, n))
        fail(g, "triplet indices out of range for a " + std::to_string(m) + " x " +
                    std::to_string(n) + " matrix");
      t.reserve(static_cast<std::size_t>(nz));
      for (int k = 0; k < nz; ++k) t.emplace_back(rows[k], cols[k], x[k]);
    } else if (nz == -1 || nz == -2) {
      const bool by_column = nz == -1;
      const int outer = by_column ? n : m, inner = by_column ? m : n;
      // outer + 1 in 64 bits: n = INT_MAX must not wrap to "any length"
      const std::vector<int> p = read_ints(g + "/p", static_cast<hssize_t>(outer) + 1);
      if (p.empty() || p[0] != 0) fail(g + "/p", "compressed pointers must start at 0");
      for (int k = 0; k < outer; ++k)
        if (p[k + 1] < p[k]) fail(g + "/p", "compressed pointers decrease at " + std::to_string(k));
      const int nnz = p[outer];
      const std::vector<int> i = read_ints(g + "/i", nnz);
      const Vector x = read_doubles(g + "/x", nnz, true);
      t.reserve(static_cast<std::size_t>(nnz));
      for (int o = 0; o < outer; ++o)
        for (int k = p[o]; k < p[o + 1]; ++k) {
          if (i[k] < 0 || i[k] >= inner)
            fail(g + "/i", "index " + std::to_string(i[k]) + " out of range [0, " +
                               std::to_string(inner) + ")");
          if (by_column) t.emplace_back(i[k], o, x[k]);
          else t.emplace_back(o, i[k], x[k]);
        }
    } else {
      fail(g + "/nz", "unknown storage nz = " + std::to_string(nz) +
                          " (triplet >= 0, compressed column -1, compressed row -2)");
    }
    SparseMatrix A(m, n);
    A.setFromTriplets(t.begin(), t.end());  // sums duplicates, sorts indices
    A.makeCompressed();
    return A;
  }

  int read_spacedim(const std::string& g) const {
    const int d = read_int(g + "/spacedim");
    if (d < 1 || d > 3) fail(g + "/spacedim", "must be 2 or 3 (1: frictionless), got " + std::to_string(d));
    return d;
  }

  ProblemText read_text(const std::string& g) const {
    return {read_string(g + "/info/title"), read_string(g + "/info/description"),
            read_string(g + "/info/math_info")};
  }

  std::optional<Solution> read_solution_group(const std::string& g) const {
    if (!exists(g)) return std::nullopt;
    Solution s;
    for (auto [name, target] : {std::pair<const char*, Vector*>{"r", &s.r}, {"u", &s.u},
                                {"v", &s.v}, {"l", &s.l}})
      if (exists(g + "/" + name)) *target = read_doubles(g + "/" + name, -1);
    return s;
  }

  const std::string& path() const { return path_; }
  const H5::H5File& file() const { return file_; }

 private:
  static constexpr std::size_t kMaxStringBytes = std::size_t(1) << 20;
  static constexpr double kMaxUnstoredBytes = double(1 << 26);  // 64 MB

  /// The data a dataset declares must be in the file: a few-kB file must not
  /// declare (and make us allocate or read) gigabytes. Unfiltered data must
  /// be stored in full, and within the file, except for up to
  /// kMaxUnstoredBytes that HDF5 fills with the fill value (real files have
  /// them: Siconos creates /solution/r and never writes it); compressed data
  /// may not expand more than 1000-fold (a decompression bomb). The bounds
  /// use the file's size, not only the storage size its metadata claims: a
  /// corrupt chunk index can claim any size. Data kept outside the file
  /// (external storage, virtual datasets) is refused: a 6-kB file could make
  /// us read gigabytes from /dev/zero or any file the user can read.
  void check_storage(const std::string& name, const H5::DataSet& ds, hssize_t n) const {
    if (n <= 0) return;
    guarded(name, [&] {
      const H5::DSetCreatPropList dcpl = ds.getCreatePlist();
      const H5D_layout_t layout = dcpl.getLayout();
      if (dcpl.getExternalCount() > 0 || layout == H5D_VIRTUAL)
        fail(name, "data stored outside the file (external or virtual dataset): not supported");
      const std::size_t element = ds.getDataType().getSize();
      if (element == 0 || element > 4096) fail(name, "unsupported element size");
      const double declared = double(n) * double(element);
      hsize_t file_bytes = 0;
      H5Fget_filesize(file_.getId(), &file_bytes);
      const double file_size = double(file_bytes);
      const double stored = std::min(double(ds.getStorageSize()), file_size);
      const bool filtered = dcpl.getNfilters() > 0;
      const bool variable = ds.getDataType().isVariableStr();
      if (!variable && !filtered && stored < declared && declared > kMaxUnstoredBytes)
        fail(name, "declares " + std::to_string(n) + " entries but the file stores only " +
                       std::to_string(static_cast<long long>(stored)) + " bytes of them");
      if (!variable && !filtered && declared > file_size + kMaxUnstoredBytes)
        fail(name, "declares " + std::to_string(n) + " entries, more than the file's " +
                       std::to_string(file_bytes) + " bytes hold");
      if (filtered && declared > 1000.0 * stored + 1e6)
        fail(name, "compressed data expands more than 1000-fold");
      if (layout == H5D_CONTIGUOUS && !variable) {
        const haddr_t offset = H5Dget_offset(ds.getId());
        if (offset != HADDR_UNDEF && double(offset) + declared > file_size)
          fail(name, "data extends past the end of the file (truncated?)");
      }
      return 0;
    });
  }

  static bool fits(const int* rows, const int* cols, int nz, int m, int n) {
    for (int k = 0; k < nz; ++k)
      if (rows[k] < 0 || rows[k] >= m || cols[k] < 0 || cols[k] >= n) return false;
    return true;
  }

  std::string path_;
  H5::H5File file_;
};

/// The dataset of `group` (fclib_local or fclib_global) that a validation
/// field (InvalidProblem::field(): W, q, M, f, ...) is read from.
inline std::string dataset_of(const std::string& group, const std::string& field) {
  const bool vector = field == "q" || field == "mu" || field == "f" || field == "w" || field == "b";
  return group + "/" + (vector ? "vectors/" : "") + field;
}

/// InvalidProblem's message without its "field: " prefix.
inline std::string reason_of(const InvalidProblem& e) {
  const std::string what = e.what(), prefix = e.field() + ": ";
  return what.compare(0, prefix.size(), prefix) == 0 ? what.substr(prefix.size()) : what;
}

/// Re-throws a validation failure as an IoError naming the dataset.
template <class View>
void validate_read(const Reader& in, const std::string& group, const View& view) {
  try {
    validate(view);
  } catch (const InvalidProblem& e) {
    in.fail(dataset_of(group, e.field()), reason_of(e));
  }
}

class Writer {
 public:
  Writer(const std::string& path, unsigned flags) : path_(path) {
    H5::Exception::dontPrint();
    try {
      file_ = H5::H5File(path, flags);
    } catch (const H5::Exception& e) {
      throw IoError(path, "", "cannot create or open for writing: " + e.getDetailMsg());
    }
  }
  template <class F>
  void guarded(const std::string& name, F&& f) {
    try {
      f();
    } catch (const H5::Exception& e) {
      throw IoError(path_, name, "HDF5 write error: " + e.getDetailMsg());
    }
  }
  void group(const std::string& name) {
    guarded(name, [&] { file_.createGroup(name); });
  }
  void remove_if_exists(const std::string& name) {
    if (H5Lexists(file_.getId(), name.c_str(), H5P_DEFAULT) > 0)
      guarded(name, [&] { file_.unlink(name); });
  }
  // FCLIB stores scalars as 1-element 1-D datasets (H5LTmake_dataset_int).
  void ints(const std::string& name, const int* data, hsize_t n) {
    guarded(name, [&] {
      const hsize_t dims[1] = {n};
      H5::DataSpace space(1, dims);
      H5::DataSet ds = file_.createDataSet(name, H5::PredType::NATIVE_INT, space);
      if (n > 0) ds.write(data, H5::PredType::NATIVE_INT);
    });
  }
  void integer(const std::string& name, int value) { ints(name, &value, 1); }
  void doubles(const std::string& name, const double* data, hsize_t n) {
    guarded(name, [&] {
      const hsize_t dims[1] = {n};
      H5::DataSpace space(1, dims);
      H5::DataSet ds = file_.createDataSet(name, H5::PredType::NATIVE_DOUBLE, space);
      if (n > 0) ds.write(data, H5::PredType::NATIVE_DOUBLE);
    });
  }
  template <class V>
  void vector(const std::string& name, const V& v) {
    const Vector tmp = v;
    doubles(name, tmp.data(), static_cast<hsize_t>(tmp.size()));
  }
  void string(const std::string& name, const std::string& s) {
    guarded(name, [&] {
      H5::StrType type(H5::PredType::C_S1, std::max<std::size_t>(1, s.size()));
      H5::DataSet ds = file_.createDataSet(name, type, H5::DataSpace(H5S_SCALAR));
      std::string padded = s;
      padded.resize(std::max<std::size_t>(1, s.size()), '\0');
      ds.write(padded.data(), type);
    });
  }
  /// Compressed column (nz = -1).
  template <class Sparse>
  void matrix(const std::string& g, const Sparse& A) {
    SparseMatrix C(A);
    C.makeCompressed();
    group(g);
    integer(g + "/m", int(C.rows()));
    integer(g + "/n", int(C.cols()));
    integer(g + "/nz", -1);
    integer(g + "/nzmax", int(C.nonZeros()));
    ints(g + "/p", C.outerIndexPtr(), hsize_t(C.cols() + 1));
    ints(g + "/i", C.innerIndexPtr(), hsize_t(C.nonZeros()));
    doubles(g + "/x", C.valuePtr(), hsize_t(C.nonZeros()));
  }
  void text(const std::string& g, const ProblemText& t) {
    group(g + "/info");
    string(g + "/info/title", t.title);
    string(g + "/info/description", t.description);
    string(g + "/info/math_info", t.math_info);
  }
  void solution(const std::string& g, const Solution& s) {
    group(g);
    for (auto [name, v] : {std::pair<const char*, const Vector*>{"r", &s.r}, {"u", &s.u},
                           {"v", &s.v}, {"l", &s.l}})
      if (v->size() > 0) vector(g + "/" + name, *v);
  }

 private:
  std::string path_;
  H5::H5File file_;
};

}  // namespace detail

/// Which problem a file holds. Throws IoError if neither group is present.
inline Kind detect_kind(const std::string& path) {
  detail::Reader in(path);
  if (in.exists("fclib_local")) return Kind::Local;
  if (in.exists("fclib_global")) return Kind::Global;
  in.fail("", "neither /fclib_local nor /fclib_global is present");
}

inline LocalProblem read_local(const std::string& path) {
  detail::Reader in(path);
  const std::string g = "fclib_local";
  if (!in.exists(g)) in.fail(g, "missing group (not a local FCLIB problem)");
  if (in.exists(g + "/V") || in.exists(g + "/R"))
    in.fail(g + "/V", "mixed local problems (V, R, s) are not supported");
  LocalProblem p;
  p.d = in.read_spacedim(g);
  // Vectors first: their lengths (data present in the file) bound the
  // matrix sizes the file declares.
  p.q = in.read_doubles(g + "/vectors/q", -1);
  const Index m = p.q.size();
  if (m % p.d != 0)
    in.fail(g + "/vectors/q", "length " + std::to_string(m) + " is not a multiple of spacedim " +
                                  std::to_string(p.d));
  p.mu = in.read_doubles(g + "/vectors/mu", m / p.d);
  p.W = in.read_matrix(g + "/W", m, m);
  p.text = in.read_text(g);
  detail::validate_read(in, g, LocalProblemView(p));
  return p;
}

inline GlobalProblem read_global(const std::string& path) {
  detail::Reader in(path);
  const std::string g = "fclib_global";
  if (!in.exists(g)) in.fail(g, "missing group (not a global FCLIB problem)");
  GlobalProblem p;
  p.d = in.read_spacedim(g);
  // Vectors first: their lengths (data present in the file) bound the
  // matrix sizes the file declares.
  p.f = in.read_doubles(g + "/vectors/f", -1);
  p.w = in.read_doubles(g + "/vectors/w", -1);
  const Index n = p.f.size(), m = p.w.size();
  if (m % p.d != 0)
    in.fail(g + "/vectors/w", "length " + std::to_string(m) + " is not a multiple of spacedim " +
                                  std::to_string(p.d));
  p.mu = in.read_doubles(g + "/vectors/mu", m / p.d);
  p.M = in.read_matrix(g + "/M", n, n);
  p.H = in.read_matrix(g + "/H", n, m);
  if (in.exists(g + "/G")) {
    p.b = in.read_doubles(g + "/vectors/b", -1);
    p.G = in.read_matrix(g + "/G", n, p.b.size());
  }
  p.text = in.read_text(g);
  detail::validate_read(in, g, GlobalProblemView(p));
  return p;
}

inline Problem read_problem(const std::string& path) {
  if (detect_kind(path) == Kind::Local) return read_local(path);
  return read_global(path);
}

/// Runs f() on a problem read from `path`; an InvalidProblem it throws
/// (e.g. a singular M found when factorising) becomes an IoError naming the
/// file and the dataset, as a reading error would.
template <class F>
decltype(auto) with_file_context(const std::string& path, const Problem& problem, F&& f) {
  try {
    return f();
  } catch (const InvalidProblem& e) {
    const std::string group =
        std::holds_alternative<LocalProblem>(problem) ? "fclib_local" : "fclib_global";
    const std::string& field = e.field();
    const bool in_file = field == "W" || field == "q" || field == "mu" || field == "M" ||
                         field == "H" || field == "G" || field == "f" || field == "w" ||
                         field == "b";
    if (!in_file) throw;
    throw IoError(path, detail::dataset_of(group, field), detail::reason_of(e));
  }
}

/// The /solution group, if any (vectors not checked against a problem).
inline std::optional<Solution> read_solution(const std::string& path) {
  detail::Reader in(path);
  return in.read_solution_group("solution");
}

/// The /guesses groups, in order.
inline std::vector<Solution> read_guesses(const std::string& path) {
  detail::Reader in(path);
  std::vector<Solution> out;
  if (!in.exists("guesses")) return out;
  const int count = in.read_int("guesses/number_of_guesses");
  if (count < 0) in.fail("guesses/number_of_guesses", "negative count");
  for (int k = 1; k <= count; ++k) {
    const std::string g = "guesses/" + std::to_string(k);
    auto s = in.read_solution_group(g);
    if (!s) in.fail(g, "missing guess group");
    out.push_back(std::move(*s));
  }
  return out;
}

/// Writes a new file (truncating) holding the local problem.
inline void write_local(const std::string& path, const LocalProblemView& p,
                        const ProblemText& text = {}) {
  validate(p);
  detail::Writer out(path, H5F_ACC_TRUNC);
  const std::string g = "fclib_local";
  out.group(g);
  out.integer(g + "/spacedim", p.d);
  out.matrix(g + "/W", p.W);
  out.group(g + "/vectors");
  out.vector(g + "/vectors/q", p.q);
  out.vector(g + "/vectors/mu", p.mu);
  out.text(g, text);
}
inline void write_local(const std::string& path, const LocalProblem& p) {
  write_local(path, LocalProblemView(p), p.text);
}

inline void write_global(const std::string& path, const GlobalProblemView& p,
                         const ProblemText& text = {}) {
  validate(p);
  detail::Writer out(path, H5F_ACC_TRUNC);
  const std::string g = "fclib_global";
  out.group(g);
  out.integer(g + "/spacedim", p.d);
  out.matrix(g + "/M", p.M);
  out.matrix(g + "/H", p.H);
  if (p.G) out.matrix(g + "/G", *p.G);
  out.group(g + "/vectors");
  out.vector(g + "/vectors/f", p.f);
  out.vector(g + "/vectors/w", p.w);
  out.vector(g + "/vectors/mu", p.mu);
  if (p.b) out.vector(g + "/vectors/b", *p.b);
  out.text(g, text);
}
inline void write_global(const std::string& path, const GlobalProblem& p) {
  write_global(path, GlobalProblemView(p), p.text);
}

inline void write_problem(const std::string& path, const Problem& p) {
  std::visit([&](const auto& pb) {
    using T = std::decay_t<decltype(pb)>;
    if constexpr (std::is_same_v<T, LocalProblem>) write_local(path, pb);
    else write_global(path, pb);
  }, p);
}

namespace detail {
inline unsigned open_flags_for_update(const std::string& path) {
  std::ifstream probe(path, std::ios::binary);
  return probe ? H5F_ACC_RDWR : H5F_ACC_TRUNC;
}
}  // namespace detail

/// Writes (or replaces) /solution in `path`; creates the file if needed.
inline void write_solution(const std::string& path, const Solution& s) {
  detail::Writer out(path, detail::open_flags_for_update(path));
  out.remove_if_exists("solution");
  out.solution("solution", s);
}

/// Writes (or replaces) /guesses in `path`; creates the file if needed.
inline void write_guesses(const std::string& path, const std::vector<Solution>& guesses) {
  detail::Writer out(path, detail::open_flags_for_update(path));
  out.remove_if_exists("guesses");
  out.group("guesses");
  out.integer("guesses/number_of_guesses", int(guesses.size()));
  for (std::size_t k = 0; k < guesses.size(); ++k)
    out.solution("guesses/" + std::to_string(k + 1), guesses[k]);
}

}  // namespace fclib
}  // namespace fcsolve

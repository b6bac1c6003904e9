// Typed exceptions thrown at fcsolve's boundaries (problem validation, file
// input/output, usage). Numerical failure inside a solver is never an
// exception: it is a Status in the solver's info().
#pragma once

#include <stdexcept>
#include <string>

namespace fcsolve {

/// A problem (or a solver argument) that does not describe a valid FC/I or
/// FC/II instance: wrong sizes, non-finite entries, negative mu, ...
/// field() names the offending member ("W", "q", "mu", "M", "H", ...).
class InvalidProblem : public std::invalid_argument {
 public:
  InvalidProblem(std::string field, const std::string& message)
      : std::invalid_argument(field + ": " + message), field_(std::move(field)) {}
  const std::string& field() const noexcept { return field_; }

 private:
  std::string field_;
};

/// A file that cannot be read or written as FCLIB. path() and dataset() say
/// where; what() carries both plus the reason.
class IoError : public std::runtime_error {
 public:
  IoError(std::string path, std::string dataset, const std::string& message)
      : std::runtime_error(path + (dataset.empty() ? "" : ": " + dataset) + ": " + message),
        path_(std::move(path)),
        dataset_(std::move(dataset)) {}
  const std::string& path() const noexcept { return path_; }
  const std::string& dataset() const noexcept { return dataset_; }

 private:
  std::string path_, dataset_;
};

/// A request the library cannot honour as asked: unknown solver name, bad
/// setting value, a solver used on a problem kind it does not support.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace fcsolve

// The one solver contract (docs/architecture.md, "The solver contract"),
// checked at compile time. A solver S of FC/II (Problem = LocalProblemView,
// second vector u = W r + q) or FC/I (Problem = GlobalProblemView, second
// vector v) offers:
//
//   typename S::Settings        default-constructible; member defaults are
//                               the one source of defaults (the catalogue
//                               reads them from there)
//   S& compute(const Problem&)  validates the problem (typed error), prepares
//   const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u_or_v)
//                               r: warm start in, solution out; UsageError
//                               when called before compute()
//   const SolverInfo& info() const
//   Settings& settings(), const Settings& settings() const
//
//   static_assert(fcsolve::satisfies_solver_contract_v<S, LocalProblemView>);
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/types.hpp>

#include <string>
#include <type_traits>
#include <utility>

namespace fcsolve {
namespace contract_detail {

template <class...>
using void_t = void;

template <class S, class Problem, class = void>
struct checks : std::false_type {};

template <class S, class Problem>
struct checks<
    S, Problem,
    void_t<typename S::Settings,
           decltype(std::declval<S&>().compute(std::declval<const Problem&>())),
           decltype(std::declval<S&>().solve(std::declval<Eigen::Ref<Vector>>(),
                                             std::declval<Eigen::Ref<Vector>>())),
           decltype(std::declval<const S&>().info()), decltype(std::declval<S&>().settings()),
           decltype(std::declval<const S&>().settings())>>
    : std::bool_constant<
          std::is_default_constructible_v<typename S::Settings> &&
          std::is_constructible_v<S, const typename S::Settings&> &&
          std::is_same_v<decltype(std::declval<S&>().compute(std::declval<const Problem&>())), S&> &&
          std::is_same_v<decltype(std::declval<S&>().solve(std::declval<Eigen::Ref<Vector>>(),
                                                           std::declval<Eigen::Ref<Vector>>())),
                         const SolverInfo&> &&
          std::is_same_v<decltype(std::declval<const S&>().info()), const SolverInfo&> &&
          std::is_same_v<decltype(std::declval<S&>().settings()), typename S::Settings&> &&
          std::is_same_v<decltype(std::declval<const S&>().settings()),
                         const typename S::Settings&>> {};

}  // namespace contract_detail

/// The argument check every solve() of the contract starts with: compute()
/// was called (`computed`; UsageError naming `solver` otherwise), r (the
/// warm start) has m finite entries and the second vector (`second`: "u" or
/// "v") n entries (InvalidProblem naming the vector otherwise).
inline void check_solve_arguments(const char* solver, bool computed,
                                  const Eigen::Ref<const Vector>& r, Index m,
                                  const Eigen::Ref<const Vector>& second_vector, Index n,
                                  const char* second) {
  if (!computed) throw UsageError(std::string(solver) + "::solve() called before compute()");
  if (r.size() != m)
    throw InvalidProblem("r", "expected " + std::to_string(m) + " entries, got " +
                                  std::to_string(r.size()));
  if (second_vector.size() != n)
    throw InvalidProblem(second, "expected " + std::to_string(n) + " entries, got " +
                                     std::to_string(second_vector.size()));
  if (!r.allFinite()) throw InvalidProblem("r", "warm start is not finite");
}

/// True when S follows the solver contract on problems of type Problem.
template <class S, class Problem>
inline constexpr bool satisfies_solver_contract_v = contract_detail::checks<S, Problem>::value;

}  // namespace fcsolve

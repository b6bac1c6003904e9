// The cone policies, their compile-time check, and the run-time dispatch on a
// problem's contact dimension d (1 frictionless, 2 or 3 Coulomb).
#pragma once

#include <fcsolve/cone/coulomb2d.hpp>
#include <fcsolve/cone/coulomb3d.hpp>
#include <fcsolve/cone/frictionless.hpp>
#include <fcsolve/core/exceptions.hpp>

#include <string>
#include <type_traits>
#include <utility>

namespace fcsolve {

/// A cone policy provides, per contact, dim, Vec, project, project_dual,
/// de_saxce_shift, modified_velocity, contains and contains_dual.
template <class C, class = void>
struct is_cone : std::false_type {};
template <class C>
struct is_cone<C, std::void_t<decltype(C::dim), typename C::Vec, typename C::Scalar,
                              decltype(C::project(std::declval<const typename C::Vec&>(),
                                                  typename C::Scalar())),
                              decltype(C::project_dual(std::declval<const typename C::Vec&>(),
                                                       typename C::Scalar())),
                              decltype(C::de_saxce_shift(std::declval<const typename C::Vec&>(),
                                                         typename C::Scalar()))>>
    : std::true_type {};
template <class C>
inline constexpr bool is_cone_v = is_cone<C>::value;

static_assert(is_cone_v<Coulomb3D> && is_cone_v<Coulomb2D> && is_cone_v<Frictionless>);

/// Calls f(Cone{}) with the cone policy for contact dimension d, so a run-time
/// problem reaches code compiled for exactly its cone and nothing else.
template <class F>
decltype(auto) dispatch_cone(int d, F&& f) {
  switch (d) {
    case 3: return std::forward<F>(f)(Coulomb3D{});
    case 2: return std::forward<F>(f)(Coulomb2D{});
    case 1: return std::forward<F>(f)(Frictionless{});
    default:
      throw InvalidProblem("spacedim", "contact dimension must be 1, 2 or 3, got " +
                                           std::to_string(d));
  }
}

}  // namespace fcsolve

// The interface every one-contact nonsmooth function of the Newton family
// has (AlartCurnierFunction, JeanMoreauFunction, NaturalMapFunction,
// FischerBurmeisterFunction), for a cone policy Cone (cone/cones.hpp):
//   static Vec value(const Vec& r, const Vec& u, double mu, const Vec& rho);
//   static void value_and_jacobian(const Vec& r, const Vec& u, double mu,
//                                  const Vec& rho, Vec& G, Mat& A, Mat& B);
// where dG = A du + B dr is an element of G's generalised Jacobian and
// rho = (rho_N, rho_T, ...) > 0. A function derives from this CRTP base and
// provides evaluate(r, u, mu, rho, G, A*, B*) (A, B null: value only).
#pragma once

#include <fcsolve/cone/cone_types.hpp>

#include <type_traits>
#include <utility>

namespace fcsolve {

template <class Derived, class Cone_>
struct OneContactFunction {
  FCSOLVE_CONE_TYPES(Cone_);

  static Vec value(const Vec& r, const Vec& u, double mu, const Vec& rho) {
    Vec G;
    Derived::evaluate(r, u, mu, rho, G, nullptr, nullptr);
    return G;
  }
  /// G and an element of its generalised Jacobian: dG = A du + B dr.
  static void value_and_jacobian(const Vec& r, const Vec& u, double mu, const Vec& rho, Vec& G,
                                 Mat& A, Mat& B) {
    Derived::evaluate(r, u, mu, rho, G, &A, &B);
  }
};

/// Compile-time check of the interface above.
template <class F, class = void>
struct is_one_contact_function : std::false_type {};
template <class F>
struct is_one_contact_function<
    F, std::void_t<typename F::Vec, typename F::Mat,
                   decltype(F::value(std::declval<const typename F::Vec&>(),
                                     std::declval<const typename F::Vec&>(), 0.0,
                                     std::declval<const typename F::Vec&>())),
                   decltype(F::value_and_jacobian(
                       std::declval<const typename F::Vec&>(), std::declval<const typename F::Vec&>(),
                       0.0, std::declval<const typename F::Vec&>(), std::declval<typename F::Vec&>(),
                       std::declval<typename F::Mat&>(), std::declval<typename F::Mat&>()))>>
    : std::true_type {};
template <class F>
inline constexpr bool is_one_contact_function_v = is_one_contact_function<F>::value;

}  // namespace fcsolve

// The catalogue's one run-time -> compile-time dispatch: a problem's contact
// dimension picks the cone policy (cone/cones.hpp, dispatch_cone) and its
// size picks a dense or a sparse representation, so that every entry
// reaches code compiled for exactly its cone and storage.
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/storage/storage.hpp>

#include <type_traits>
#include <utility>

namespace fcsolve {
namespace registry {

/// Calls f(Cone{}, std::bool_constant<dense>{}) with the cone of contact
/// dimension d.
template <class F>
decltype(auto) dispatch_cone_and_density(int d, bool dense, F&& f) {
  return dispatch_cone(d, [&](auto cone) {
    if (dense) return f(cone, std::true_type{});
    return f(cone, std::false_type{});
  });
}

/// The storage of W for a solver on p: DenseStorage up to
/// kDenseStorageMaxContacts contacts, Sparse<dim> beyond.
template <class Cone_, class Storage_>
struct ConeAndStorage {
  using Cone = Cone_;
  using Storage = Storage_;
};

/// Calls f(ConeAndStorage<Cone, Storage>{}) for problem p (see above).
template <template <int> class Sparse, class F>
decltype(auto) dispatch_cone_and_storage(const LocalProblemView& p, F&& f) {
  return dispatch_cone_and_density(p.d, p.num_contacts() <= kDenseStorageMaxContacts,
                                   [&](auto cone, auto dense) {
                                     using Cone = decltype(cone);
                                     constexpr int D = Cone::dim;
                                     using Storage = std::conditional_t<decltype(dense)::value,
                                                                        DenseStorage<D>, Sparse<D>>;
                                     return f(ConeAndStorage<Cone, Storage>{});
                                   });
}

}  // namespace registry
}  // namespace fcsolve

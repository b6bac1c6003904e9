// One Moreau-Jean step of an elastic scene (elastic_scene.hpp), solved as
// FC/I (M_hat, H, f, w, mu) by a global-native solver, W never formed: the
// semismooth Newton solver (Alart-Curnier function) by default, or ADMM in
// (v, r) (AdmmGlobal: one Cholesky of M + rho H H^T per rho where Newton
// factorises a new Jacobian each iteration; what `fcsolve generate` uses),
// warm-started from the previous step's reactions. f and M_hat: elastodynamics.hpp; w and the index set:
// contact_law.hpp. The last step's problem stays available (global()).
#pragma once

#include <fcsolve/core/timer.hpp>
#include <fcsolve/admm/admm_global.hpp>
#include <fcsolve/newton.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/scenes/elastic_scene.hpp>
#include <fcsolve/scenes/step_report.hpp>
#include <fcsolve/scenes/warm_start.hpp>

#include <vector>

namespace fcsolve::scenes {

/// `Solver`: a global-native solver of the contract on GlobalProblemView
/// (GlobalNewton, AdmmGlobal), its settings' tol and max_iter from StepSettings.
template <class Solver = GlobalNewton<AlartCurnierFunction, Coulomb3D>>
class ElasticStepper {
 public:
  ElasticStepper(ElasticScene& scene, const StepSettings& s)
      : scene_(scene), s_(s), solver_(solver_settings(s)) {
    problem_.d = 3;
    problem_.M = scene.dynamics().M_hat();
  }

  const StepReport& step() {
    LinearElastodynamics& dyn = scene_.dynamics();
    report_ = StepReport();
    report_.step = ++steps_;
    const double t = (double(steps_ - 1) + s_.theta) * s_.h;
    const Vector f = dyn.step_force(scene_.external_force(t));
    v_next_ = dyn.free_velocity(f);

    contacts_.clear();
    std::vector<double> w_normal;
    for (const NodeContact& c : scene_.candidates()) {
      if (!ContactLaw::active(c.gap, ElasticScene::local_velocity(c, v_next_)[0], s_.h)) continue;
      w_normal.push_back(s_.law.normal_offset(c.gap, ElasticScene::local_velocity(c, dyn.velocity())[0], s_.h));
      contacts_.push_back(c);
    }
    const int nc = int(contacts_.size());
    report_.contacts = nc;
    if (nc == 0) {
      warm_.clear();
      r_.resize(0);
      dyn.advance(v_next_);
      return report_;
    }
    triplets_.clear();
    for (int a = 0; a < nc; ++a) ElasticScene::add_columns(contacts_[a], a, triplets_);
    problem_.H.resize(dyn.dofs(), 3 * nc);
    problem_.H.setFromTriplets(triplets_.begin(), triplets_.end());
    problem_.H.makeCompressed();
    problem_.f = f;
    problem_.w = Vector::Zero(3 * nc);
    for (int a = 0; a < nc; ++a) problem_.w[3 * a] = w_normal[a];
    problem_.mu = Vector::Constant(nc, s_.mu);

    const Mat3 frame = ElasticScene::frame();
    r_ = Vector::Zero(3 * nc);
    if (s_.warm_start)
      for (int a = 0; a < nc; ++a) r_.segment<3>(3 * a) = warm_.initial(contacts_[a].key, frame);
    Stopwatch clock;
    solver_.compute(problem_);  // views problem_: it outlives the solve
    report_.info = solver_.solve(r_, v_next_);
    report_.seconds = clock.seconds();

    warm_.begin_record();
    for (int a = 0; a < nc; ++a) warm_.record(contacts_[a].key, frame, r_.segment<3>(3 * a));
    warm_.end_record();
    dyn.advance(v_next_);
    return report_;
  }

  /// The last step's FC/I (M_hat, H, f, w, mu).
  const GlobalProblem& global() const { return problem_; }
  const std::vector<NodeContact>& contacts() const { return contacts_; }
  const Vector& reactions() const { return r_; }
  const Vector& velocity_after() const { return v_next_; }

 private:
  static typename Solver::Settings solver_settings(const StepSettings& s) {
    typename Solver::Settings settings;
    settings.tol = s.tol;
    settings.max_iter = s.max_iter;
    return settings;
  }

  ElasticScene& scene_;
  StepSettings s_;
  Solver solver_;
  WarmStart warm_;
  long steps_ = 0;
  StepReport report_;
  GlobalProblem problem_;
  std::vector<NodeContact> contacts_;
  std::vector<Eigen::Triplet<double, int>> triplets_;
  Vector v_next_, r_;
};

}  // namespace fcsolve::scenes

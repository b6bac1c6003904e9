// One Moreau-Jean step of an elastic scene (elastic_scene.hpp), solved as
// FC/I (M_hat, H, f, w, mu) by fcsolve's global semismooth Newton solver
// (Alart-Curnier function; W never formed), warm-started from the previous
// step's reactions. f and M_hat: elastodynamics.hpp; w and the index set:
// contact_law.hpp. The last step's problem stays available (global()).
#pragma once

#include <fcsolve/core/timer.hpp>
#include <fcsolve/newton.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/scenes/elastic_scene.hpp>
#include <fcsolve/scenes/step_report.hpp>
#include <fcsolve/scenes/warm_start.hpp>

#include <vector>

namespace fcsolve::scenes {

class ElasticStepper {
 public:
  ElasticStepper(ElasticScene& scene, const StepSettings& s)
      : scene_(scene), s_(s), newton_(newton_settings(s)) {
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
    newton_.compute(problem_);  // views problem_: it outlives the solve
    report_.info = newton_.solve(r_, v_next_);
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
  static NewtonSettings newton_settings(const StepSettings& s) {
    NewtonSettings n;
    n.tol = s.tol;
    n.max_iter = s.max_iter;
    return n;
  }

  ElasticScene& scene_;
  StepSettings s_;
  GlobalNewton<AlartCurnierFunction, Coulomb3D> newton_;
  WarmStart warm_;
  long steps_ = 0;
  StepReport report_;
  GlobalProblem problem_;
  std::vector<NodeContact> contacts_;
  std::vector<Eigen::Triplet<double, int>> triplets_;
  Vector v_next_, r_;
};

}  // namespace fcsolve::scenes

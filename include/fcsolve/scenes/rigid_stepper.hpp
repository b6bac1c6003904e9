// One Moreau-Jean step of a rigid-body scene, solved as FC/II by fcsolve's
// NSGS, warm-started from the previous step's reactions (Jean 1999; Acary &
// Brogliato 2008, sec. 10.1). With the diagonal mass matrix M of
// rigid_bodies.hpp, gravity f_ext and the step h:
//   v_free = v + h M^-1 f_ext
//   M v+ = M v + h f_ext + H r,  u = H^T v+ + w           (FC/I: f = M v + h f_ext)
//   W = H^T M^-1 H,  q = H^T v_free + w                   (FC/II, problem/reduction.hpp)
// on the contacts that the index set of contact_law.hpp keeps among the
// scene's candidates within reach of a step's motion. The last step's
// problem stays available (global(), local()) for writing it out.
//
// Scene: bodies() -> RigidBodies&, size() -> a length (search margin),
// candidates(margin) -> std::vector<RigidContact>.
#pragma once

#include <fcsolve/core/timer.hpp>
#include <fcsolve/nsgs.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/scenes/rigid_bodies.hpp>
#include <fcsolve/scenes/step_report.hpp>
#include <fcsolve/scenes/warm_start.hpp>

#include <vector>

namespace fcsolve::scenes {

template <class Scene>
class RigidStepper {
 public:
  RigidStepper(Scene& scene, const StepSettings& s) : scene_(scene), s_(s) {
    nsgs_.settings().tol = s.tol;
    nsgs_.settings().max_iter = s.max_iter;
  }

  const StepReport& step() {
    RigidBodies& bodies = scene_.bodies();
    const VectorMap minv = bodies.inverse_mass();
    V_ = bodies.velocity();
    impulse_ = bodies.gravity_impulse(s_.h, s_.gravity);
    V_next_ = V_ + minv.cwiseProduct(impulse_);  // v_free

    // Index set: candidates within reach of a step's motion (contact_law.hpp).
    const double margin = 0.5 * scene_.size() + 2.0 * s_.h * bodies.max_speed();
    contacts_.clear();
    std::vector<double> w_normal;
    for (const RigidContact& c : scene_.candidates(margin)) {
      if (!ContactLaw::active(c.gap, bodies.local_velocity(c, V_next_)[0], s_.h)) continue;
      w_normal.push_back(s_.law.normal_offset(c.gap, bodies.local_velocity(c, V_)[0], s_.h));
      contacts_.push_back(c);
    }
    const int nc = int(contacts_.size());
    report_ = StepReport();
    report_.step = ++steps_;
    report_.contacts = nc;
    if (nc == 0) {
      warm_.clear();
      r_.resize(0);
      bodies.advance(V_next_, s_.h, s_.theta);
      return report_;
    }
    triplets_.clear();
    for (int a = 0; a < nc; ++a) bodies.add_columns(contacts_[a], a, triplets_);
    H_.resize(bodies.dofs(), 3 * nc);
    H_.setFromTriplets(triplets_.begin(), triplets_.end());
    H_.prune(0.0);  // the frames' zero entries
    H_.makeCompressed();
    w_ = Vector::Zero(3 * nc);
    for (int a = 0; a < nc; ++a) w_[3 * a] = w_normal[a];

    local_.d = 3;
    local_.W = SparseMatrix(H_.transpose()) * (minv.asDiagonal() * H_);
    local_.W.prune(0.0);
    local_.W.makeCompressed();
    local_.q = H_.transpose() * V_next_ + w_;
    local_.mu = Vector::Constant(nc, s_.mu);

    r_ = Vector::Zero(3 * nc);
    Vector u(3 * nc);
    if (s_.warm_start)
      for (int a = 0; a < nc; ++a) r_.segment<3>(3 * a) = warm_.initial(contacts_[a].key, contacts_[a].frame);
    Stopwatch clock;
    nsgs_.compute(local_);
    report_.info = nsgs_.solve(r_, u);
    report_.seconds = clock.seconds();

    V_next_ += minv.cwiseProduct(H_ * r_);  // v+ = v_free + M^-1 H r
    warm_.begin_record();
    for (int a = 0; a < nc; ++a) warm_.record(contacts_[a].key, contacts_[a].frame, r_.segment<3>(3 * a));
    warm_.end_record();
    bodies.advance(V_next_, s_.h, s_.theta);
    return report_;
  }

  /// The last step's FC/I: M = diag(m_i I3, J_i), f = M v + h f_ext (so that
  /// M^-1 f = v_free), H, w, mu.
  GlobalProblem global() const {
    const VectorMap minv = scene_.bodies().inverse_mass();
    const Index n = minv.size();
    GlobalProblem g;
    g.d = 3;
    g.M = SparseMatrix(n, n);
    g.M.reserve(Eigen::VectorXi::Constant(n, 1));
    for (Index i = 0; i < n; ++i) g.M.insert(i, i) = 1.0 / minv[i];
    g.M.makeCompressed();
    g.H = H_;
    g.f = V_.cwiseQuotient(minv) + impulse_;
    g.w = w_;
    g.mu = local_.mu;
    return g;
  }
  /// The last step's FC/II (W, q, mu).
  const LocalProblem& local() const { return local_; }
  const std::vector<RigidContact>& contacts() const { return contacts_; }
  const Vector& reactions() const { return r_; }          ///< the last step's r
  const Vector& velocity_after() const { return V_next_; }  ///< the last step's v+

 private:
  Scene& scene_;
  StepSettings s_;
  Nsgs<Coulomb3D, BlockSparseStorage<3>> nsgs_;  // BSR rows for the sweeps
  WarmStart warm_;
  long steps_ = 0;
  StepReport report_;
  std::vector<RigidContact> contacts_;
  std::vector<Triplet> triplets_;
  SparseMatrix H_;
  Vector V_, V_next_, impulse_, w_, r_;
  LocalProblem local_;
};

}  // namespace fcsolve::scenes

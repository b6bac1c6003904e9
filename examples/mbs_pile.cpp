// A pile of spheres falling into an open box: rigid bodies stepped in time by
// the Moreau-Jean scheme, one FC/II problem per step solved by fcsolve's NSGS
// through its user header, warm-started from the previous step's reactions.
//
//   mbs_pile [--spheres N] [--steps K] [--seed S] [--mu X] [--theta T] [--dt H]
//            [--tol X] [--max-iter N] [--restitution E] [--beta B] [--slop S]
//            [--no-warm-start] [--quiet] [--dump STEP FILE.hdf5] [--dump-local FILE.hdf5]
//
// Prints one line per step (step, contacts, iterations, error, time) and a
// summary; exits with 0 when every step reached --tol, 1 otherwise, 2 on bad
// usage. --dump writes step STEP's FC/I problem (M, H, f, w, mu) with the
// solution found as /solution; --dump-local writes its FC/II reduction too.
//
// Mechanics: include/fcsolve/scenes/ (rigid_bodies.hpp: M, H; sphere_pile.hpp:
// the layout and contact detection; rigid_stepper.hpp: one Moreau-Jean step,
// NSGS on W = H^T M^-1 H, warm start; contact_law.hpp: the index set and w),
// shared with `fcsolve generate sphere-pile`.
#include <fcsolve/scenes/rigid_stepper.hpp>
#include <fcsolve/scenes/sphere_pile.hpp>

#include "stepping/options.hpp"
#include "stepping/settings.hpp"
#include "stepping/step_log.hpp"
#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
#include "stepping/dump.hpp"
#endif

#include <cstdio>
#include <iostream>
#include <string>

namespace {

using fcsolve::scenes::ContactLaw;

struct Parameters {
  Parameters() { law.slop = 0.005 * 0.05; }  // 0.5 % of R0
  long spheres = 200, steps = 200, seed = 1;
  double mu = 0.5, theta = 0.5, h = 2e-3, tol = 1e-8;
  long max_iter = 10000;
  ContactLaw law;
  bool warm_start = true, quiet = false;
  long dump_step = -1;
  std::string dump_file, dump_local_file;
};

Parameters parse(int argc, char** argv) {
  stepping::Options o(argc, argv);
  Parameters p;
  p.spheres = o.integer("spheres", p.spheres);
  p.steps = o.integer("steps", p.steps);
  p.seed = o.integer("seed", p.seed);
  p.mu = o.real("mu", p.mu);
  p.theta = o.real("theta", p.theta);
  p.h = o.real("dt", p.h);
  p.tol = o.real("tol", p.tol);
  p.max_iter = o.integer("max-iter", p.max_iter);
  p.law.restitution = o.real("restitution", p.law.restitution);
  p.law.beta = o.real("beta", p.law.beta);
  p.law.slop = o.real("slop", p.law.slop);
  p.warm_start = !o.flag("no-warm-start");
  p.quiet = o.flag("quiet");
  const auto dump = o.values("dump", 2);
  if (!dump.empty()) {
    p.dump_step = stepping::Options::to_integer("dump", dump[0]);
    p.dump_file = dump[1];
  }
  p.dump_local_file = o.text("dump-local", "");
  o.expect_all_used();
  if (p.spheres < 1 || p.steps < 1 || p.max_iter < 1) throw std::invalid_argument("--spheres, --steps and --max-iter must be positive");
  if (!(p.theta >= 0.5 && p.theta <= 1.0)) throw std::invalid_argument("--theta must be in [1/2, 1]");
  if (!(p.h > 0) || !(p.tol > 0) || !(p.mu >= 0)) throw std::invalid_argument("--dt and --tol must be positive, --mu not negative");
  if (!p.dump_local_file.empty() && p.dump_step < 0) throw std::invalid_argument("--dump-local needs --dump STEP FILE");
#ifndef FCSOLVE_EXAMPLES_WITH_FCLIB
  if (p.dump_step >= 0) throw std::invalid_argument("--dump needs HDF5: build with the fcsolve::fclib target");
#endif
  return p;
}

int run(const Parameters& p) {
  fcsolve::scenes::SpherePileLayout layout;
  layout.spheres = p.spheres;
  layout.seed = p.seed;
  fcsolve::scenes::SpherePile pile(layout);
  std::printf("# mbs_pile spheres=%ld steps=%ld seed=%ld mu=%g theta=%g dt=%g tol=%g box=%.3f "
              "restitution=%g beta=%g slop=%g warm_start=%d\n",
              p.spheres, p.steps, p.seed, p.mu, p.theta, p.h, p.tol, pile.box(), p.law.restitution,
              p.law.beta, p.law.slop, int(p.warm_start));
  fcsolve::scenes::RigidStepper<fcsolve::scenes::SpherePile> stepper(pile, stepping::step_settings(p));
  stepping::StepLog log(p.quiet);
  bool dumped = false;
  for (long step = 1; step <= p.steps; ++step) {
    const fcsolve::scenes::StepReport& s = stepper.step();
    log.step(s);
    if (s.contacts == 0) continue;
#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
    if (step == p.dump_step) {
      fcsolve::GlobalProblem global = stepper.global();
      const std::string params = "spheres=" + std::to_string(p.spheres) + " seed=" +
                                 std::to_string(p.seed) + " mu=" + std::to_string(p.mu) +
                                 " theta=" + std::to_string(p.theta) + " dt=" + std::to_string(p.h) +
                                 " restitution=" + std::to_string(p.law.restitution) +
                                 " beta=" + std::to_string(p.law.beta) + " slop=" +
                                 std::to_string(p.law.slop) + " step=" + std::to_string(step);
      global.text.title = "mbs_pile step " + std::to_string(step);
      global.text.description = "fcsolve examples/mbs_pile.cpp: spheres falling into an open box; " + params;
      global.text.math_info =
          "Moreau-Jean step: M v+ = f + H r, f = M v + h f_ext, u = H^T v+ + w, "
          "w_N = e min(u_N,0) + beta min(gap+slop,0)/h; solution: NSGS on W = H^T M^-1 H";
      stepping::dump_global(p.dump_file, global, stepper.reactions(), stepper.velocity_after());
      if (!p.dump_local_file.empty()) {
        fcsolve::LocalProblem local = stepper.local();
        local.text = global.text;
        stepping::dump_local(p.dump_local_file, local, stepper.reactions());
      }
      std::printf("# dumped step %ld (%ld contacts) to %s\n", step, s.contacts, p.dump_file.c_str());
      dumped = true;
    }
#endif
  }
  log.summary();
  if (p.dump_step >= 0 && !dumped) {
    std::cerr << "mbs_pile: nothing dumped: step " << p.dump_step << " has no contact or is not simulated\n";
    return 1;
  }
  return log.all_converged() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Parameters p;
  try {
    p = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "mbs_pile: " << e.what() << "\n";
    return 2;
  }
  try {
    return run(p);
  } catch (const std::exception& e) {
    std::cerr << "mbs_pile: " << e.what() << "\n";
    return 3;
  }
}

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
#include <string>

namespace {

struct Parameters : stepping::SteppingParameters {
  Parameters() {
    steps = 200;
    max_iter = 10000;
    h = 2e-3;
    law.slop = 0.005 * 0.05;  // 0.5 % of R0
  }
  long spheres = 200, seed = 1;
};

Parameters parse(int argc, char** argv) {
  stepping::Options o(argc, argv);
  Parameters p;
  p.read(o, /*with_restitution=*/true);
  p.spheres = o.integer("spheres", p.spheres);
  p.seed = o.integer("seed", p.seed);
  o.expect_all_used();
  if (p.spheres < 1) throw std::invalid_argument("--spheres must be positive");
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
  return stepping::run_steps("mbs_pile", stepper, p.steps, p.quiet, p.dump.step,
                             [&](long step, long contacts) {
#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
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
    stepping::dump_step(p.dump.file, p.dump.local_file, global, [&] { return stepper.local(); },
                        stepper.reactions(), stepper.velocity_after(), step, contacts);
#else
    (void)step, (void)contacts;  // --dump is refused without HDF5 (stepping/options.hpp)
#endif
  });
}

}  // namespace

int main(int argc, char** argv) { return stepping::example_main("mbs_pile", argc, argv, parse, run); }

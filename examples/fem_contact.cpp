// An elastic block pressed on a rigid plane: linear hexahedra (small strain)
// stepped in time by the Moreau-Jean scheme, one FC/I problem
// (M_hat, H, f, w, mu) per step solved natively (W never formed) by fcsolve's
// global semismooth Newton solver through its user header, warm-started from
// the previous step's reactions.
//
//   fem_contact [--nx 8] [--ny 8] [--nz 4] [--steps K] [--mu X] [--theta T] [--dt H]
//               [--young E] [--poisson NU] [--pressure P] [--shear S] [--consistent-mass]
//               [--tol X] [--max-iter N] [--beta B] [--slop S]
//               [--no-warm-start] [--quiet] [--dump STEP FILE.hdf5] [--dump-local FILE.hdf5]
//
// Prints one line per step (step, contacts, iterations, error, time) and a
// summary; exits with 0 when every step reached --tol, 1 otherwise, 2 on bad
// usage. --dump writes step STEP's FC/I problem with the solution found as
// /solution; --dump-local writes its FC/II reduction W = H^T M_hat^-1 H too.
//
// Mechanics. The block [0, Lx] x [0, Ly] x [0, Lz] starts at rest a little
// above the plane z = 0. It carries gravity and, on its top face, a pressure
// P and a shear traction S P along x, both ramped up over the first half of
// the run; its bottom nodes are node-to-plane contacts (normal e_z, tangents
// e_x, e_y). The mesh, M, K, the scheme (M_hat = M + h^2 theta^2 K, f) and
// the step solved by GlobalNewton live in include/fcsolve/scenes/
// (hex_mesh.hpp, elastodynamics.hpp, elastic_scene.hpp, elastic_stepper.hpp),
// shared with `fcsolve generate fem-block`.
#include <fcsolve/scenes/elastic_stepper.hpp>

#include "stepping/options.hpp"
#include "stepping/settings.hpp"
#include "stepping/step_log.hpp"
#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
#include <fcsolve/problem/reduction.hpp>

#include "stepping/dump.hpp"
#endif

#include <cstdio>
#include <string>
#include <vector>

namespace {

struct Parameters : stepping::SteppingParameters {
  long nx = 8, ny = 8, nz = 4;
  double size_x = 0.4, size_y = 0.4, size_z = 0.2;  // m
  double young = 1e6, poisson = 0.3;  // Pa, -
  double pressure = 5e4, shear = 0.45;  // Pa on the top face; shear traction = shear * pressure
  double initial_gap = 1e-4;  // m
  bool consistent_mass = false;
};

Parameters parse(int argc, char** argv) {
  stepping::Options o(argc, argv);
  Parameters p;
  p.read(o, /*with_restitution=*/false);
  p.nx = o.integer("nx", p.nx);
  p.ny = o.integer("ny", p.ny);
  p.nz = o.integer("nz", p.nz);
  p.young = o.real("young", p.young);
  p.poisson = o.real("poisson", p.poisson);
  p.pressure = o.real("pressure", p.pressure);
  p.shear = o.real("shear", p.shear);
  p.consistent_mass = o.flag("consistent-mass");
  o.expect_all_used();
  if (p.nx < 1 || p.ny < 1 || p.nz < 1) throw std::invalid_argument("--nx, --ny and --nz must be positive");
  if (!(p.mu > 0) || !(p.young > 0) || !(p.poisson > -1 && p.poisson < 0.5))
    throw std::invalid_argument("--mu and --young must be positive, --poisson in (-1, 1/2)");
  return p;
}

int run(const Parameters& p) {
  fcsolve::scenes::HexBlock block;
  block.origin = fcsolve::scenes::Vec3(0, 0, p.initial_gap);
  block.size = fcsolve::scenes::Vec3(p.size_x, p.size_y, p.size_z);
  block.nx = p.nx;
  block.ny = p.ny;
  block.nz = p.nz;
  block.material.young = p.young;
  block.material.poisson = p.poisson;
  fcsolve::scenes::ElasticLoad load;
  load.h = p.h;
  load.theta = p.theta;
  load.pressure = p.pressure;
  load.shear = p.shear;
  load.ramp_time = 0.5 * double(p.steps) * p.h;
  load.consistent_mass = p.consistent_mass;
  fcsolve::scenes::ElasticScene scene({block}, load);
  std::printf("# fem_contact nx=%ld ny=%ld nz=%ld dofs=%ld steps=%ld mu=%g theta=%g dt=%g tol=%g "
              "young=%g poisson=%g pressure=%g shear=%g mass=%s beta=%g slop=%g warm_start=%d\n",
              p.nx, p.ny, p.nz, long(scene.dynamics().dofs()), p.steps, p.mu, p.theta, p.h, p.tol,
              p.young, p.poisson, p.pressure, p.shear, p.consistent_mass ? "consistent" : "lumped",
              p.law.beta, p.law.slop, int(p.warm_start));
  fcsolve::scenes::ElasticStepper stepper(scene, stepping::step_settings(p));
  return stepping::run_steps("fem_contact", stepper, p.steps, p.quiet, p.dump.step,
                             [&](long step, long contacts) {
#ifdef FCSOLVE_EXAMPLES_WITH_FCLIB
    fcsolve::GlobalProblem problem = stepper.global();
    problem.text.title = "fem_contact step " + std::to_string(step);
    problem.text.description =
        "fcsolve examples/fem_contact.cpp: elastic block (trilinear hexahedra, " +
        std::string(p.consistent_mass ? "consistent" : "lumped") + " mass) pressed on a rigid plane; nx=" +
        std::to_string(p.nx) + " ny=" + std::to_string(p.ny) + " nz=" + std::to_string(p.nz) +
        " mu=" + std::to_string(p.mu) + " theta=" + std::to_string(p.theta) + " dt=" +
        std::to_string(p.h) + " young=" + std::to_string(p.young) + " poisson=" +
        std::to_string(p.poisson) + " pressure=" + std::to_string(p.pressure) + " shear=" +
        std::to_string(p.shear) + " step=" + std::to_string(step);
    problem.text.math_info =
        "Moreau-Jean step: M_hat v+ = f + H r, M_hat = M + h^2 theta^2 K, "
        "f = M v - h K (x + h theta (1-theta) v) + h f_ext, u = H^T v+ + w, "
        "w_N = beta min(gap+slop,0)/h; solution: GlobalNewton (Alart-Curnier)";
    const auto reduce = [&] { return fcsolve::GlobalReduction<fcsolve::DefaultBackend>(problem).local(); };
    stepping::dump_step(p.dump.file, p.dump.local_file, problem, reduce,
                        stepper.reactions(), stepper.velocity_after(), step, contacts);
#else
    (void)step, (void)contacts;  // --dump is refused without HDF5 (stepping/options.hpp)
#endif
  });
}

}  // namespace

int main(int argc, char** argv) { return stepping::example_main("fem_contact", argc, argv, parse, run); }

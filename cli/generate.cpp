// `fcsolve generate`: scenes stepped in time, one step's problem written as
// FCLIB. Why native (and not a Python module): the scenes reach 10^5
// contacts, each step is solved by fcsolve's own solvers and written by its
// FCLIB writer, and one binary does it all (README "Generated scenes").
//
// The snapshot: the step whose number of contacts is closest to the target
// (the latest among equals). Rigid scenes stop at the first step that
// reaches the target (bodies still falling and settling), or 20 steps after
// the best one (settled short of it); elastic scenes run all their steps
// (the top load ramps up, the block starts to slide).
//
// The trajectory is solved as engines do, with a budget: NSGS to 1e-4 within
// 50 sweeps per step (rigid), GlobalNewton to 1e-6 within 20 iterations
// (elastic). A step that stops short still advances: the state carries that
// error, the written problem is exact for that state.
#include "generate.hpp"

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/scenes/box_layouts.hpp>
#include <fcsolve/scenes/elastic_stepper.hpp>
#include <fcsolve/scenes/mixed_shapes.hpp>
#include <fcsolve/scenes/rigid_stepper.hpp>
#include <fcsolve/scenes/sphere_pile.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>

namespace fcsolve_cli {

namespace {

using namespace fcsolve;
using namespace fcsolve::scenes;

/// The FC/II of an elastic scene has W = H^T M_hat^-1 H dense (M_hat^-1 is):
/// --local-out stops at this many contacts (W: 3 nc x 3 nc doubles, 160 MB).
constexpr long kMaxDenseLocalContacts = 1500;

struct SceneInfo {
  const char* name;
  bool elastic;
  double default_mass_ratio;
  const char* what;
};

const SceneInfo kScenes[] = {
    {"sphere-pile", false, 1, "spheres (radius 0.04..0.06 m) falling into an open box; every 7th sphere mass_ratio times denser"},
    {"box-stack", false, 1, "columns of 0.1 m cubes, 4 contacts per face; the top box of a column mass_ratio times denser"},
    {"wall", false, 1, "running-bond wall of 0.2 x 0.1 x 0.06 m bricks, rows offset by half a brick; top row mass_ratio times denser"},
    {"tower", false, 1, "Kapla-style towers of 0.12 x 0.024 x 0.008 m planks, 3 per level crossed at right angles (12 contacts per face); top level mass_ratio times denser"},
    {"mixed-shapes", false, 1, "spheres (radius 0.04..0.06 m) and boxes (half extents 0.03..0.05 m), half of each, falling into an open box; every 7th body mass_ratio times denser"},
    {"heavy-on-light", false, 1e3, "columns of 0.1 m cubes whose upper half is mass_ratio times denser than the lower"},
    {"fem-block", true, 1, "elastic block of trilinear hexahedra (lumped mass, E = 1e6 Pa, nu = 0.3) pressed and sheared on a rigid plane, node-to-plane contacts"},
    {"fem-two-bodies", true, 1, "elastic block pressed and sheared on a larger elastic block lying on a rigid plane: node-to-surface (non-matching meshes) and node-to-plane contacts; upper block mass_ratio times denser"},
};

const SceneInfo& scene_info(const std::string& name) {
  for (const SceneInfo& s : kScenes)
    if (name == s.name) return s;
  std::string list;
  for (const SceneInfo& s : kScenes) list += std::string(list.empty() ? "" : ", ") + s.name;
  throw UsageError("generate: unknown scene '" + name + "' (scenes: " + list + ")");
}

/// Rigid scenes stop this many steps after the last step that came closer.
constexpr long kPatience = 20;

/// The snapshot kept along the trajectory.
struct Snapshot {
  long step = 0, contacts = -1;
  GlobalProblem global;
  std::optional<LocalProblem> local;
};

struct Trajectory {
  Snapshot best;
  long steps_run = 0, bodies = 0;
  double h = 0;
};

/// Steps `stepper` up to `steps` times, keeping the step closest to
/// `target` (file comment); `keep(snapshot)` copies the step's problem.
template <class Stepper, class Keep>
void run_steps(Stepper& stepper, long target, long steps, bool stop_at_target, Trajectory& t, Keep keep) {
  long improved = 0;  // the last step that came closer to the target
  for (long k = 1; k <= steps; ++k) {
    const StepReport& s = stepper.step();
    t.steps_run = k;
    if (s.contacts == 0) continue;
    const long distance = std::labs(s.contacts - target);
    if (t.best.contacts < 0 || distance < std::labs(t.best.contacts - target)) improved = k;
    if (t.best.contacts < 0 || distance <= std::labs(t.best.contacts - target)) {
      t.best.step = k;
      t.best.contacts = s.contacts;
      keep(t.best);
    }
    if (stop_at_target && (s.contacts >= target || k - improved >= kPatience)) break;
  }
}

StepSettings trajectory_settings(const GenerateRequest& r, bool elastic) {
  StepSettings s;
  s.mu = r.mu;
  s.law.beta = r.penetration_correction;
  s.law.slop = 0;
  s.warm_start = true;
  s.h = elastic ? 1e-3 : 2e-3;
  s.tol = elastic ? 1e-6 : 1e-4;
  s.max_iter = elastic ? 2000 : 50;  // elastic: ADMM iterations (run_elastic)
  return s;
}

template <class Scene>
void run_rigid(Scene& scene, const GenerateRequest& r, StepSettings s, long steps, Trajectory& t) {
  t.bodies = scene.bodies().count();
  t.h = s.h;
  RigidStepper<Scene> stepper(scene, s);
  const bool want_local = !r.local_out.empty();
  run_steps(stepper, r.contacts, steps, true, t, [&](Snapshot& snap) {
    snap.global = stepper.global();
    if (want_local) snap.local = stepper.local();
  });
}

/// The piles falling into the open box (sphere-pile, mixed-shapes), seeded
/// and weighted from the request, stepped with h = 5 ms.
template <class Scene, class Layout>
void run_pile(Layout layout, const GenerateRequest& r, StepSettings s, Trajectory& t) {
  layout.seed = r.seed;
  layout.mass_ratio = r.mass_ratio;
  Scene pile(layout);
  s.h = 5e-3;
  run_rigid(pile, r, s, r.steps, t);
}

/// Bodies for about `contacts` contacts at `small` contacts per body below
/// 100 contacts, `large` from there.
long bodies_for(long contacts, double small, double large) {
  return std::max(1L, long(std::ceil(double(contacts) / (contacts < 100 ? small : large))));
}

/// fem-block: an (n+1) x (n+1) grid of bottom nodes ~ target contacts.
ElasticScene fem_scene(const GenerateRequest& r, const StepSettings& s, long steps, bool two_bodies,
                       long& bodies) {
  Uniform uni(std::uint32_t(r.seed));
  ElasticLoad load;
  load.h = s.h;
  load.theta = s.theta;
  load.pressure = 5e4 * uni(0.8, 1.2);
  load.shear = 0.45 * uni(0.8, 1.2);
  load.shear_angle = uni(0.0, 2 * 3.14159265358979323846);
  load.ramp_time = 0.5 * double(steps) * s.h;
  const auto grid = [](double nodes) { return std::max(1L, long(std::lround(std::sqrt(nodes))) - 1); };
  const double gap = 2e-5;  // contact from the second step: each contact step costs factorisations
  HexBlock lower;
  std::vector<HexBlock> blocks;
  if (!two_bodies) {
    lower.size = Vec3(0.4, 0.4, 0.2);
    lower.nx = lower.ny = grid(double(r.contacts));
    lower.nz = std::clamp(lower.nx / 8, 1L, 2L);  // thin: the Newton matrix grows with the volume
    lower.origin = Vec3(0, 0, gap);
    blocks.push_back(lower);
  } else {
    lower.size = Vec3(0.4, 0.4, 0.1);
    lower.nx = lower.ny = grid(0.5 * double(r.contacts));
    lower.nz = std::clamp(lower.nx / 8, 1L, 2L);
    lower.origin = Vec3(0, 0, gap);
    HexBlock upper;
    upper.size = Vec3(0.24, 0.24, 0.1);
    upper.nx = upper.ny = grid(0.5 * double(r.contacts));
    upper.nz = std::clamp(upper.nx / 8, 1L, 2L);
    upper.material.density *= r.mass_ratio;
    const double dy = uni(-0.03, 0.03);  // last coordinate first (scenes/geometry.hpp, Uniform)
    const double dx = uni(-0.03, 0.03);
    upper.origin = Vec3(0.08 + dx, 0.08 + dy, gap + lower.size.z() + gap);
    blocks = {lower, upper};
  }
  bodies = long(blocks.size());
  return ElasticScene(std::move(blocks), load);
}

void run_elastic(const GenerateRequest& r, StepSettings s, long steps, bool two_bodies, Trajectory& t) {
  ElasticScene scene = fem_scene(r, s, steps, two_bodies, t.bodies);
  t.h = s.h;
  // ADMM in (v, r): 2 to 5 times faster than the global Newton on these
  // scenes, and the only one that steps 10^5 contacts (docs/results.md)
  ElasticStepper<AdmmGlobal<Coulomb3D>> stepper(scene, s);
  run_steps(stepper, r.contacts, steps, false, t, [&](Snapshot& snap) { snap.global = stepper.global(); });
}

std::string number(double x) {
  std::ostringstream o;
  o.precision(6);
  o << x;
  return o.str();
}

}  // namespace

const std::vector<std::string>& scene_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const SceneInfo& s : kScenes) v.push_back(s.name);
    return v;
  }();
  return names;
}

int generate(const GenerateRequest& request) {
  GenerateRequest r = request;
  const SceneInfo& info = scene_info(r.scene);
  if (r.contacts < 4 || r.contacts > 200000) throw UsageError("generate: --contacts must be in [4, 200000]");
  if (r.seed < 0 || r.seed > 4294967295L) throw UsageError("generate: --seed must be in [0, 2^32 - 1]");
  if (!(r.mu >= 0 && r.mu <= 2)) throw UsageError("generate: --mu must be in [0, 2]");
  if (r.mass_ratio < 0) r.mass_ratio = info.default_mass_ratio;
  else if (!(r.mass_ratio >= 1 && r.mass_ratio <= 1e4)) throw UsageError("generate: --mass-ratio must be in [1, 1e4]");
  if (r.scene == "fem-block" && r.mass_ratio != 1)
    throw UsageError("generate: fem-block has one body: --mass-ratio does not apply");
  if (!(r.penetration_correction >= 0 && r.penetration_correction <= 1))
    throw UsageError("generate: --penetration-correction must be in [0, 1]");
  if (r.steps == 0) r.steps = info.elastic ? 8 : 400;
  if (r.steps < 1 || r.steps > 100000) throw UsageError("generate: --steps must be in [1, 100000]");
  if (r.out.empty() && r.local_out.empty()) throw UsageError("generate: give --out FILE.hdf5 and/or --local-out FILE.hdf5");
  if (r.out == r.local_out) throw UsageError("generate: --out and --local-out must be different files");
  if (info.elastic && !r.local_out.empty() && r.contacts > kMaxDenseLocalContacts)
    throw UsageError("generate: the FC/II reduction of " + r.scene + " has a dense W (M_hat^-1 is dense): --local-out needs --contacts <= " +
                     std::to_string(kMaxDenseLocalContacts));

  Stopwatch clock;
  const StepSettings s = trajectory_settings(r, info.elastic);
  Trajectory t;
  if (r.scene == "sphere-pile") {
    SpherePileLayout layout;
    // settled piles hold ~1.6 (small) to ~2.3 (large) contacts per sphere
    layout.spheres = bodies_for(r.contacts, 1.5, 2.0);
    run_pile<SpherePile>(layout, r, s, t);
  } else if (r.scene == "mixed-shapes") {
    MixedShapesLayout layout;
    // a pile of 200 bodies settles with ~3.5 contacts per body (boxes 4 per
    // face patch), a few bodies on the floor with fewer
    layout.bodies = bodies_for(r.contacts, 2.0, 3.0);
    run_pile<MixedShapes>(layout, r, s, t);
  } else if (!info.elastic) {
    BoxLayout layout;
    layout.contacts = r.contacts;
    layout.seed = r.seed;
    layout.mass_ratio = r.mass_ratio;
    BoxScene scene = r.scene == "box-stack"        ? box_stack(layout)
                     : r.scene == "wall"           ? brick_wall(layout)
                     : r.scene == "tower"          ? kapla_towers(layout)
                                                   : heavy_on_light(layout);
    StepSettings bs = s;
    if (r.scene == "tower") bs.h = 1e-3;  // 8 mm planks
    run_rigid(scene, r, bs, r.steps, t);
  } else {
    run_elastic(r, s, r.steps, r.scene == "fem-two-bodies", t);
  }
  if (t.best.contacts <= 0) {  // nothing to write: not a usage error, not a crash
    std::fprintf(stderr, "fcsolve: generate: no contact in %ld steps (raise --steps); nothing written\n", t.steps_run);
    return 1;
  }
  const double seconds = clock.seconds();

  Snapshot& snap = t.best;
  const std::string params =
      "scene=" + r.scene + " contacts_target=" + std::to_string(r.contacts) + " nc=" + std::to_string(snap.contacts) +
      " seed=" + std::to_string(r.seed) + " mu=" + number(r.mu) + " mass_ratio=" + number(r.mass_ratio) +
      " penetration_correction=" + number(r.penetration_correction) + " steps=" + std::to_string(r.steps) +
      " step=" + std::to_string(snap.step) + " h=" + number(t.h) + " theta=0.5 bodies=" + std::to_string(t.bodies);
  ProblemText text;
  text.title = "fcsolve generate " + r.scene + " nc=" + std::to_string(snap.contacts) + " seed=" + std::to_string(r.seed);
  text.description = "fcsolve " FCSOLVE_VERSION_STRING " generate: " + std::string(info.what) + "; step " +
                     std::to_string(snap.step) + " of a Moreau-Jean trajectory; " + params;
  text.math_info = info.elastic
                       ? "Moreau-Jean step (Jean 1999; Acary & Brogliato 2008, sec. 10.1): M_hat v+ = f + H r, "
                         "M_hat = M + h^2 theta^2 K, f = M v - h K (x + h theta (1-theta) v) + h f_ext, "
                         "u = H^T v+ + w, w_N = beta min(gap,0)/h, w_T = 0"
                       : "Moreau-Jean step (Jean 1999; Acary & Brogliato 2008, sec. 10.1): M v+ = f + H r, "
                         "M = diag(m I3, J), f = M v + h f_ext, u = H^T v+ + w, w_N = beta min(gap,0)/h, w_T = 0; "
                         "FC/II: W = H^T M^-1 H, q = H^T M^-1 f + w";
  snap.global.text = text;
  if (!r.out.empty()) fclib::write_global(r.out, snap.global);
  if (!r.local_out.empty()) {
    LocalProblem local = snap.local ? std::move(*snap.local)
                                    : GlobalReduction<DefaultBackend>(snap.global).local();
    local.text = text;
    fclib::write_local(r.local_out, local);
  }
  std::printf("scene=%s nc=%ld n=%ld bodies=%ld step=%ld steps_run=%ld seed=%ld mu=%g mass_ratio=%g "
              "penetration_correction=%g seconds=%.3f",
              r.scene.c_str(), snap.contacts, long(snap.global.M.rows()), t.bodies, snap.step, t.steps_run,
              r.seed, r.mu, r.mass_ratio, r.penetration_correction, seconds);
  if (!r.out.empty()) std::printf(" out=%s", r.out.c_str());
  if (!r.local_out.empty()) std::printf(" local_out=%s", r.local_out.c_str());
  std::printf("\n");
  return 0;
}

}  // namespace fcsolve_cli

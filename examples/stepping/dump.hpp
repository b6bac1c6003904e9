// --dump: one step's problem as an FCLIB file, with the example's own
// solution stored as /solution, so that `fcsolve error FILE FILE` and
// shared/tools/fcref.py can judge it. Needs the fcsolve::fclib target (HDF5).
#pragma once

#include <fcsolve/io/fclib.hpp>

#include <cstdio>
#include <string>

namespace stepping {

/// FC/I (M, H, f, w, mu) and /solution {r, u = H^T v + w, v}.
inline void dump_global(const std::string& path, const fcsolve::GlobalProblem& p,
                        const fcsolve::Vector& r, const fcsolve::Vector& v) {
  fcsolve::fclib::write_global(path, p);
  fcsolve::fclib::Solution s;
  s.r = r;
  s.v = v;
  s.u = p.H.transpose() * v + p.w;
  fcsolve::fclib::write_solution(path, s);
}

/// FC/II (W, q, mu) and /solution {r, u = W r + q}.
inline void dump_local(const std::string& path, const fcsolve::LocalProblem& p,
                       const fcsolve::Vector& r) {
  fcsolve::fclib::write_local(path, p);
  fcsolve::fclib::Solution s;
  s.r = r;
  s.u = p.W * r + p.q;
  fcsolve::fclib::write_solution(path, s);
}

/// --dump of one step: FC/I to global_path and, when local_path is set, the
/// FC/II that make_local() builds from it, both with the example's solution.
template <class MakeLocal>
void dump_step(const std::string& global_path, const std::string& local_path,
               const fcsolve::GlobalProblem& global, MakeLocal make_local,
               const fcsolve::Vector& r, const fcsolve::Vector& v, long step, long contacts) {
  dump_global(global_path, global, r, v);
  if (!local_path.empty()) {
    fcsolve::LocalProblem local = make_local();
    local.text = global.text;
    dump_local(local_path, local, r);
  }
  std::printf("# dumped step %ld (%ld contacts) to %s\n", step, contacts, global_path.c_str());
}

}  // namespace stepping

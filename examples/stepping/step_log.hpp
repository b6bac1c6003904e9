// The per-step table the time-stepping examples print, and its summary. The
// format is read by examples/check_stepping.py:
//   # <header lines>
//   step contacts iterations error time_s setup_s status
//   ...
//   # summary steps=K converged=K iterations=... time_s=... setup_s=... contacts=...
// time_s is the solver's whole time for the step (setup and solve), setup_s
// its compute() part (storage of W, factorisations), which a warm start
// cannot shorten.
#pragma once

#include <fcsolve/core/status.hpp>
#include <fcsolve/scenes/step_report.hpp>

#include <cstdio>
#include <string>

namespace stepping {

class StepLog {
 public:
  explicit StepLog(bool quiet = false) : quiet_(quiet) {
    std::printf("# step contacts iterations error time_s setup_s status\n");
  }

  /// One line per step. A step without contacts counts as converged.
  void step(long k, long contacts, int iterations, double error, double seconds,
            double setup_seconds, const std::string& status, bool converged) {
    ++steps_;
    converged_ += converged ? 1 : 0;
    iterations_ += iterations;
    seconds_ += seconds;
    setup_seconds_ += setup_seconds;
    contacts_ += contacts;
    if (!quiet_)
      std::printf("%ld %ld %d %.3e %.3e %.3e %s\n", k, contacts, iterations, error, seconds,
                  setup_seconds, status.c_str());
  }

  /// The line of a stepper's step (no-contact when it had none).
  void step(const fcsolve::scenes::StepReport& s) {
    if (s.contacts == 0) step(s.step, 0, 0, 0.0, 0.0, 0.0, "no-contact", true);
    else
      step(s.step, s.contacts, s.info.iterations, s.info.error, s.seconds, s.info.setup_seconds,
           fcsolve::to_string(s.info.status), s.info.converged());
  }

  void summary() const {
    std::printf("# summary steps=%ld converged=%ld iterations=%lld time_s=%.6f setup_s=%.6f contacts=%lld\n",
                steps_, converged_, iterations_, seconds_, setup_seconds_, contacts_);
    std::fflush(stdout);
  }
  bool all_converged() const { return converged_ == steps_; }

 private:
  bool quiet_;
  long steps_ = 0, converged_ = 0;
  long long iterations_ = 0, contacts_ = 0;
  double seconds_ = 0, setup_seconds_ = 0;
};

/// The time loop of an example: `steps` steps of the stepper, a logged line
/// each, and dump(step, contacts) at step dump_step when it has contacts.
/// Returns the example's exit status: 1 when a step failed or the dump step
/// was never reached, else 0.
template <class Stepper, class Dump>
int run_steps(const char* example, Stepper& stepper, long steps, bool quiet, long dump_step,
              Dump dump) {
  StepLog log(quiet);
  bool dumped = false;
  for (long step = 1; step <= steps; ++step) {
    const fcsolve::scenes::StepReport& s = stepper.step();
    log.step(s);
    if (s.contacts == 0 || step != dump_step) continue;
    dump(step, long(s.contacts));
    dumped = true;
  }
  log.summary();
  if (dump_step >= 0 && !dumped) {
    std::fprintf(stderr, "%s: nothing dumped: step %ld has no contact or is not simulated\n", example,
                 dump_step);
    return 1;
  }
  return log.all_converged() ? 0 : 1;
}

}  // namespace stepping

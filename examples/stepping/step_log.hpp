// The per-step table the time-stepping examples print, and its summary. The
// format is read by examples/check_stepping.py:
//   # <header lines>
//   step contacts iterations error time_s status
//   ...
//   # summary steps=K converged=K iterations=... time_s=... contacts=...
#pragma once

#include <cstdio>
#include <string>

namespace stepping {

class StepLog {
 public:
  explicit StepLog(bool quiet = false) : quiet_(quiet) {
    std::printf("# step contacts iterations error time_s status\n");
  }

  /// One line per step. A step without contacts counts as converged.
  void step(long k, long contacts, int iterations, double error, double seconds,
            const std::string& status, bool converged) {
    ++steps_;
    converged_ += converged ? 1 : 0;
    iterations_ += iterations;
    seconds_ += seconds;
    contacts_ += contacts;
    if (!quiet_)
      std::printf("%ld %ld %d %.3e %.3e %s\n", k, contacts, iterations, error, seconds,
                  status.c_str());
  }

  void summary() const {
    std::printf("# summary steps=%ld converged=%ld iterations=%lld time_s=%.6f contacts=%lld\n",
                steps_, converged_, iterations_, seconds_, contacts_);
    std::fflush(stdout);
  }
  bool all_converged() const { return converged_ == steps_; }

 private:
  bool quiet_;
  long steps_ = 0, converged_ = 0;
  long long iterations_ = 0, contacts_ = 0;
  double seconds_ = 0;
};

}  // namespace stepping

// Reads an untrusted FCLIB file once in a child process before the CLI reads
// it for real. fcsolve's reader checks everything it reads, but the HDF5
// library itself (Debian's 1.10.8) can crash or allocate without bound while
// parsing corrupt metadata (object headers, local heaps): fuzzing found such
// files, and h5py crashes on them too. A child that dies turns into a clear
// IoError (exit 2) instead of a signal in the parent; reading is
// deterministic, so a child that comes back clean means the parent's read is
// safe. Costs one extra read of the file (milliseconds for FCLIB files).
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/io/fclib.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>

namespace fcsolve_cli {

/// Address-space limit of the probing child: far above what any FCLIB file
/// this machine can solve needs, far below what a runaway allocation asks.
inline constexpr rlim_t kProbeAddressSpace = rlim_t(4) << 30;

/// The child's exit code when the problem read cleanly and only /solution
/// or /guesses did not (a clean error, which those commands report).
inline constexpr int kGroupsFailed = 4;

/// Reads `path` (its problem unless `with_problem` is false, its solution and
/// guesses) in a child process. Returns
/// normally when the child read it cleanly (the caller then reads it itself,
/// safely: reading is deterministic); otherwise throws the child's IoError, or
/// an IoError saying that the HDF5 library died. The parent never re-reads a
/// file the child failed on (a read that exhausted the child's memory limit
/// would exhaust the parent's memory).
inline void probe_read_in_child(const std::string& path, bool with_problem = true) {
  int channel[2];
  if (pipe(channel) != 0) return;  // cannot isolate: read in-process as before
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) {
    close(channel[0]);
    close(channel[1]);
    return;
  }
  if (pid == 0) {
    close(channel[0]);
#if !defined(__SANITIZE_ADDRESS__)  // AddressSanitizer reserves terabytes of shadow memory
    const rlimit limit{kProbeAddressSpace, kProbeAddressSpace};
    setrlimit(RLIMIT_AS, &limit);
#endif
    std::string report;  // "dataset\0message" of a clean failure
    int code = 0;
    bool problem_read = !with_problem;
    try {
      if (with_problem) (void)fcsolve::fclib::read_problem(path);
      problem_read = true;
      // The solution and guesses are probed too (the HDF5 library can die
      // there as well); a clean error in them is left to the commands that
      // read them (exit code kGroupsFailed: the parent goes on).
      code = kGroupsFailed;
      (void)fcsolve::fclib::read_solution(path);
      (void)fcsolve::fclib::read_guesses(path);
      code = 0;
    } catch (const fcsolve::IoError& e) {
      const std::string what = e.what(), prefix = path + (e.dataset().empty() ? "" : ": " + e.dataset()) + ": ";
      report = e.dataset() + '\0' + (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what);
      if (!problem_read) code = 2;
    } catch (const std::exception& e) {
      report = std::string() + '\0' + e.what();
      if (!problem_read) code = 2;
    }
    for (std::size_t done = 0; done < report.size();) {
      const ssize_t n = write(channel[1], report.data() + done, report.size() - done);
      if (n <= 0) break;
      done += std::size_t(n);
    }
    _exit(code);
  }
  close(channel[1]);
  std::string report;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(channel[0], buffer, sizeof buffer);
    if (n > 0) report.append(buffer, std::size_t(n));
    else if (n == 0 || errno != EINTR) break;
  }
  close(channel[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return;
  }
  if (WIFSIGNALED(status))
    throw fcsolve::IoError(path, "",
                           std::string("corrupt HDF5 metadata: the HDF5 library died reading it (") +
                               strsignal(WTERMSIG(status)) + ")");
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0 && WEXITSTATUS(status) != kGroupsFailed) {
    const std::size_t split = report.find('\0');
    if (split == std::string::npos)
      throw fcsolve::IoError(path, "", "the reading process failed (exit status " +
                                           std::to_string(WEXITSTATUS(status)) + ")");
    throw fcsolve::IoError(path, report.substr(0, split), report.substr(split + 1));
  }
}

}  // namespace fcsolve_cli

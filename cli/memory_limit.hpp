// The CLI's address space is capped at the machine's physical memory, so that
// a problem too large for the machine ends in "fcsolve: out of memory" (exit
// 3, from std::bad_alloc) or in a solver's failed factorisation, not in the
// kernel's OOM killer: `fcsolve check` on a sphere pile of 10^5 contacts
// (FC/II) grew to 24 GB on a machine of 23 GB and was killed by it
// (docs/results.md, stop 67). Linux overcommits, so without a limit malloc
// rarely fails.
#pragma once

#include <sys/resource.h>
#include <unistd.h>

namespace fcsolve_cli {

/// The machine's physical memory in bytes, 0 if unknown.
inline rlim_t physical_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? rlim_t(pages) * rlim_t(page) : 0;
}

/// Lowers the soft RLIMIT_AS to the physical memory where it is unlimited
/// (a limit the caller set, e.g. `ulimit -v`, is kept, above or below);
/// the hard limit is untouched. Not under AddressSanitizer, which reserves
/// terabytes of shadow memory.
inline void cap_address_space_at_physical_memory() {
#if !defined(__SANITIZE_ADDRESS__)
  const rlim_t physical = physical_memory();
  rlimit limit{};
  if (physical == 0 || getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur != RLIM_INFINITY) return;
  if (limit.rlim_max != RLIM_INFINITY && limit.rlim_max < physical) return;
  limit.rlim_cur = physical;
  setrlimit(RLIMIT_AS, &limit);
#endif
}

}  // namespace fcsolve_cli

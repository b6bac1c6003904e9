#!/usr/bin/env bash
# Replays each input that made the fuzzer fail and says whose defect it is:
# "libhdf5" when the first frame below the C library, the sanitizer runtime
# and libFuzzer is inside the HDF5 library (Debian's 1.10.8 crashes or
# allocates without bound on some corrupt metadata; see
# fuzz/regressions/README.md), "fcsolve" otherwise. Exit status 1 if any
# input is fcsolve's.
#
# An out-of-memory on the RSS limit ("used: N Mb") prints the live heap, not
# the allocation that made the peak: when that peak was transient (freed
# before libFuzzer's once-a-second check), the live heap is libFuzzer's own
# and the first frame left is main(), which says nothing. Such an input is
# replayed with a malloc limit of a quarter of the RSS limit, so the first
# large allocation stops it with its own stack.
#   bash fuzz/classify.sh FUZZER INPUT...
set -uo pipefail
fuzzer=$1; shift
rss_limit_mb=${FCSOLVE_FUZZ_RSS_MB:-2048}  # as .ci/fuzz.sh runs it

# Replays one input; prints its log, returns its exit status.
replay() {  # INPUT [EXTRA FUZZER FLAGS...]
  local input=$1; shift
  ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1 \
    "$fuzzer" -rss_limit_mb=$rss_limit_mb -timeout=60 "$@" "$input" 2>&1
}

# The first stack frame that belongs to neither the C library, the
# allocator, the sanitizer runtime, libFuzzer nor main().
culprit_frame() {
  grep -E '^ +#[0-9]+ ' \
    | grep -vE ' in (__)?(mem(cpy|move|set|cmp)|str[a-z]*|malloc|calloc|realloc|free|operator new)|__interceptor|__asan|__sanitizer|libc\.so|libFuzzer|fuzzer::| in main |sanitizer_common' \
    | head -1
}

ours=0
for input in "$@"; do
  name=$(basename "$input")
  log=$(replay "$input")
  status=$?
  if [[ $status -eq 0 ]]; then
    echo "fuzz: $name: does not reproduce"
    continue
  fi
  frame=$(culprit_frame <<<"$log")
  if [[ -z $frame ]] && grep -q 'libFuzzer: out-of-memory (used:' <<<"$log"; then
    log=$(replay "$input" -malloc_limit_mb=$((rss_limit_mb / 4)))
    frame=$(culprit_frame <<<"$log")
    echo "fuzz: $name: a transient peak over the RSS limit; replayed with a malloc limit of $((rss_limit_mb / 4)) MB"
  fi
  if grep -q 'libhdf5' <<<"$frame"; then
    echo "fuzz: $name: libhdf5 defect: $(sed -E 's/ +/ /g' <<<"$frame" | cut -c1-120)"
  else
    echo "fuzz: $name: FCSOLVE DEFECT (exit $status): ${frame:-no stack}"
    grep -E 'ERROR|SUMMARY' <<<"$log" | head -3
    grep -E '^ +#[0-9]+ ' <<<"$log" | head -12
    ours=1
  fi
done
exit $ours

#!/usr/bin/env bash
# Replays each input that made the fuzzer fail and says whose defect it is:
# "libhdf5" when the first frame below the C library and the sanitizer
# runtime is inside the HDF5 library (Debian's 1.10.8 crashes or allocates
# without bound on some corrupt metadata; see fuzz/regressions/README.md),
# "fcsolve" otherwise. Exit status 1 if any input is fcsolve's.
#   bash fuzz/classify.sh FUZZER INPUT...
set -uo pipefail
fuzzer=$1; shift
ours=0
for input in "$@"; do
  log=$(ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1 \
        "$fuzzer" -rss_limit_mb=2048 -timeout=60 "$input" 2>&1)
  status=$?
  if [[ $status -eq 0 ]]; then
    echo "fuzz: $(basename "$input"): does not reproduce"
    continue
  fi
  frame=$(grep -E '^ +#[0-9]+ ' <<<"$log" \
          | grep -vE ' in (__)?(mem(cpy|move|set|cmp)|str[a-z]*|malloc|calloc|realloc|free|operator new)|__interceptor|__asan|__sanitizer|libc\.so|libFuzzer|fuzzer::|sanitizer_common' \
          | head -1)
  if grep -q 'libhdf5' <<<"$frame"; then
    echo "fuzz: $(basename "$input"): libhdf5 defect: $(sed -E 's/ +/ /g' <<<"$frame" | cut -c1-120)"
  else
    echo "fuzz: $(basename "$input"): FCSOLVE DEFECT (exit $status): ${frame:-no stack}"
    grep -E 'ERROR|SUMMARY' <<<"$log" | head -3
    ours=1
  fi
done
exit $ours

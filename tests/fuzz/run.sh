#!/usr/bin/env bash
# Builds the libFuzzer harnesses with clang under ASan+UBSan (in build-fuzz/) and runs each for
# a bounded time (see seconds_for). The seed corpus in tests/fuzz/corpus/ is only read; what the
# fuzzer learns goes to build-fuzz/corpus/, crashing inputs to build-fuzz/artifacts/. Exits
# non-zero on any finding.
# Usage: tests/fuzz/run.sh [SECONDS_PER_HARNESS (default 60)] [HARNESS...]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-60}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(scene obj partial job_request query job_patch texture)
build=build-fuzz
# A request target and a one-field PATCH body are small inputs whose parsers the fuzzer covers
# quickly: they get half the time (CI's run.sh 60 then takes one minute more for both, not two).
seconds_for() {
  case $1 in
    query | job_patch) echo $((seconds > 1 ? seconds / 2 : seconds)) ;;
    *) echo "$seconds" ;;
  esac
}

CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGLINT_BUILD_TESTS=OFF -DGLINT_BUILD_BENCH=OFF -DGLINT_BUILD_FUZZ=ON \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer" \
  >/dev/null
cmake --build "$build" -j2 --target "${harnesses[@]/#/fuzz_}"

export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
for h in "${harnesses[@]}"; do
  mkdir -p "$build/corpus/$h" "$build/artifacts/$h"
  echo "fuzz: $h for $(seconds_for "$h")s"
  # -rss_limit_mb: a parser that needs more than 2 GB for a small input is a finding too.
  "$build/tests/fuzz/fuzz_$h" "$build/corpus/$h" "tests/fuzz/corpus/$h" -max_total_time="$(seconds_for "$h")" -timeout=10 \
    -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/artifacts/$h/" \
    2>"$build/fuzz_$h.log" || { tail -n 60 "$build/fuzz_$h.log"; echo "fuzz: $h found a crash (input in $build/artifacts/$h/)"; exit 1; }
  grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec|^stat::peak_rss_mb' "$build/fuzz_$h.log" |
    sed "s/^/fuzz: $h /"
done
echo "fuzz: no findings"

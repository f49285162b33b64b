#!/bin/bash
# Builds the whole suite with AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer
# (-DHAIRFIT_SANITIZE=ON) and runs it with ctest; exits 1 if ctest fails or any program (a test
# or a `hairfit` it started) made a sanitizer report.
#
#   tests/sanitize.sh [CTEST ARGS ...]     e.g. tests/sanitize.sh -R corpus
#
# Build folder: $HAIRFIT_SANITIZE_BUILD (default build-asan at the repository root); 40 minutes
# or more of building on two cores the first time. Any report stops the program that made it
# (halt_on_error) with exit code 99, which no test expects, and goes to a file in
# build-asan/sanitizer-reports/: a `hairfit` started by a test whose exit code the test does not
# look at cannot hide a report. Debian's shared stb, tinyobjloader and Ceres are not
# instrumented: only our code and the headers it compiles are checked (the fuzz targets in fuzz/
# compile stb_image and tinyobjloader in).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${HAIRFIT_SANITIZE_BUILD:-$root/build-asan}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHAIRFIT_SANITIZE=ON >/dev/null || exit 1
cmake --build "$build" -j2 || exit 1

reports=$build/sanitizer-reports
rm -rf "$reports" && mkdir -p "$reports"
common="halt_on_error=1:exitcode=99:log_path=$reports/report"
export ASAN_OPTIONS=${ASAN_OPTIONS:-$common:detect_leaks=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-$common:print_stacktrace=1}
# Instrumented code runs several times slower than a Release build; the slowest tests need more
# than ctest's default 1500 s per test.
(cd "$build" && ctest --output-on-failure --timeout 3600 "$@")
status=$?
for report in "$reports"/report.*; do
  [ -e "$report" ] || continue
  echo "=== sanitizer report $report"
  cat "$report"
  status=1
done
exit $status

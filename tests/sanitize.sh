#!/bin/bash
# Builds the whole suite with AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer
# (-DHAIRFIT_SANITIZE=ON) and runs it with ctest; exits with ctest's status.
#
#   tests/sanitize.sh [CTEST ARGS ...]     e.g. tests/sanitize.sh -R corpus
#
# Build folder: $HAIRFIT_SANITIZE_BUILD (default build-asan at the repository root); about 20
# minutes of building on two cores the first time. Any report stops the program that made it
# (halt_on_error), so a sanitizer finding fails its test. Debian's shared stb, tinyobjloader and
# Ceres are not instrumented: only our code and the headers it compiles are checked (the fuzz
# targets in fuzz/ compile stb_image and tinyobjloader in).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${HAIRFIT_SANITIZE_BUILD:-$root/build-asan}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHAIRFIT_SANITIZE=ON >/dev/null || exit 1
cmake --build "$build" -j2 || exit 1
export ASAN_OPTIONS=${ASAN_OPTIONS:-halt_on_error=1:detect_leaks=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}
cd "$build" && ctest --output-on-failure "$@"

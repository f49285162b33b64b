#!/bin/bash
# Builds the libFuzzer targets of fuzz/ (clang, AddressSanitizer, UndefinedBehaviorSanitizer) and
# runs each for a bounded time, one after the other.
#
#   tests/fuzz.sh [SECONDS] [TARGET ...]     SECONDS per target (default 60); targets: scene obj png
#
# Build folder: $HAIRFIT_FUZZ_BUILD (default build-fuzz at the repository root). The growing corpus
# stays in BUILD/fuzz-corpus/TARGET between runs; seeds come from the fixtures and tests/corpus.
# A crash leaves its input in BUILD/fuzz-artifacts/ and makes the script exit 1: reproduce it with
# `BUILD/fuzz/fuzz_TARGET FILE`, then add the input to tests/corpus with a test and fix the loader.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
targets=${*:-scene obj png}
build=${HAIRFIT_FUZZ_BUILD:-$root/build-fuzz}

# The compiler is given only at the first configure: naming it again makes CMake wipe the cache.
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
    -DHAIRFIT_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null || exit 1
fi
for t in $targets; do cmake --build "$build" -j2 --target "fuzz_$t" || exit 1; done

seeds() {  # the committed inputs each target starts from
  case $1 in
    scene) ls "$root"/fixtures/*/*.toml "$root"/spec/example.toml "$root"/tests/corpus/scenes/*.toml \
              "$root"/tests/corpus/accepted/*.toml ;;
    obj) ls "$root"/tests/corpus/data/*.obj ;;
    png) ls "$root"/tests/corpus/data/*.png "$root"/fixtures/maps/*.png ;;
  esac
}

status=0
for t in $targets; do
  corpus=$build/fuzz-corpus/$t
  mkdir -p "$corpus" "$build/fuzz-artifacts"
  seeds "$t" | while read -r f; do cp -n "$f" "$corpus/seed-$(basename "$f")"; done
  options=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1
           -artifact_prefix="$build/fuzz-artifacts/$t-")
  if [ "$t" = scene ]; then  # TOML punctuation and every key name of the reference scene
    { cat "$root/fuzz/toml.dict"
      grep -oE '^[a-z_]+ =|^\[[a-z_.]+\]' "$root/spec/example.toml" | sed 's/ =$//; s/.*/"&"/'; } >"$build/fuzz-scene.dict"
    options+=(-dict="$build/fuzz-scene.dict")
  fi
  echo "== fuzz_$t for ${seconds} s"
  if ! "$build/fuzz/fuzz_$t" "${options[@]}" "$corpus" 2>"$build/fuzz-$t.log"; then
    status=1
    echo "fuzz_$t FOUND A CRASH: see $build/fuzz-$t.log and $build/fuzz-artifacts/"
  fi
  grep -E '^stat::number_of_executed_units|^#[0-9]+[[:space:]]+DONE' "$build/fuzz-$t.log" | tail -2
done
exit $status

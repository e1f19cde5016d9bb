#!/usr/bin/env bash
# Fuzzes the input readers with libFuzzer: the scenario reader (TOML), the
# particle CSV reader, the checkpoint decoder and the STL reader (with the
# mesh built and one sphere's contacts), each for a bounded time, with
# AddressSanitizer and UndefinedBehaviorSanitizer. Not part of CI.
#     bash scripts/fuzz.sh [SECONDS_PER_TARGET]     (default 60)
# Builds into build-fuzz/ with clang; installs clang and libclang-rt-14-dev
# (the libFuzzer runtime) if missing. Seeds: the examples and the corpus of
# bad files (tests/data/bad), the STL files of tests/data/stl, and a
# checkpoint of a tiny drum run. Findings (crashes, leaks, timeouts,
# out-of-memory) are written as build-fuzz/TARGET-findings/crash-*; the
# script then exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
bash scripts/install-deps.sh clang libclang-rt-14-dev

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DTUMBLE_FUZZ=ON \
  -DTUMBLE_TESTS=OFF >/dev/null
cmake --build build-fuzz -j2 --target fuzz_scenario fuzz_particle_csv fuzz_checkpoint fuzz_stl

seeds=build-fuzz/seeds
rm -rf "$seeds"
mkdir -p "$seeds/fuzz_scenario" "$seeds/fuzz_particle_csv" "$seeds/fuzz_checkpoint" "$seeds/fuzz_stl"
cp examples/*.toml tests/data/bad/*.toml "$seeds/fuzz_scenario/"
cp examples/*.csv tests/data/bad/*.csv "$seeds/fuzz_particle_csv/"
cp tests/data/stl/*.stl "$seeds/fuzz_stl/"
if [ -x build/tumble ]; then  # a real checkpoint to start from (the normal build)
  rm -rf "$seeds/drum"
  build/tumble drum -q --mode self --grains 4 --length 0.02 --diameter 0.02 --revolutions 0.1 --no-plot \
    --out "$seeds/drum" --stop-at-step 50 >"$seeds/drum.log" 2>&1 || true  # exits 4: stopped as asked
  cp "$seeds"/drum/checkpoints/*.tck "$seeds/fuzz_checkpoint/" 2>/dev/null || true
fi
if ! compgen -G "$seeds/fuzz_checkpoint/*.tck" >/dev/null; then
  echo "fuzz: no real checkpoint among the seeds (build/tumble missing, or its run failed: $seeds/drum.log)" >&2
fi

status=0
for target in fuzz_scenario fuzz_particle_csv fuzz_checkpoint fuzz_stl; do
  corpus=build-fuzz/corpus/$target findings=build-fuzz/$target-findings
  mkdir -p "$corpus" "$findings"
  echo "fuzz: $target for $seconds s" >&2
  extra=()
  [ "$target" = fuzz_checkpoint ] && extra=(-use_value_profile=1)
  if ! "build-fuzz/tests/fuzz/$target" "$corpus" "$seeds/$target" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
      -artifact_prefix="$findings/" -print_final_stats=1 "${extra[@]}" 2>"build-fuzz/$target.log"; then
    echo "fuzz: $target found a problem: $(ls "$findings") (log: build-fuzz/$target.log)" >&2
    status=1
  fi
  tail -n 3 "build-fuzz/$target.log" >&2
done
exit $status

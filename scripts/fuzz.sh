#!/usr/bin/env bash
# Long fuzzing runs: every libFuzzer target (fuzz/fuzz_*.cpp), or those named, for SECONDS each
# (default 600), in the sanitizer build (./build-san). The corpus grows in build-san/fuzz/long/
# and is kept between runs; a crash leaves its input there (crash-*), to be minimised
# (TARGET -minimize_crash=1 -runs=10000 CRASH) and kept in fuzz/regressions/<target>/.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]     e.g. scripts/fuzz.sh 3600 pfm scene_json
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
CC=clang-14 CXX=clang++-14 cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DLFCAM_SANITIZE=ON -DLFCAM_BUILD_BENCH=OFF >/dev/null
cmake --build build-san
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in fuzz/fuzz_*.cpp; do n=$(basename "$f" .cpp); targets+=("${n#fuzz_}"); done
fi
seeds=build-san/fuzz/seeds
[ -d "$seeds" ] || scripts/fuzz_seeds.sh build-san/lfcam "$seeds" ../shared/data
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/fuzz/lsan.supp}
status=0
for t in "${targets[@]}"; do
  echo "== fuzz_$t for $seconds s"
  parallel=()
  [ -n "${LFCAM_FUZZ_JOBS:-}" ] && parallel=(-fork="$LFCAM_FUZZ_JOBS")  # processes per target
  fuzz/run_one.sh "build-san/fuzz/fuzz_$t" "$seeds" "build-san/fuzz/long/$t" "$seconds" "${parallel[@]}" || status=1
done
exit $status

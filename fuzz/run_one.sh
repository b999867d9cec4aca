#!/usr/bin/env bash
# Runs one fuzz target for a bounded time: first every regression input (fuzz/regressions/NAME) and
# seed, then new inputs. New corpus entries go to WORK/corpus (never into the source tree); a crash
# leaves its input in WORK/ and fails the run.
# Usage: fuzz/run_one.sh TARGET_EXECUTABLE SEEDS_FOLDER WORK_FOLDER SECONDS [libFuzzer flags...]
set -euo pipefail
binary=$1 seeds=$2 work=$3 seconds=$4
shift 4
name=$(basename "$binary")
name=${name#fuzz_}
regressions="$(cd "$(dirname "$0")" && pwd)/regressions/$name"
mkdir -p "$work/corpus" "$seeds/$name" "$regressions"
exec "$binary" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=262144 \
  -print_final_stats=1 -artifact_prefix="$work/" "$@" "$work/corpus" "$regressions" "$seeds/$name"

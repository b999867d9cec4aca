#!/usr/bin/env bash
# The paper's experiments at full size (minutes each, not part of the tests): one report folder
# per experiment under OUT (default ./experiments), plus an index.
#   scripts/experiments.sh [OUT] [LFCAM]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-experiments}
lfcam=${2:-build/lfcam}
[ -x "$lfcam" ] || scripts/build.sh
mkdir -p "$out"
for name in fnumber-match observer-range sharpness-vs-n refocus-limit snr; do
  echo "== $name"
  start=$(date +%s)
  "$lfcam" experiment "$name" -o "$out/$name"
  echo "   $(( $(date +%s) - start )) s: $out/$name/report.html"
done
{
  echo "# The paper's experiments, reproduced by lfcam"
  echo
  for name in fnumber-match observer-range sharpness-vs-n refocus-limit snr; do
    echo "- [$name]($name/report.md): \`$(tr -d '\n ' < "$out/$name/results.json" | cut -c1-160)...\`"
  done
} > "$out/index.md"
echo "index: $out/index.md"

#!/usr/bin/env bash
# Load test of `lfcam view` (issue 9): wrk on loopback against a running viewer, bounded in time
# and connections, mixing focus-slider renders (varied slopes: cache misses), clicks (focus
# search + render) and page/API requests. Reports requests/s, p50/p99 latency, errors (socket
# errors and non-2xx answers) and the server's peak memory (VmHWM).
#
#   bench/viewer_load.sh [LFCAM] [INPUT] [SECONDS] [CONNECTIONS]
# Defaults: build/lfcam, ../shared/data/hci-antinous (else a 9x9x512x512 layered-planes field
# made with `lfcam synth`), 20 s, 8 connections.
set -euo pipefail
cd "$(dirname "$0")/.."
lfcam="${1:-build/lfcam}"
input="${2:-../shared/data/hci-antinous}"
seconds="${3:-20}"
connections="${4:-8}"
work="$(mktemp -d)"
server=""
cleanup() {
  [ -n "$server" ] && kill "$server" 2>/dev/null && wait "$server" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

command -v wrk >/dev/null || { echo "viewer_load.sh: wrk is missing (scripts/setup.sh installs it)" >&2; exit 1; }
if [ ! -e "$input" ]; then
  echo "viewer_load.sh: $input is absent; using a 9x9x512x512 layered-planes light field" >&2
  input="$work/planes.lf.h5"
  "$lfcam" synth -o "$input" --views 9 --size 512
fi

"$lfcam" view "$input" --port 0 >"$work/out" 2>"$work/err" &
server=$!
for _ in $(seq 1200); do
  grep -q 'http://' "$work/out" 2>/dev/null && break
  kill -0 "$server" 2>/dev/null || { echo "viewer_load.sh: lfcam view failed: $(cat "$work/err")" >&2; exit 1; }
  sleep 0.1
done
url="$(grep -o 'http://[^ ]*/' "$work/out")"
echo "server: $url (pid $server), input $input"

cat >"$work/mix.lua" <<'LUA'
-- A user's mix: 60% slider renders at varied slopes, 25% clicks, 15% cheap requests.
local counter = 0
request = function()
  counter = counter + 1
  local r = counter % 20
  if r < 12 then
    local slope = -1.5 + (counter * 0.0173) % 3.0
    return wrk.format("GET", string.format("/api/image?slope=%.4f&f-number=%d", slope, 1 + counter % 4))
  elseif r < 17 then
    return wrk.format("GET", string.format("/api/image?focus-at=%d,%d", 20 + (counter * 37) % 470, 20 + (counter * 53) % 470))
  elseif r < 19 then
    return wrk.format("GET", "/api/status")
  else
    return wrk.format("GET", "/")
  end
end
LUA

wrk --threads 2 --connections "$connections" --duration "${seconds}s" --timeout 10s --latency \
    --script "$work/mix.lua" "$url" | tee "$work/wrk"
peak="$(awk '/VmHWM/ {print $2, $3}' "/proc/$server/status")"
rss="$(awk '/VmRSS/ {print $2, $3}' "/proc/$server/status")"
alive=$(curl -s -o /dev/null -w '%{http_code}' "${url}api/info" 2>/dev/null || echo "none")

requests="$(awk '/Requests\/sec/ {print $2}' "$work/wrk")"
p50="$(awk '$1 == "50%" {print $2}' "$work/wrk")"
p99="$(awk '$1 == "99%" {print $2}' "$work/wrk")"
socketErrors="$(awk -F'[ ,]+' '/Socket errors/ {print $4 "+" $6 "+" $8 "+" $10}' "$work/wrk")"
non2xx="$(awk '/Non-2xx/ {print $5}' "$work/wrk")"
echo "summary: ${requests:-?} requests/s, p50 ${p50:-?}, p99 ${p99:-?}, socket errors (connect+read+write+timeout) ${socketErrors:-0}, non-2xx ${non2xx:-0}, server peak memory ${peak:-?} (now ${rss:-?}), /api/info after the test: $alive"

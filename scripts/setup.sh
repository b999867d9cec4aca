#!/usr/bin/env bash
# Installs every build and test dependency of lfcam from Debian 12's packages.
# Idempotent: apt-get install -y of named packages; nothing is downloaded from anywhere else.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  python3              # tests/module_includes: the check of module boundaries
  python3-dev pybind11-dev python3-numpy python3-pytest  # the Python package (python/) and its tests
  python3-dask python3-distributed  # lfcam batch --dask / lfcam.batch.run(client=): one task per capture on a Dask cluster
  python3-h5py         # tests/h5py: the native .lf.h5 as Python users read it
  python3-tqdm         # progress=True of the Python package's long calls: a tqdm bar (a widget in Jupyter)
  clang-format-14      # tests/format: the check of the one style (.clang-format)
  ccache               # repeat builds (scripts/build.sh, build-san) reuse earlier compiles
  libpng-dev libjpeg-dev libtiff-dev libopenexr-dev libgif-dev  # image formats: their own libraries (docs/design.md, "Start-up")
  libhdf5-dev          # the native .lf.h5 light-field file
  libdeflate-dev       # its chunks, deflated and inflated by lfcam's own threads
  libaec-dev           # szip (libsz): its 8- and 16-bit chunks, HDF5's own filter, coded by lfcam's threads
  zlib1g-dev libzstd-dev  # bench/native_codec_bench: the codecs it could have used instead
  libeigen3-dev        # least-squares fits (lenslet grid)
  nlohmann-json3-dev   # metadata, scene and grid JSON
  libpugixml-dev       # Raytrix calibration XML (focused plenoptic cameras)
  libcli11-dev         # the command line
  libtbb-dev           # threads
  libhwy-dev           # SIMD with run-time dispatch
  libraw-dev           # camera raw files
  libfftw3-dev         # Fourier slice refocusing
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev  # MP4 animations (H.264 by libx264)
  libssl-dev           # SHA-1 of Lytro container sections
  libarchive-dev       # tar archives of Lytro calibration data (lfcam whites index)
  libgtest-dev libgmock-dev libbenchmark-dev
  clang-14 libclang-rt-14-dev  # sanitizer build and libFuzzer targets (scripts/test_sanitized.sh, scripts/fuzz.sh)
  libcpp-httplib-dev   # the viewer's local web server (header-only)
  chromium             # browser tests of the viewer (driven by playwright-core, tests/browser)
  wrk                  # load test of the viewer (bench/viewer_load.sh)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# playwright-core for the browser tests (tests/browser), pinned by its package-lock.json; it
# drives Debian's chromium above and downloads no browser. Node and npm come from the machine
# (NodeSource); Debian's npm package is not used, as it conflicts with NodeSource's.
browser_tests="$(cd "$(dirname "$0")/.." && pwd)/tests/browser"
if ! command -v npm >/dev/null; then
  echo "setup.sh: npm is missing, so the browser tests (label browser) cannot be installed" >&2
elif [ ! -f "$browser_tests/node_modules/.package-lock.json" ] ||
     [ "$browser_tests/package-lock.json" -nt "$browser_tests/node_modules/.package-lock.json" ]; then
  (cd "$browser_tests" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error)
fi

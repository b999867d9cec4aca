#!/usr/bin/env bash
# Installs every build and test dependency of lfcam from Debian 12's packages.
# Idempotent: apt-get install -y of named packages; nothing is downloaded from anywhere else.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev   # image files: PNG, TIFF, OpenEXR, JPEG
  libhdf5-dev          # the native .lf.h5 light-field file
  libeigen3-dev        # least-squares fits (lenslet grid)
  nlohmann-json3-dev   # metadata, scene and grid JSON
  libcli11-dev         # the command line
  libtbb-dev           # threads
  libhwy-dev           # SIMD with run-time dispatch
  libraw-dev           # camera raw files
  libfftw3-dev         # Fourier slice refocusing
  libssl-dev           # SHA-1 of Lytro container sections
  libgtest-dev libgmock-dev libbenchmark-dev
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

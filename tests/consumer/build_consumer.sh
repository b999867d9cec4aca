#!/usr/bin/env bash
# Installs lfcam from BUILD_DIR into a scratch prefix, then configures, builds and runs the programs
# in tests/consumer against it with find_package(lfcam), as a user of the library would: consumer.cpp,
# and the README's C++ example (its first ```cpp block), run on a light field lfcam synth makes.
set -euo pipefail
build_dir=$1
here=$(cd "$(dirname "$0")" && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build_dir" --prefix "$scratch/prefix" >/dev/null
awk '/^```cpp$/ {inside = 1; next} /^```$/ && inside {exit} inside' "$here/../../README.md" >"$scratch/readme_example.cpp"
if [ ! -s "$scratch/readme_example.cpp" ]; then
  echo "README.md has no \`\`\`cpp example" >&2
  exit 1
fi
cmake -S "$here" -B "$scratch/build" -G Ninja -DCMAKE_PREFIX_PATH="$scratch/prefix" \
  -DREADME_EXAMPLE="$scratch/readme_example.cpp" >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/consumer"
"$build_dir/lfcam" synth --views 5 --size 32 -o "$scratch/planes.lf.h5" >/dev/null
"$scratch/build/readme_example" "$scratch/planes.lf.h5" "$scratch/photo.png"
test -s "$scratch/photo.png"
echo "the README's example wrote a photograph"

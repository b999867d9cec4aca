#!/usr/bin/env bash
# Builds the seed corpora of the fuzz targets (fuzz/) at run time, one folder per target, from
# files lfcam writes itself and from the real data in ../shared/data (read, never copied into the
# project). Usage: scripts/fuzz_seeds.sh LFCAM_EXECUTABLE OUTPUT_FOLDER [SHARED_DATA_FOLDER]
set -euo pipefail
lfcam=$1
out=$2
data=${3:-"$(cd "$(dirname "$0")/.." && pwd)/../shared/data"}
rm -rf "$out"
mkdir -p "$out"
scratch="$out/scratch"
mkdir -p "$scratch"
seed() { mkdir -p "$out/$1"; cp "$2" "$out/$1/${3:-$(basename "$2")}"; }
# A folder as one input: "LFCAMFILE <name>\n<content>" per file (fuzz/fuzz_support.hpp).
pack() {
  local folder=$1 target=$2 name=$3
  mkdir -p "$out/$target"
  for f in "$folder"/*; do
    [ -f "$f" ] || continue
    printf 'LFCAMFILE %s\n' "$(basename "$f")"
    cat "$f"
  done > "$out/$target/$name"
}

# Files lfcam writes: small light fields in every format, a disparity PFM, a simulation's JSON.
"$lfcam" synth -o "$scratch/lf.lf.h5" --views 2 --size 8 --disparity "$scratch/disparity.pfm"
"$lfcam" synth -o "$scratch/lf3.lf.h5" --views 3 --size 8 --seed 2
"$lfcam" convert "$scratch/lf.lf.h5" -o "$scratch/lenslet.png"
"$lfcam" convert "$scratch/lf3.lf.h5" -o "$scratch/lenslet16.tif" --16bit
"$lfcam" convert "$scratch/lf.lf.h5" -o "$scratch/hci"
"$lfcam" convert "$scratch/lf3.lf.h5" -o "$scratch/rc" --layout rowcol
"$lfcam" convert "$scratch/hci" -o "$scratch/lf8.lf.h5"             # 8-bit sRGB codes
"$lfcam" convert "$scratch/lenslet16.tif" -o "$scratch/lf16.lf.h5"  # 16-bit linear codes
"$lfcam" simulate pinhole -o "$scratch/sim" --size 64 --samples 1 --no-ground-truth --no-white >/dev/null
seed hdf5_light_field "$scratch/lf.lf.h5"
seed hdf5_light_field "$scratch/lf3.lf.h5"
seed hdf5_light_field "$scratch/lf8.lf.h5"
seed hdf5_light_field "$scratch/lf16.lf.h5"
seed pfm "$scratch/disparity.pfm"
seed lenslet_image "$scratch/lenslet.png"
seed lenslet_image "$scratch/lenslet16.tif"
pack "$scratch/hci" view_folder hci
pack "$scratch/rc" view_folder rowcolumn
seed hci_parameters "$scratch/hci/parameters.cfg"
seed camera_json "$scratch/sim/camera.json"
# The scene file of docs/formats.md, without its comments, and a few shorter ones.
mkdir -p "$out/scene_json"
cat > "$out/scene_json/desk.json" <<'JSON'
{"name": "desk", "builtin": "people", "background": [0.6, 0.7, 0.9],
 "camera": {"main_lens": {"focal_length_mm": 140, "f_number": 2.8, "focus_distance_mm": 457.2},
            "microlenses": {"pitch_mm": 0.125, "focal_length_mm": 0.5, "packing": "hexagonal",
                            "rotation_deg": 1, "offset_mm": [0, 0], "to_sensor_mm": 0.5, "fill_factor": 1,
                            "columns": 0, "rows": 0},
            "sensor": {"width": 200, "height": 200, "pixel_pitch_mm": 0.009, "color_filter": "RGGB",
                       "bit_depth": 12, "black_level": 64, "white_level": 4095, "exposure": 1,
                       "electrons_per_irradiance": 200000, "full_well": 20000, "read_noise": 3,
                       "noise": true, "hot_pixels": 0, "seed": 1}},
 "planes": [{"name": "card", "centre_mm": [0, 0, 500], "size_mm": [100, 100], "tilt_deg": [10, 0],
             "texture": {"type": "checkerboard", "period_mm": 10, "dark": 0.05, "light": 0.9}},
            {"centre_mm": [0, 0, 600], "texture": {"type": "chart", "groups": 6, "min_frequency": 0.2, "max_frequency": 2}},
            {"centre_mm": [0, 0, 700], "texture": {"type": "siemens_star", "spokes": 36}},
            {"centre_mm": [0, 0, 800], "texture": {"type": "text", "period_mm": 5, "seed": 3}},
            {"centre_mm": [0, 0, 900], "texture": {"type": "noise", "period_mm": 5}},
            {"centre_mm": [0, 0, 950], "texture": {"type": "edge", "angle_deg": 5}},
            {"centre_mm": [0, 0, 990], "texture": {"type": "image", "file": "card.png"}}],
 "lights": [{"position_mm": [0, 0, 457.2], "radius_mm": 0.05, "radiance": 1}]}
JSON
echo '{"builtin": "pinhole", "camera": {"microlenses": false}}' > "$out/scene_json/conventional.json"
echo '{"planes": [{"centre_mm": [0, 0, 500], "texture": {"type": "constant", "colour": [1, 0.5, 0]}}]}' \
  > "$out/scene_json/constant.json"
echo '{"main_lens": {"focal_length_mm": 50, "image_f_number": 4, "focus_distance_mm": 1000},
 "microlenses": {"pitch_mm": 0.02, "focal_length_mm": 0.08, "packing": "hexagonal", "rotation_deg": 0.5},
 "sensor": {"width": 120, "height": 80, "pixel_pitch_mm": 0.0014, "color_filter": "BGGR", "bit_depth": 10}}' \
  > "$out/camera_json/hexagonal.json"

# Lytro containers and raws lfcam writes (simulate --raw-format lfp/lfr), packed samples, a grid.
if "$lfcam" simulate pinhole -o "$scratch/lfp" --size 64 --samples 1 --no-ground-truth --raw-format lfp >/dev/null 2>&1; then
  seed lytro_container "$scratch/lfp/raw.lfp"
  seed read_raw "$scratch/lfp/raw.lfp"
fi
if "$lfcam" simulate pinhole -o "$scratch/lfr" --size 64 --samples 1 --no-ground-truth --raw-format lfr >/dev/null 2>&1; then
  seed lytro_container "$scratch/lfr/raw.lfr"
  seed lytro_container "$scratch/lfr/white.lfr"
fi
seed read_raw "$scratch/sim/raw.png"
mkdir -p "$out/raw_unpack"
for p in 0 1 2; do printf "\\x0$p\\x00\\x10%s" "$(printf 'lfcam packed samples %.0s' 1 2 3)" > "$out/raw_unpack/packing$p"; done
mkdir -p "$out/grid_json"
echo '{"format": "lfcam-lenslet-grid", "version": 1, "packing": "hexagonal", "pitch_x_px": 14.29, "pitch_y_px": 12.37,
 "rotation_deg": 0.1, "origin_px": [7.5, 6.2], "columns": 200, "rows": 230, "hex_parity": 1,
 "fit": {"lenslets_found": 40000, "lenslets_used": 39000, "rms_residual_px": 0.05, "max_residual_px": 0.3}}' \
  > "$out/grid_json/hexagonal.json"

# The real data, when present.
if [ -d "$data" ]; then
  for f in "$data"/hci-parameters/*.cfg "$data"/hci-antinous/parameters.cfg; do
    [ -f "$f" ] && seed hci_parameters "$f" "$(basename "$(dirname "$f")")-$(basename "$f")"
  done
  for f in "$data"/lytro-lfp/*.lfp "$data"/lytro-lfp/*.LFP; do [ -f "$f" ] && seed lytro_container "$f"; done
  for f in "$data"/lytro-metadata/*.json "$data"/lytro-metadata/*.TXT "$data"/lytro-lfp/*.json; do
    [ -f "$f" ] && seed lytro_metadata "$f"
  done
  [ -f "$data/hci-antinous/gt_disp_lowres.pfm" ] && seed pfm "$data/hci-antinous/gt_disp_lowres.pfm"
  for f in "$data"/lfm-guv/*.tif; do [ -f "$f" ] && seed lenslet_image "$f"; done
  # Lytro calibration data: a real white image's .TXT beside a short .RAW, loose and in a tar archive.
  if [ -f "$data/lytro-metadata/MOD_0015.TXT" ]; then
    mkdir -p "$scratch/caldata"
    cp "$data/lytro-metadata/MOD_0015.TXT" "$scratch/caldata/MOD_0000.TXT"
    head -c 4096 /dev/zero > "$scratch/caldata/MOD_0000.RAW"
    tar -cf "$scratch/caldata.tar" -C "$scratch/caldata" MOD_0000.RAW MOD_0000.TXT
    mv "$scratch/caldata.tar" "$scratch/caldata/"
    pack "$scratch/caldata" caldata loose-and-tar
  fi
  # Small real view folders: four views of each set.
  if [ -d "$data/lytro-f01-flower" ]; then
    mkdir -p "$scratch/flower"
    views=("$data/lytro-f01-flower/views"/*.png)  # a few views are enough for a seed
    cp "${views[@]:0:4}" "$scratch/flower/"
    pack "$scratch/flower" view_folder lytro-flower
  fi
fi
rm -rf "$scratch"
echo "fuzz seeds in $out: $(find "$out" -type f | wc -l) files"

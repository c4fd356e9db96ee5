#!/usr/bin/env bash
# One command-line case of float screenshots and imgdiff's linear comparisons:
# float_case.sh BIN_DIR WORK_DIR CASE. --screenshot F.exr / F.pfm writes the
# renderer's radiance before exposure, tone map and curve; that each renderer's
# float frame encodes to its PNG is tests/game/float_screenshot_test.cpp's question.
source "$(dirname "${BASH_SOURCE[0]}")/cli_common.sh"

CORNELL="$SRC/assets/scenes/cornell.json"
MATERIALS="$SRC/assets/scenes/materials.json"

# same_floats A B: imgdiff finds no difference at all between the two files.
same_floats() {
  expect 0 "^max_abs 0 mean_abs 0 psnr inf$" -- "$BIN/imgdiff" "$1" "$2"
}

# starts_with FILE HEX: the file's first bytes, as od prints them.
starts_with() {
  local got; got="$(od -An -tx1 -N"$(( ${#2} / 3 ))" "$1" | tr -d '\n')"
  [ "$got" = "$2" ] || { echo "FAIL: $1 begins with '$got', not '$2'"; exit 1; }
}

case "$CASE" in
  screenshot_float_raster)
    # The room keeps its HDR target anyway (the mirror's probe); the default scene
    # would draw direct, without one, and is given it. The viewer likewise.
    rm -f r.exr r.pfm d.exr v.pfm
    expect 0 "r\.exr" -- "$BIN/demo" "$CORNELL" --offscreen --size 64x48 --screenshot r.exr
    expect 0 "r\.pfm" -- "$BIN/demo" "$CORNELL" --offscreen --size 64x48 --screenshot r.pfm
    starts_with r.exr " 76 2f 31 01"
    starts_with r.pfm " 50 46 0a 36 34 20 34 38 0a 2d 31 2e 30 0a"  # "PF\n64 48\n-1.0\n"
    [ "$(stat -c %s r.pfm)" -eq $((14 + 64 * 48 * 12)) ] || { echo "FAIL: r.pfm is not 64x48 RGB floats"; exit 1; }
    same_floats r.exr r.pfm
    expect 0 "d\.exr" -- "$BIN/demo" --offscreen --size 64x48 --screenshot d.exr
    expect 0 "v\.pfm" -- "$BIN/viewer" "$SRC/assets/models/character.gltf" --offscreen --size 64x48 --screenshot v.pfm
    [ -s d.exr ] && [ -s v.pfm ] || { echo "FAIL: no float image"; exit 1; }
    [ -z "$(ls ./*.tmp 2>/dev/null)" ] || { echo "FAIL: a temporary file was left"; exit 1; } ;;
  screenshot_float_tracers)
    # The path tracer's floats are the same in both files, and its render the same
    # from run to run (thread-independent). The GPU tracers' floats against the
    # CPU's, on llvmpipe: the path tracer's identical, the Whitted tracer's 163 dB
    # apart (5e-7 at most). 40 dB, an RMS error of 1 % of the brightest value,
    # allows a GPU that rounds otherwise and a few diverged paths; a scale, row order
    # or channel order gone wrong is far below it.
    rm -f pt.pfm pt.exr ptg.pfm rt.exr rtg.exr
    expect 0 "path traced 64x48, spp 4" -- "$BIN/demo" "$CORNELL" --mode pathtrace --offscreen --size 64x48 --spp 4 \
      --screenshot pt.pfm
    expect 0 "path traced 64x48, spp 4" -- "$BIN/demo" "$CORNELL" --mode pathtrace --offscreen --size 64x48 --spp 4 \
      --screenshot pt.exr
    same_floats pt.pfm pt.exr
    expect 0 "path traced on the GPU 64x48, spp 4" -- "$BIN/demo" "$CORNELL" --mode pathtrace --device gpu --offscreen \
      --size 64x48 --spp 4 --screenshot ptg.pfm
    expect 0 "psnr" -- "$BIN/imgdiff" pt.pfm ptg.pfm --min-psnr 40
    expect 0 "ray traced 64x48" -- "$BIN/demo" "$MATERIALS" --mode raytrace --offscreen --size 64x48 --screenshot rt.exr
    expect 0 "ray traced on the GPU 64x48" -- "$BIN/demo" "$MATERIALS" --mode raytrace --device gpu --offscreen \
      --size 64x48 --screenshot rtg.exr
    expect 0 "psnr" -- "$BIN/imgdiff" rt.exr rtg.exr --min-psnr 40
    # Radiance, not display values: the room's brightest pixel is above white (2.2).
    python3 - pt.pfm <<'PY' || exit 1
import struct, sys
data = open(sys.argv[1], "rb").read()
values = struct.unpack("<%df" % (64 * 48 * 3), data[-64 * 48 * 12:])
assert max(values) > 1.0, f"FAIL: the brightest value is {max(values)}"
print(f"ok: values up to {max(values):.3f}")
PY
    # --animate offscreen: the last frame's floats are the still's of its time.
    rm -f ga.pfm gs.pfm
    expect 0 "pass 2" -- "$BIN/demo" "$CORNELL" --mode pathtrace --device gpu --animate --offscreen --size 64x48 \
      --spp 2 --frames 2 --dt 0.5 --time 0.5 --screenshot ga.pfm
    expect 0 "gs\.pfm" -- "$BIN/demo" "$CORNELL" --mode pathtrace --device gpu --offscreen --size 64x48 --spp 2 \
      --time 0.5 --screenshot gs.pfm
    same_floats ga.pfm gs.pfm ;;
  screenshot_float_window)
    # The whole window is display values: refused before a window opens. The frame
    # alone in a window is the offscreen one's floats, rasterized or traced (the GPU
    # window sums its passes in the offscreen kernel's order, as its PNG shows).
    start_xvfb
    rm -f w.exr off.pfm win.pfm gpw.exr gpo.exr
    expect 2 "^demo: --screenshot-window --screenshot w\.exr: the whole window \(panel included\) exists only as display values; write it as \.png$" \
      -- "$BIN/demo" --frames 3 --size 64x48 --screenshot-window --screenshot w.exr
    [ ! -e w.exr ] || { echo "FAIL: wrote w.exr"; exit 1; }
    expect 0 "off\.pfm" -- "$BIN/demo" "$CORNELL" --offscreen --size 64x48 --time 0 --screenshot off.pfm
    expect 0 "win\.pfm" -- "$BIN/demo" "$CORNELL" --frames 3 --size 64x48 --time 0 --screenshot win.pfm
    same_floats off.pfm win.pfm
    expect 0 "pass 4 of 4" -- "$BIN/demo" "$MATERIALS" --mode pathtrace --device gpu --size 64x48 --spp 4 --frames 40 \
      --screenshot gpw.exr
    expect 0 "gpo\.exr" -- "$BIN/demo" "$MATERIALS" --mode pathtrace --device gpu --offscreen --size 64x48 --spp 4 \
      --screenshot gpo.exr
    same_floats gpo.exr gpw.exr ;;
  imgdiff_float)
    # Linear pairs in any of the formats: the values' differences and PSNR, HDR-FLIP
    # with --flip, limits; a PNG beside a float image, PNG-only options and broken
    # files are refused naming what is wrong.
    "$BIN/demo" --offscreen --time 0 --size 96x64 --screenshot t0.pfm >/dev/null || exit 1
    "$BIN/demo" --offscreen --time 2 --size 96x64 --screenshot t2.exr >/dev/null || exit 1
    "$BIN/demo" --offscreen --time 0 --size 96x64 --screenshot t0.png >/dev/null || exit 1
    expect 0 "^max_abs 0 mean_abs 0 psnr inf hdr_flip 0\.000000 exposures " -- "$BIN/imgdiff" t0.pfm t0.pfm --flip
    expect 0 "^max_abs [0-9.e+-]+ mean_abs [0-9.e+-]+ psnr [0-9.]+$" -- "$BIN/imgdiff" t0.pfm t2.exr
    rm -f f.png
    expect 1 "over the limit" -- "$BIN/imgdiff" t0.pfm t2.exr --min-psnr 200 --flip-map f.png
    grep -Eq "hdr_flip 0\.[0-9]{6} exposures" "$OUT" || { echo "FAIL: no HDR-FLIP"; cat "$OUT"; exit 1; }
    [ -s f.png ] || { echo "FAIL: no FLIP map"; exit 1; }
    expect 2 "t0\.pfm is a linear image and t0\.png is not" -- "$BIN/imgdiff" t0.pfm t0.png
    expect 2 "--diff, --max-mean and --max-abs are for PNG images" -- "$BIN/imgdiff" t0.pfm t2.exr --max-abs 1
    head -c 300 t2.exr > cut.exr
    expect 2 "^imgdiff: cut\.exr: cannot read OpenEXR: " -- "$BIN/imgdiff" cut.exr t2.exr
    head -c 1000 t0.pfm > cut.pfm
    expect 2 "^imgdiff: cut\.pfm: cannot read PFM: 986 bytes of pixels, 96x64 RGB needs 73728 \(truncated\)$" -- \
      "$BIN/imgdiff" t0.pfm cut.pfm
    expect 2 "^imgdiff: missing\.exr: no such file$" -- "$BIN/imgdiff" missing.exr t0.png ;;
  *) echo "unknown case $CASE"; exit 1 ;;
esac

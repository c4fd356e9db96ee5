#!/usr/bin/env bash
# One bad-input case: bad_input_case.sh BIN_DIR WORK_DIR CASE SOURCE_DIR
# The inputs are in WORK_DIR/data (tests/data/bad/make_bad_inputs.py); the table of
# expected messages is tests/data/bad/README.md. Each case checks the exit code,
# that the output names the file and the element, and that no sanitizer spoke.
set -u
BIN="$1"; WORK="$2"; CASE="$3"; SRC="$4"
DATA="$WORK/data"
mkdir -p "$WORK/$CASE" && cd "$DATA" || exit 1
OUT="$WORK/$CASE/out.txt"

# expect CODE PATTERN -- COMMAND...: runs COMMAND in the data folder, checks its
# exit code and that stdout+stderr match PATTERN (grep -E).
expect() {
  local code="$1" pattern="$2"; shift 3
  "$@" >"$OUT" 2>&1; local got=$?
  if grep -Eq "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:|SUMMARY: (Address|Leak|UndefinedBehavior)Sanitizer" "$OUT"; then
    echo "FAIL: '$*': sanitizer report"; cat "$OUT"; exit 1
  fi
  if [ "$got" -ne "$code" ]; then
    echo "FAIL: '$*' exited $got, expected $code"; cat "$OUT"; exit 1
  fi
  if ! grep -Eq -- "$pattern" "$OUT"; then
    echo "FAIL: '$*' output does not match '$pattern'"; cat "$OUT"; exit 1
  fi
  echo "ok: '$*' -> $got: $(head -c 300 "$OUT")"
}

# The viewer loads the model and dumps the pose at t = 0.5 (no GL needed).
model() {  # model FILE CODE PATTERN
  rm -f "$WORK/$1.pose.json"
  expect "$2" "$3" -- "$BIN/viewer" "$1" --time 0.5 --dump-pose "$WORK/$1.pose.json"
  if [ "$2" -ne 0 ] && [ -e "$WORK/$1.pose.json" ]; then echo "FAIL: pose written for a bad model"; exit 1; fi
}
scene() {  # scene FILE PATTERN
  expect 2 "$2" -- "$BIN/demo" "$1" --offscreen --size 64x64 --screenshot "$WORK/$CASE/shot.png"
  [ ! -e "$WORK/$CASE/shot.png" ] || { echo "FAIL: a bad scene rendered"; exit 1; }
}

case "$CASE" in
  truncated_glb) model truncated.glb 2 "truncated\.glb: truncated GLB: header says 1584 bytes, the file has 30" ;;
  wrong_magic) model wrong_magic.glb 2 "wrong_magic\.glb: not a GLB file \(bad magic\)" ;;
  json_chunk_past_end) model json_chunk_past_end.glb 2 "json_chunk_past_end\.glb: truncated GLB: JSON chunk of [0-9]+ bytes runs past the end" ;;
  bin_chunk_past_end) model bin_chunk_past_end.glb 2 "bin_chunk_past_end\.glb: truncated GLB: BIN chunk of 1048576 bytes runs past the end" ;;
  accessor_count_overflow) model accessor_count_overflow.glb 2 "accessor_count_overflow\.glb: mesh 0 primitive 0 POSITION: accessor 0: count 4294967295 is outside \[1, 67108864\]" ;;
  accessor_count_limit) model accessor_count_limit.glb 2 "accessor_count_limit\.glb: .*accessor 5: count 67108865 is outside \[1, 67108864\]" ;;
  bufferview_past_buffer) model bufferview_past_buffer.glb 2 "bufferview_past_buffer\.glb: .*bufferView 6: bytes \[240, 304\) run past buffer 0 of 272 bytes" ;;
  joint_past_skin) model joint_past_skin.glb 2 "joint_past_skin\.glb: node 0: mesh 0 primitive 0: vertex 1 uses joint 5 past skin 0 of 2 joints" ;;
  morph_target_count) model morph_target_count.glb 2 "morph_target_count\.glb: mesh 0 primitive 0 target 0 POSITION: has 2 elements, expected 3" ;;
  morph_weights_keys) model morph_weights_keys.glb 2 "morph_weights_keys\.glb: animation 0 channel 1 sampler 1 output: 3 weights for 2 keys of 1 morph targets \(2 expected\)" ;;
  negative_key_time) model negative_key_time.glb 2 "negative_key_time\.glb: animation 0 channel 0 sampler 0 input: key 0 time -1\.0+ is negative" ;;
  nan_key_time) model nan_key_time.glb 2 "nan_key_time\.glb: animation 0 channel 0 sampler 0 input: key 1 time is NaN or infinite" ;;
  unsorted_keys) model unsorted_keys.glb 2 "unsorted_keys\.glb: animation 0 channel 0 sampler 0 input: key 1 time 0\.50+ is before the previous key" ;;
  node_cycle) model node_cycle.glb 2 "node_cycle\.glb: node [0-9]+: (is part of a cycle|has two parents)" ;;
  uri_dotdot) model uri_dotdot.gltf 2 "uri_dotdot\.gltf: buffer 0: uri \"\.\./outside\.bin\" leaves the model's folder; refused" ;;
  uri_absolute) model uri_absolute.gltf 2 "uri_absolute\.gltf: buffer 0: uri \"/etc/passwd\" leaves the model's folder; refused" ;;
  buffer_4gb_declared) model buffer_4gb_declared.gltf 2 "buffer_4gb_declared\.gltf: .*small\.bin.*4294967296" ;;
  buffer_4gb_file) model buffer_4gb_file.gltf 2 "buffer_4gb_file\.gltf: .*huge\.bin is too large" ;;
  file_too_large) model file_too_large.glb 2 "file_too_large\.glb: file is 629145600 bytes, the limit is 536870912" ;;
  too_many_nodes)
    # Refused from the raw JSON, before tinygltf builds a gigabyte of nodes: the
    # memory cap makes a regression fail instead of swapping (ASan needs more).
    limit=$((400 * 1024)); [ -n "${ASAN_OPTIONS:-}" ] && limit=unlimited
    ( ulimit -v $limit; "$BIN/viewer" too_many_nodes.gltf --dump-pose "$WORK/nodes.json" >"$WORK/$CASE/capped.txt" 2>&1 )
    grep -q "too_many_nodes\.gltf: 1048577 nodes, the limit is 1048576" "$WORK/$CASE/capped.txt" \
      || { echo "FAIL: not refused within $limit KiB"; cat "$WORK/$CASE/capped.txt"; exit 1; }
    model too_many_nodes.gltf 2 "too_many_nodes\.gltf: 1048577 nodes, the limit is 1048576" ;;
  too_many_joints) model too_many_joints.glb 2 "too_many_joints\.glb: skin 0: 65537 joints, the limit is 65536" ;;
  # Compressed geometry that does not decode: the file, the element and the
  # extension, and the decoder's own reason.
  draco_truncated) model draco_truncated.glb 2 "draco_truncated\.glb: mesh 0 primitive 0: KHR_draco_mesh_compression: decode failed: " ;;
  # Instancing attributes that do not fit: the file, the node, the extension and
  # the attribute.
  instancing_type) model instancing_type.glb 2 "instancing_type\.glb: node 0: EXT_mesh_gpu_instancing ROTATION: accessor 0 has 3 components per element, expected 4" ;;
  instancing_count) model instancing_count.glb 2 "instancing_count\.glb: node 0: EXT_mesh_gpu_instancing ROTATION: has 2 instances, the other attributes 3" ;;
  instancing_too_many) model instancing_too_many.glb 2 "instancing_too_many\.glb: node 0: EXT_mesh_gpu_instancing TRANSLATION: accessor 7: 1048577 instances, the limit is 1048576" ;;
  meshopt_truncated) model meshopt_truncated.glb 2 "meshopt_truncated\.glb: bufferView 0: EXT_meshopt_compression: decode failed: meshopt error -2 " ;;
  # A texture that cannot be used is not fatal (the loader's documented rule: a
  # model without its texture is still worth showing): a warning naming the file
  # and the image, a white fallback, exit 0.
  zero_size_image) model zero_size_image.glb 0 "warning: zero_size_image\.glb: image 0: image is 0x0 pixels" ;;
  huge_image) model huge_image.glb 0 "warning: huge_image\.glb: image 0: 20000 x 20000 pixels is over the limit of 16384" ;;
  bad_clearcoat) model bad_clearcoat.glb 2 "bad_clearcoat\.glb: material 0 \(\"paint\"\): KHR_materials_clearcoat: clearcoatFactor must be a number in \[0, 1\]" ;;
  bad_anisotropy) model bad_anisotropy.glb 2 "bad_anisotropy\.glb: material 0 \(\"brushed\"\): KHR_materials_anisotropy: anisotropyStrength must be a number in \[0, 1\]" ;;
  bad_iridescence) model bad_iridescence.glb 2 "bad_iridescence\.glb: material 0 \(\"soap\"\): KHR_materials_iridescence: iridescenceIor must be a number in \[1, 1e\+06\]" ;;
  bad_spot_cone) model bad_spot_cone.glb 2 "bad_spot_cone\.glb: light 0 \(\"torch\"\): spot\.innerConeAngle and spot\.outerConeAngle must be 0 <= inner <= outer <= pi/2" ;;
  bad_sheen) model bad_sheen.glb 2 "bad_sheen\.glb: material 0 \(\"velvet\"\): KHR_materials_sheen: sheenRoughnessFactor must be a number in \[0, 1\]" ;;
  bad_volume) model bad_volume.glb 2 "bad_volume\.glb: material 0 \(\"glass\"\): KHR_materials_volume: attenuationColor must be three numbers in \[0, 1\]" ;;
  bad_texture_settings) model bad_texture_settings.glb 0 "warning: bad_texture_settings\.glb: material 0 \(\"tiles\"\): baseColorTexture 0: TEXCOORD_2 is not supported" ;;
  # The same images given to a program that needs them are errors.
  zero_size_png) expect 2 "zero_size\.png: image is 0x0 pixels; each side must be in \[1, 16384\]" -- "$BIN/imgdiff" zero_size.png zero_size.png ;;
  huge_claim_png) expect 2 "huge_claim\.png: image is 20000x20000 pixels; each side must be in \[1, 16384\]" -- "$BIN/imgdiff" huge_claim.png huge_claim.png ;;
  # imgdiff's mask and size checks come before anything is written.
  mask_size_png|mask_black_png|size_mismatch_png)
    case "$CASE" in
      mask_size_png) args=(mask_pair.png mask_pair.png --mask mask_small.png); pattern="mask_small\.png: the mask is 2x2 pixels, the images 4x4" ;;
      mask_black_png) args=(mask_pair.png mask_pair.png --mask mask_black.png); pattern="mask_black\.png: the mask selects no pixel" ;;
      size_mismatch_png) args=(mask_pair.png other_size.png); pattern="images differ in size: mask_pair\.png is 4x4, other_size\.png 4x3" ;;
    esac
    rm -f "$WORK/$CASE/diff.png" "$WORK/$CASE/flip.png"
    expect 2 "$pattern" -- "$BIN/imgdiff" "${args[@]}" --flip --diff "$WORK/$CASE/diff.png" --flip-map "$WORK/$CASE/flip.png"
    [ ! -e "$WORK/$CASE/diff.png" ] && [ ! -e "$WORK/$CASE/flip.png" ] || { echo "FAIL: an image was written"; exit 1; } ;;
  # Float images (imgdiff): an OpenEXR written from the specification reads as the
  # PFM of the same pixels; broken ones are refused naming the file.
  good_float_images) expect 0 "^max_abs 0 mean_abs 0 psnr inf$" -- "$BIN/imgdiff" good.exr good.pfm ;;
  truncated_exr) expect 2 "^imgdiff: truncated\.exr: cannot read OpenEXR: " -- "$BIN/imgdiff" truncated.exr good.exr ;;
  truncated_pfm) expect 2 "^imgdiff: truncated\.pfm: cannot read PFM: 100 bytes of pixels, 4x4 RGB needs 192 \(truncated\)$" -- \
    "$BIN/imgdiff" good.pfm truncated.pfm ;;
  wrong_size_pfm) expect 2 "^imgdiff: wrong_size\.pfm: cannot read PFM: 200 bytes of pixels, 4x4 RGB needs 192$" -- \
    "$BIN/imgdiff" wrong_size.pfm good.pfm ;;
  not_an_image_exr) expect 2 "^imgdiff: not_an_image\.exr: neither an OpenEXR nor a PFM image$" -- \
    "$BIN/imgdiff" not_an_image.exr good.exr ;;
  # --screenshot's name picks the format: one it cannot write, or a float image
  # where it cannot go, is refused before anything renders.
  screenshot_unwritable_exr)
    expect 2 "^demo: --screenshot /nonexistent/dir/a\.exr: cannot write there" -- \
      "$BIN/demo" --offscreen --size 64x64 --screenshot /nonexistent/dir/a.exr ;;
  screenshot_bad_extension)
    rm -f "$WORK/$CASE/shot.jpg"
    expect 2 "^demo: --screenshot .*/shot\.jpg: the name must end in \.png \(the frame as shown\), \.exr or \.pfm" -- \
      "$BIN/demo" --offscreen --size 64x64 --screenshot "$WORK/$CASE/shot.jpg"
    [ ! -e "$WORK/$CASE/shot.jpg" ] || { echo "FAIL: wrote shot.jpg"; exit 1; }
    expect 2 "^viewer: --screenshot .*/shot\.tga: the name must end in" -- \
      "$BIN/viewer" good.glb --offscreen --size 64x64 --screenshot "$WORK/$CASE/shot.tga" ;;
  scene_fovy_string) scene scene_fovy_string.json "scene_fovy_string\.json: /camera/fovy: expected a number" ;;
  scene_models_number) scene scene_models_number.json "scene_models_number\.json: /models: expected an array" ;;
  scene_model_path_number) scene scene_model_path_number.json "scene_model_path_number\.json: /models/0/path: expected a string" ;;
  scene_light_type) scene scene_light_type.json "scene_light_type\.json: /lights/0/type: expected one of" ;;
  scene_spot_cone_inverted) scene scene_spot_cone_inverted.json "scene_spot_cone_inverted\.json: /lights/0/inner_cone: the inner cone must not be wider than the outer one" ;;
  scene_fog_negative_scattering) scene scene_fog_negative_scattering.json "scene_fog_negative_scattering\.json: /fog/scattering/1: expected a number in \[0, 1e6\] per metre" ;;
  scene_fog_anisotropy_one) scene scene_fog_anisotropy_one.json "scene_fog_anisotropy_one\.json: /fog/anisotropy: expected a number in \[-0\.999, 0\.999\], got 1" ;;
  scene_fog_height_falloff_negative) scene scene_fog_height_falloff_negative.json "scene_fog_height_falloff_negative\.json: /fog/height_falloff: expected a number in \[0, 1\], got -0\.01" ;;
  scene_atmosphere_radius_zero) scene scene_atmosphere_radius_zero.json "scene_atmosphere_radius_zero\.json: /atmosphere/planet_radius: expected a number in \[1000, 1e\+09\], got 0" ;;
  scene_atmosphere_mie_infinite) scene scene_atmosphere_mie_infinite.json "scene_atmosphere_mie_infinite\.json: not valid JSON: .*number overflow parsing '1e999'" ;;
  scene_atmosphere_mie_anisotropy_one) scene scene_atmosphere_mie_anisotropy_one.json "scene_atmosphere_mie_anisotropy_one\.json: /atmosphere/mie/anisotropy: expected a number in \[-0\.999, 0\.999\], got 1" ;;
  scene_medium_box_inverted) scene scene_medium_box_inverted.json "scene_medium_box_inverted\.json: /media/0/max/1: a box's max must be greater than its min" ;;
  scene_medium_negative_absorption) scene scene_medium_negative_absorption.json "scene_medium_negative_absorption\.json: /media/0/absorption/2: expected a number in \[0, 1e6\] per metre" ;;
  scene_point_cone) scene scene_point_cone.json "scene_point_cone\.json: /lights/0/outer_cone: only a spot light has a cone" ;;
  scene_position_null) scene scene_position_null.json "scene_position_null\.json: /camera/position/1: expected a (finite )?number" ;;
  scene_msaa_string) scene scene_msaa_string.json "scene_msaa_string\.json: /render/msaa: expected an integer" ;;
  scene_skinning_unknown) scene scene_skinning_unknown.json "scene_skinning_unknown\.json: /render/skinning: \"gpu\" is not one of: auto, compute, vertex" ;;
  scene_lod_negative) scene scene_lod_negative.json "scene_lod_negative\.json: /render/lod_pixels: expected a number in \[0, 64\], got -1" ;;
  scene_gpu_culling_string) scene scene_gpu_culling_string.json "scene_gpu_culling_string\.json: /render/gpu_culling: expected true or false" ;;
  scene_unknown_key) scene scene_unknown_key.json "scene_unknown_key\.json: /origin: unknown key" ;;
  scene_not_object) scene scene_not_object.json "scene_not_object\.json: /: expected an object" ;;
  # A sky image is checked from its header when the scene loads, and decoded by each
  # renderer: the truncated one passes the first and fails the second, in both modes.
  scene_sky_image_missing) scene scene_sky_image_missing.json "scene_sky_image_missing\.json: /sky/image: no_such_sky\.hdr: no such file" ;;
  scene_sky_image_not_image) scene scene_sky_image_not_image.json "scene_sky_image_not_image\.json: /sky/image: not_an_image\.hdr: neither a Radiance \.hdr nor a PNG image" ;;
  scene_sky_image_empty) scene scene_sky_image_empty.json "scene_sky_image_empty\.json: /sky/image: empty\.hdr: the file is empty \(0 bytes\)" ;;
  scene_sky_image_zero_size) scene scene_sky_image_zero_size.json "scene_sky_image_zero_size\.json: /sky/image: zero_size\.hdr: image is 0x0 pixels; each side must be in \[1, 16384\]" ;;
  scene_sky_image_zero_png) scene scene_sky_image_zero_png.json "scene_sky_image_zero_png\.json: /sky/image: zero_size\.png: image is 0x0 pixels; each side must be in \[1, 16384\]" ;;
  scene_sky_image_truncated)
    pattern="scene_sky_image_truncated\.json: /sky/image: truncated_sky\.hdr: cannot read image: the Radiance data ends early"
    scene scene_sky_image_truncated.json "$pattern"
    expect 2 "$pattern" -- timeout 60 "$BIN/demo" scene_sky_image_truncated.json --offscreen --mode raytrace --size 64x64 --screenshot "$WORK/$CASE/traced.png"
    [ ! -e "$WORK/$CASE/traced.png" ] || { echo "FAIL: a bad scene was traced"; exit 1; } ;;
  good_model)
    # The unbroken base of every model case loads and dumps a pose.
    model good.glb 0 "good\.glb\.pose\.json"
    grep -q '"nodes"' "$WORK/good.glb.pose.json" || { echo "FAIL: pose lacks nodes"; exit 1; } ;;
  # Leak checks: a whole offscreen run of each program. Under the sanitizer build
  # LeakSanitizer runs at exit and any leak from the project's code fails the case
  # (driver libraries are suppressed in tests/sanitizers/lsan.supp).
  leak_demo) expect 0 "leak_demo\.png" -- "$BIN/demo" --offscreen --frames 3 --size 96x64 --screenshot "$WORK/leak_demo.png" ;;
  leak_viewer)
    [ -x "$BIN/viewer" ] || { echo "no viewer: skipped"; exit 77; }
    expect 0 "leak_viewer\.png" -- "$BIN/viewer" good.glb --offscreen --frames 3 --size 96x64 --screenshot "$WORK/leak_viewer.png" ;;
  *) echo "unknown case $CASE"; exit 1 ;;
esac

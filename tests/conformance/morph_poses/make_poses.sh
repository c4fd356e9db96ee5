#!/bin/sh
# Regenerates the reference poses in this folder with three.js (pose.mjs of
# ../shared/conformance/threeref). shared/ is read-only, so the oracle runs from a
# copy where `npm ci` has installed three.js r187:
#
#   cp -r ../shared/conformance/threeref /tmp/threeref && (cd /tmp/threeref && npm ci)
#   tests/conformance/morph_poses/make_poses.sh /tmp/threeref
#
# Khronos models are named relative to ../shared, this folder's own model relative
# to this folder: the conformance test resolves "model" the same way.
set -eu
threeref=$(cd "${1:?usage: make_poses.sh THREEREF_DIR}" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
shared="$here/../../../../shared"

pose() {  # FOLDER MODEL ANIM TIME OUT [--loop clamp]
  folder=$1 model=$2 anim=$3 time=$4 out=$5
  shift 5
  (cd "$folder" && node "$threeref/pose.mjs" "$model" --anim "$anim" --time "$time" --out "$here/$out" "$@")
}

cube=gltf-samples/AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb
pose "$shared" $cube -1 0 AnimatedMorphCube_a-1_t0.json
# D = 4.199997425 s; 0.25 D, 0.5 D + 0.013, D - 0.001, 1.5 D (wraps to 0.5 D) and clamped.
pose "$shared" $cube 0 1.05 AnimatedMorphCube_a0_t1.05.json
pose "$shared" $cube 0 2.113 AnimatedMorphCube_a0_t2.113.json
pose "$shared" $cube 0 4.199 AnimatedMorphCube_a0_t4.199.json
pose "$shared" $cube 0 6.3 AnimatedMorphCube_a0_t6.3.json
pose "$shared" $cube 0 6.3 AnimatedMorphCube_a0_t6.3_clamp.json --loop clamp

pose "$shared" gltf-samples/MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb -1 0 MorphPrimitivesTest_a-1_t0.json

# Own model (make_morph_model.py): keys at 0, 1, 2 s; 2.5 wraps to 0.5.
pose "$here" MorphInterpolation.gltf -1 0 MorphInterpolation_a-1_t0.json
for anim in 0 1 2; do
  for time in 0.5 1.25 1.75 2.5; do
    pose "$here" MorphInterpolation.gltf $anim $time MorphInterpolation_a${anim}_t$time.json
  done
  pose "$here" MorphInterpolation.gltf $anim 3 MorphInterpolation_a${anim}_t3_clamp.json --loop clamp
done

#!/usr/bin/env bash
# Regenerates character_meshopt.glb, the EXT_meshopt_compression sample of the
# loader tests (tests/asset/compressed_mesh_test.cpp), from the project's own robot
# (assets/models/character.gltf, so no third-party licence comes along). Run by
# hand when the robot changes; the .glb is committed (about 30 KB). Needs Debian's
# gltfpack (apt-get install gltfpack; 0.18 was used):
#   gltfpack -i character_untextured.gltf -o character_meshopt.glb -cc -si 0.25
# -cc: meshopt compression with the OCTAHEDRAL, QUATERNION and EXPONENTIAL filters
# (normals, rotation keys, translation/scale keys) and KHR_mesh_quantization;
# gltfpack puts the uncompressed layout in a fallback buffer with no uri.
# -si 0.25: a quarter of the triangles, to keep the file small.
# The texture is dropped first (it would be most of the file and tests nothing here).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
MODELS="$HERE/../../../assets/models"
TMP="$(mktemp -d)"; trap 'rm -rf "$TMP"' EXIT
python3 - "$MODELS/character.gltf" "$TMP/character_untextured.gltf" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
for key in ("images", "textures", "samplers"):
    doc.pop(key, None)
for m in doc["materials"]:
    m.get("pbrMetallicRoughness", {}).pop("baseColorTexture", None)
json.dump(doc, open(sys.argv[2], "w"))
PY
cp "$MODELS/character.bin" "$TMP/"
gltfpack -i "$TMP/character_untextured.gltf" -o "$HERE/character_meshopt.glb" -cc -si 0.25
ls -l "$HERE/character_meshopt.glb"

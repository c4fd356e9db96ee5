#!/usr/bin/env bash
# Runs the Khronos glTF validator on every assets/models/*.gltf and fails on any
# error or warning. validate_models.sh SOURCE_DIR WORK_DIR
# The validator lives outside the project (../shared/conformance/validator, or
# $CONFORMANCE_DIR/validator); without it, node/npm, or a working `npm ci` (no
# network), the test is skipped with exit 77 so a fresh clone still passes.
set -u
SOURCE="$1"; WORK="$2"
skip() { echo "skipped: $*"; exit 77; }

CONFORMANCE="${CONFORMANCE_DIR:-$SOURCE/../shared/conformance}"
VALIDATOR_SRC="$CONFORMANCE/validator"
[ -f "$VALIDATOR_SRC/validate.mjs" ] || skip "no validator at $VALIDATOR_SRC"
command -v node >/dev/null || skip "node not found"
command -v npm >/dev/null || skip "npm not found"

# A writable copy, installed once: node_modules is kept between runs and refreshed
# only when the lock file changes.
VALIDATOR="$WORK/validator"
mkdir -p "$WORK" || exit 1
if ! cmp -s "$VALIDATOR_SRC/package-lock.json" "$VALIDATOR/package-lock.json" ||
   [ ! -d "$VALIDATOR/node_modules" ]; then
  rm -rf "$VALIDATOR" && cp -r "$VALIDATOR_SRC" "$VALIDATOR" || exit 1
  rm -rf "$VALIDATOR/node_modules"
  (cd "$VALIDATOR" && npm ci --no-audit --no-fund >"$WORK/npm-ci.log" 2>&1) || {
    rm -rf "$VALIDATOR/node_modules"
    skip "npm ci failed (no network?), see $WORK/npm-ci.log"
  }
fi

shopt -s nullglob
models=("$SOURCE"/assets/models/*.gltf)
[ ${#models[@]} -gt 0 ] || { echo "FAIL: no assets/models/*.gltf"; exit 1; }
status=0
for model in "${models[@]}"; do
  report=$(node "$VALIDATOR/validate.mjs" "$model"); rc=$?
  echo "$report"
  if [ $rc -ne 0 ]; then
    echo "FAIL: $model has validator errors (exit $rc)"; status=1
  elif ! grep -q "errors 0, warnings 0," <<<"$report"; then
    echo "FAIL: $model has validator warnings"; status=1
  fi
done
exit $status

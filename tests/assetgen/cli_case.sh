#!/usr/bin/env bash
# The generator's command line: cli_case.sh ASSETGEN WORK_DIR
# --out into a fresh folder writes the three files; an output folder that cannot be
# made exits 2 with one line naming the path; a bad option exits 2.
set -u
ASSETGEN="$1"; WORK="$2"
rm -rf "$WORK" && mkdir -p "$WORK" || exit 1
fail() { echo "FAIL: $*"; cat "$WORK/err" 2>/dev/null; exit 1; }

"$ASSETGEN" --out "$WORK/new/models" >"$WORK/out" 2>"$WORK/err" || fail "--out new folder exited $?"
for f in character.gltf character.bin character_albedo.png materials.gltf materials.bin materials_bricks_normal.png; do
  [ -s "$WORK/new/models/$f" ] || fail "$f not written"
done
echo "ok: writes into a new folder"

# A regular file where the folder should be: it can never become a directory.
touch "$WORK/file"
"$ASSETGEN" --out "$WORK/file/models" >"$WORK/out" 2>"$WORK/err"; rc=$?
[ $rc -eq 2 ] || fail "unwritable --out exited $rc, expected 2"
[ "$(wc -l <"$WORK/err")" -eq 1 ] || fail "expected one line on stderr"
grep -q "$WORK/file/models" "$WORK/err" || fail "message does not name the path"
echo "ok: unwritable folder -> 2: $(cat "$WORK/err")"

"$ASSETGEN" --bogus >"$WORK/out" 2>"$WORK/err"; rc=$?
[ $rc -eq 2 ] || fail "--bogus exited $rc, expected 2"
grep -q -- "--bogus" "$WORK/err" || fail "message does not name the option"
echo "ok: bad option -> 2"

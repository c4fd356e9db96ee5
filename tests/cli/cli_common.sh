# What the command-line cases share (cli_case.sh, float_case.sh), sourced first by
# each: its arguments BIN_DIR WORK_DIR CASE, the work folder entered, the helpers.
set -u
BIN="$1"; WORK="$2"; CASE="$3"
SRC="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
mkdir -p "$WORK" && cd "$WORK" || exit 1
OUT="$WORK/$CASE.out"; ERR="$WORK/$CASE.err"

# expect CODE PATTERN -- COMMAND...: runs COMMAND, checks its exit code and that
# stderr+stdout match PATTERN (grep -E).
expect() {
  local code="$1" pattern="$2"; shift 3
  "$@" >"$OUT" 2>"$ERR"; local got=$?
  if [ "$got" -ne "$code" ]; then
    echo "FAIL: '$*' exited $got, expected $code"; cat "$OUT" "$ERR"; exit 1
  fi
  if ! cat "$OUT" "$ERR" | grep -Eq -- "$pattern"; then
    echo "FAIL: '$*' output does not match '$pattern'"; cat "$OUT" "$ERR"; exit 1
  fi
  echo "ok: '$*' -> $got"
}

# Processes to stop when the case ends (a private X server, busy loops).
CLEANUP=()
trap 'kill "${CLEANUP[@]}" 2>/dev/null' EXIT

# Starts a private Xvfb and exports its DISPLAY. Xvfb picks a free display itself
# (-displayfd) and writes it once ready: xvfb-run -a races parallel tests for the
# numbers, and its own clean-up failed a command under load (exit 5).
start_xvfb() {
  command -v Xvfb >/dev/null || { echo "Xvfb missing: skipped"; exit 77; }
  rm -f "$CASE.display"
  Xvfb -displayfd 3 -nolisten tcp 3>"$CASE.display" 2>"$CASE.xvfb.log" &
  CLEANUP+=($!)
  for _ in $(seq 50); do [ -s "$CASE.display" ] && break; sleep 0.1; done
  [ -s "$CASE.display" ] || { echo "FAIL: Xvfb did not start"; cat "$CASE.xvfb.log"; exit 1; }
  export DISPLAY=":$(cat "$CASE.display")"
}

# The last command's output names no GL object deleted after its context.
no_orphans() {
  if cat "$OUT" "$ERR" | grep -q "outlived its context"; then
    echo "FAIL: a GL object outlived its context"; cat "$OUT" "$ERR"; exit 1
  fi
}

# Shared helpers for the command-line tests (sourced; not a test itself).
# Usage from a test: source "$(dirname "$0")/testlib.bash" "$@"
set -u

DP=${1:?usage: bash test.sh <path-to-diffphoton> <scratch-dir>}
SCRATCH=${2:?usage: bash test.sh <path-to-diffphoton> <scratch-dir>}
[ -x "$DP" ] || { echo "FAIL: $DP is not an executable" >&2; exit 1; }
DP=$(cd "$(dirname "$DP")" && pwd)/$(basename "$DP")
case $SCRATCH in /|/*/..|.|..) echo "FAIL: refusing scratch dir '$SCRATCH'" >&2; exit 1 ;; esac
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH" && cd "$SCRATCH" || exit 1

fail() {
    echo "FAIL: $*" >&2
    echo "--- stdout of the last command:" >&2; cat stdout.txt >&2 2>/dev/null
    echo "--- stderr of the last command:" >&2; cat stderr.txt >&2 2>/dev/null
    exit 1
}

# run ARGS...: runs diffphoton; sets RC, and keeps its output in stdout.txt / stderr.txt.
run() {
    "$DP" "$@" >stdout.txt 2>stderr.txt
    RC=$?
}

expect_rc() {  # expect_rc CODE DESCRIPTION
    [ "$RC" -eq "$1" ] || fail "$2: exit code $RC, expected $1"
}

expect_stderr() {  # expect_stderr TEXT DESCRIPTION (fixed string)
    grep -qF -- "$1" stderr.txt || fail "$2: stderr does not contain '$1'"
}

# The command is refused (exit 2) or runs with a warning (exit 0), its stderr holding TEXT.
expect_refused() {  # expect_refused DESCRIPTION TEXT COMMAND...
    local what=$1 text=$2
    shift 2
    run "$@"
    expect_rc 2 "$what"
    expect_stderr "$text" "$what"
}
expect_warned() {  # expect_warned DESCRIPTION TEXT COMMAND...
    local what=$1 text=$2
    shift 2
    run "$@"
    expect_rc 0 "$what"
    expect_stderr "$text" "$what"
}

expect_stdout() {
    grep -qF -- "$1" stdout.txt || fail "$2: stdout does not contain '$1'"
}

# field NAME: the number after NAME in the last command's stdout ("max_diff 0.5" -> 0.5).
field() {
    awk -v key="$1" '{ for (i = 1; i < NF; ++i) if ($i == key) { print $(i + 1); exit } }' \
        stdout.txt
}

# is_zero / is_positive NUMBER, for the figures `diffphoton compare` prints.
is_zero() { awk -v v="$1" 'BEGIN { exit !(v == 0) }'; }
is_positive() { awk -v v="$1" 'BEGIN { exit !(v > 0) }'; }
at_most() { awk -v v="$1" -v m="$2" 'BEGIN { exit !(v <= m) }'; }

# compare A B [--layer L]: runs `diffphoton compare`; sets MAX_DIFF and RMSE.
compare() {
    run compare "$@"
    expect_rc 0 "compare $*"
    MAX_DIFF=$(field max_diff)
    RMSE=$(field rmse)
    [ -n "$MAX_DIFF" ] || fail "compare $*: no max_diff in the output"
}

# Inputs every test shares: a grey photo and a sky probe with a sun up and to the front.
make_inputs() {
    run make-test-image photo.exr --size 64 48 --value 0.5 0.5 0.5
    expect_rc 0 "make-test-image photo"
    run make-test-image probe.exr --size 64 32 --probe-sun --value 0.1 0.1 0.12
    expect_rc 0 "make-test-image probe"
}

BALL='{"name": "ball", "shape": {"type": "sphere", "radius": 0.5},
       "transform": {"translation": [0, 0.5, 0]},
       "material": {"type": "diffuse", "albedo": [0.8, 0.3, 0.2]}}'
FLOOR='{"name": "floor", "shape": {"type": "plane", "size": [10, 10]}, "albedo": [0.5, 0.5, 0.5]}'

# write_project FILE OBJECTS REAL [PHOTO]: a small look-at scene; OBJECTS and REAL are the
# contents of the JSON arrays.
write_project() {
    cat >"$1" <<JSON
{
  "schema_version": 1,
  "photo": {"path": "${4:-photo.exr}"},
  "probe": {"path": "probe.exr"},
  "camera": {"model": "lookat", "eye": [0, 1.5, 4], "target": [0, 0.4, 0], "vfov_deg": 40},
  "real": [$3],
  "objects": [$2],
  "render": {"photons_per_pass": 20000, "passes": 3}
}
JSON
}

# A camera 5 m above the origin looking straight down (FX, CX, CY set by the caller): world
# (x, 0, z) is pixel (fx x / 5 + cx, fx z / 5 + cy), which the calibrate tests' clicks are
# computed from. WHITE_BALANCE, when given, is the probe's "white_balance" array.
write_topdown() {  # write_topdown FILE PHOTO PROBE REAL ROTATION_Y INTENSITY [WHITE_BALANCE]
    cat >"$1" <<JSON
{
  "schema_version": 1,
  "photo": {"path": "$2"},
  "probe": {"path": "$3", "rotation_deg": [0, $5, 0], "intensity": $6${7:+, \"white_balance\": $7}},
  "camera": {"model": "opencv", "fx": $FX, "fy": $FX, "cx": $CX, "cy": $CY,
             "rotation": [[1, 0, 0], [0, 0, 1], [0, -1, 0]], "translation": [0, 0, 5]},
  "real": [$4]
}
JSON
}
FLOOR18='{"name": "floor", "shape": {"type": "plane", "size": [20, 20]}, "albedo": [0.18, 0.18, 0.18]}'

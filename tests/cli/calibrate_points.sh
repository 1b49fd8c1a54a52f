# `calibrate rectangle | points | vanishing` with image points of a known camera: 1000x750,
# f = 800 px, at (1.5, 1.6, 2.5) looking at (0.3, 0, -0.2). The rectangle, the points and the
# origin put the world origin where the true camera has it, so the position must match.
source "$(dirname "$0")/testlib.bash" "$@"

# expect_camera WHAT: fx within 1% of 800 and the position within 1% of the 3.4 m distance.
expect_camera() {
    local fx pos
    fx=$(awk '/^intrinsics:/ { print $3 }' stdout.txt)
    awk -v f="$fx" 'BEGIN { exit !(f > 792 && f < 808) }' || fail "$1: fx $fx, expected 800"
    pos=$(awk '/^position:/ { print $2, $3, $4 }' stdout.txt)
    echo "$pos" | awk '{ d = sqrt(($1 - 1.5)^2 + ($2 - 1.6)^2 + ($3 - 2.5)^2); exit !(d < 0.034) }' ||
        fail "$1: position $pos, expected 1.5 1.6 2.5"
}

# --size alone creates a project whose photo is to be named.
run calibrate rectangle rect.json --size 1000x750 --focal 800 --width 0.6 --height 0.4 \
    --corners 413.518,381.519 549.410,412.026 508.295,466.634 360.722,428.922
expect_rc 0 "a new project from --size"
expect_stdout "set photo.path to the 1000x750 photograph" "a new project from --size"
expect_stdout "uncertainty: focal length given, principal point held, rotation ± " "rectangle"
grep -q '"path": "photo.jpg"' rect.json || fail "the new project names no photo to replace"
expect_camera "rectangle on a new project"

# --json: stdout is one JSON object with the same camera; the human lines go to stderr.
run calibrate rectangle rect_json.json --size 1000x750 --focal 800 --width 0.6 --height 0.4 \
    --corners 413.518,381.519 549.410,412.026 508.295,466.634 360.722,428.922 --json
expect_rc 0 "rectangle --json"
expect_stderr "set photo.path to the 1000x750 photograph" "rectangle --json: notes on stderr"
/usr/bin/python3 - stdout.txt <<'PY' || fail "rectangle --json"
import json, math, sys
d = json.load(open(sys.argv[1]))
assert d["method"].startswith("rectangle"), d["method"]
assert abs(d["intrinsics"]["fx"] - 800) < 1e-6, d["intrinsics"]
p = d["position"]
assert math.dist(p, [1.5, 1.6, 2.5]) < 0.034, p
assert d["uncertainty"]["rotation_deg"] > 0 and not d["uncertainty"]["focal_free"], d["uncertainty"]
assert d["image"] == {"width": 1000, "height": 750}, d["image"]
PY

make_inputs
run make-test-image photo1000.png --size 1000 750 --value 0.5 0.5 0.5
write_project scene.json "$BALL" "$FLOOR" photo1000.png
run calibrate rectangle scene.json --size 1000x750 --focal 800 --width 0.6 --height 0.4 \
    --corners 413.518,381.519 549.410,412.026 508.295,466.634 360.722,428.922
expect_rc 0 "rectangle with a focal length"
expect_camera "rectangle"
run info scene.json
expect_rc 0 "the project loads after calibration"

cat >points.json <<'JSON'
{"points": [
  {"world": [0, 0, 0], "image": [413.518, 381.519]},
  {"world": [0.6, 0, 0], "image": [549.410, 412.026]},
  {"world": [0.6, 0, 0.4], "image": [508.295, 466.634]},
  {"world": [0, 0, 0.4], "image": [360.722, 428.922]},
  {"world": [0.3, 0.5, 0.2], "image": [453.093, 298.624]},
  {"world": [0.1, 0.8, -0.3], "image": [463.179, 173.747]},
  {"world": [0.5, 0.3, -0.4], "image": [563.372, 298.975]}]}
JSON
run calibrate points scene.json --photo photo1000.png --file points.json
expect_rc 0 "seven points, focal length unknown"
expect_camera "points"

run calibrate vanishing scene.json --photo photo1000.png \
    --x 313.041,358.962,650.975,434.827 --x 253.016,401.398,620.047,495.192 \
    --x 374.111,315.787,681.292,375.654 \
    --z 475.916,325.495,345.697,442.412 --z 597.218,348.529,496.481,482.324 \
    --z 686.503,365.483,611.095,512.663 \
    --origin 413.518,381.519 --distance 413.518,381.519,650.975,434.827,1
expect_rc 0 "vanishing points"
expect_camera "vanishing"
RMS=$(field rms_px)
at_most "$RMS" 0.01 || fail "vanishing: rms_px $RMS for exact lines"
# The focal length's uncertainty beside it, in pixels and percent.
grep -qE '^uncertainty: fx 800(\.[0-9]+)? ± [0-9.]+ px \([0-9.]+ %\), principal point held, rotation ± [0-9.]+°, position ± [0-9.]+ m' stdout.txt ||
    fail "vanishing: no uncertainty line"

# The scale from a vertical box edge 0.28 m tall (its foot first), three directions.
run calibrate vanishing scene.json --photo photo1000.png \
    --x 313.041,358.962,650.975,434.827 --x 253.016,401.398,620.047,495.192 \
    --z 475.916,325.495,345.697,442.412 --z 597.218,348.529,496.481,482.324 \
    --y 446.174,375.654,443.965,314.488 --y 582.363,405.326,586.041,341.114 \
    --y 397.620,421.737,392.931,355.904 \
    --origin 413.518,381.519 --vertical 582.363,405.326,586.041,341.114,0.28
expect_rc 0 "vanishing points, vertical length"
expect_camera "vanishing, vertical length"
[ -s stderr.txt ] && fail "vanishing, vertical length: warnings for exact input"
echo PASS

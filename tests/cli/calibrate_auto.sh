# `calibrate auto`: the camera from the photo's own lines. A checkered floor rendered through a
# known camera is matched (focal length, where up is); the proposed lines, written as a
# `calibrate vanishing` file, solve the same when read back and can be edited; bad input and
# a photo without lines exit 2 saying what to do.
source "$(dirname "$0")/testlib.bash" "$@"

# The floor: an 8 x 8 m plane of 0.5 m checks as a virtual object, turned 45 degrees (both
# directions converge), rendered over a grey plate.
run make-test-image checks.png --size 256 256 --checker 16 --value 0.85 0.85 0.85 --value2 0.08 0.08 0.08
expect_rc 0 "make-test-image checks"
run make-test-image plate.exr --size 320 240 --value 0.3 0.3 0.3
expect_rc 0 "make-test-image plate"
run make-test-image probe.exr --size 64 32 --value 1 1 1
expect_rc 0 "make-test-image probe"
cat >floor.json <<'JSON'
{
  "schema_version": 1,
  "photo": {"path": "plate.exr"},
  "probe": {"path": "probe.exr"},
  "camera": {"model": "lookat", "eye": [0.4, 1.5, 3], "target": [0, 0, -1], "vfov_deg": 50},
  "real": [],
  "objects": [{"name": "floor", "shape": {"type": "plane", "size": [8, 8]}, "transform": {"translation": [0, 0, -1.5], "rotation_deg": [0, 45, 0]},
               "material": {"type": "diffuse", "albedo": {"texture": "checks.png"}}}],
  "render": {"photons_per_pass": 20000, "passes": 8, "seed": 3}
}
JSON
run render floor.json -o floor.png
expect_rc 0 "render the floor"

run calibrate auto auto.json --photo floor.png --camera-height 1.5 --lines-out lines.json --picture lines.png --json
expect_rc 0 "calibrate auto on the floor"
cp stdout.txt result.json
expect_stderr "X (ground)" "the proposal names its directions"
[ -s auto.json ] && [ -s lines.json ] && [ -s lines.png ] || fail "auto.json, lines.json or lines.png missing"
# The truth: vfov 50 at 240 rows is a focal length of 120 / tan(25 deg); up from the look-at.
# Within three of the solver's own standard deviations (its stated uncertainty covers the
# truth), and within 10 % and 3 degrees whatever it states.
python3 - auto.json result.json <<'PY' || fail "the camera from the lines is not the renderer's"
import json, math, sys
cam = json.load(open(sys.argv[1]))["camera"]
u = json.load(open(sys.argv[2]))["uncertainty"]
f_true = 120 / math.tan(math.radians(25))
eye, target = [0.4, 1.5, 3], [0, 0, -1]
fwd = [t - e for t, e in zip(target, eye)]
n = math.sqrt(sum(v * v for v in fwd)); fwd = [v / n for v in fwd]
# Camera axes in the world (x right, y down, z forward) with world up (0, 1, 0).
x = [-fwd[2], 0, fwd[0]]; n = math.sqrt(sum(v * v for v in x)); x = [v / n for v in x]
y = [fwd[1] * x[2] - fwd[2] * x[1], fwd[2] * x[0] - fwd[0] * x[2], fwd[0] * x[1] - fwd[1] * x[0]]
up_true = [x[1], y[1], fwd[1]]  # world up in camera coordinates
R = cam["rotation"]
up = [R[0][1], R[1][1], R[2][1]]
cosang = sum(a * b for a, b in zip(up, up_true)) / math.sqrt(sum(a * a for a in up) * sum(b * b for b in up_true))
angle = math.degrees(math.acos(max(-1, min(1, cosang))))
print(f"calibrate auto: focal {cam['fx']:.1f} px (true {f_true:.1f}, stated +- {u['fx']:.1f}), "
      f"up {angle:.3f} deg from the truth (stated rotation +- {u['rotation_deg']:.2f})")
assert abs(cam["fx"] - f_true) < 3 * u["fx"] and abs(cam["fx"] / f_true - 1) < 0.1, cam["fx"]
assert angle < 3 * u["rotation_deg"] and angle < 3, angle
PY

# The lines file solves the same through `calibrate vanishing`; with its Z lines dropped it
# no longer fixes the focal length, which the solve says.
run calibrate vanishing again.json --photo floor.png --file lines.json
expect_rc 0 "calibrate vanishing on the proposed lines"
python3 - auto.json again.json <<'PY' || fail "the lines file does not give the same camera"
import json, sys
a, b = (json.load(open(p))["camera"] for p in sys.argv[1:3])
assert abs(a["fx"] / b["fx"] - 1) < 1e-6, (a["fx"], b["fx"])
PY
python3 - lines.json <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
doc["z"] = []
json.dump(doc, open("x_only.json", "w"))
PY
expect_refused "one direction of lines" "x_only.json" calibrate vanishing xonly.json --photo floor.png --file x_only.json

# --dry-run prints the camera and writes nothing; --json gives the result on stdout.
run calibrate auto dry.json --photo floor.png --dry-run --json
expect_rc 0 "calibrate auto --dry-run --json"
[ ! -e dry.json ] || fail "--dry-run wrote the project"
python3 -c 'import json, sys; d = json.load(open("stdout.txt")); assert d["intrinsics"]["fx"] > 0, d' ||
    fail "--json printed no result"

# Bad input and a photo without lines: exit 2, the file and what to do named.
expect_refused "a missing photo" "gone.png" calibrate auto x.json --photo gone.png
expect_refused "a camera height of 0" "--camera-height" calibrate auto x.json --photo floor.png --camera-height 0
run make-test-image flat.png --size 160 120 --value 0.5 0.5 0.5
expect_refused "a photo without lines" "draw lines along two directions" \
    calibrate auto x.json --photo flat.png --lines-out flat_lines.json
[ -s flat_lines.json ] || fail "the lines file is not written when no camera is found"
[ ! -e x.json ] || fail "a project was written without a camera"
expect_refused "the lines file onto the photo" "--lines-out" calibrate auto x.json --photo floor.png --lines-out floor.png
echo "ok"

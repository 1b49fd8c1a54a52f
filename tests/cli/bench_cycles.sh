# The `cycles` bench method: one skip line when Blender is missing (CI has none), a clear
# message when Blender fails; where Blender is installed, a tiny scene renders and its rows
# appear, and cycles_render.py --artist (Blender 5 only) exits 2. The Blender 5 methods:
# bench_cycles5.sh.
SCRIPT=$(cd "$(dirname "$0")/../../bench/cycles" && pwd)/cycles_render.py
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
mkdir -p scenes/tiny
cp photo.exr probe.exr scenes/tiny/
write_project scenes/tiny/scene.json "$BALL" "$FLOOR"
for half in a:11 b:22; do
    run render scenes/tiny/scene.json -o "scenes/tiny/truth-${half%%:*}.exr" --layers \
        --method standard-correlated --passes 16 --seed "${half##*:}"
    expect_rc 0 "truth half ${half%%:*}"
done
SKIP="cycles: skipped, Blender not found (install Debian's blender or pass --blender)"

# rows_of FILE METHOD: the number of rows of METHOD in a bench output.
rows_of() {
    python3 -c 'import json, sys; print(sum(r["method"] == sys.argv[2] for r in json.load(open(sys.argv[1]))["rows"]))' "$1" "$2"
}

run bench scenes/tiny -o rows.json --methods cycles --blender /nonexistent
expect_rc 0 "--blender /nonexistent"
expect_stdout "$SKIP" "the skip line for a missing --blender"
[ "$(grep -cF "cycles: skipped" stdout.txt)" -eq 1 ] || fail "the skip line is printed more than once"
[ "$(rows_of rows.json cycles)" -eq 0 ] || fail "rows for a skipped method"

# The other methods go on; $DP_BLENDER, then PATH, are where Blender is looked for.
DP_BLENDER=/nonexistent run bench scenes/tiny -o rows.json --methods differential,cycles \
    --max-seconds-differential 0.3
expect_rc 0 "\$DP_BLENDER pointing nowhere"
expect_stdout "$SKIP" "the skip line for a missing \$DP_BLENDER"
[ "$(rows_of rows.json differential)" -ge 1 ] || fail "no differential rows beside the skipped method"
(unset DP_BLENDER; PATH=/nonexistent run bench scenes/tiny -o rows.json --methods cycles; exit "$RC")
RC=$?
expect_rc 0 "no Blender on PATH"
[ "$(cat stdout.txt)" = "$SKIP
wrote rows.json" ] || fail "no Blender on PATH: expected the skip line, got: $(cat stdout.txt)"

# A Blender that fails: reported on stderr naming the scene, the bench still writes its rows.
run bench scenes/tiny -o rows.json --methods cycles --blender /bin/false
expect_rc 0 "a failing Blender"
expect_stderr "Blender failed (exit code 1)" "message for a failing Blender"
expect_stderr "scenes/tiny/scene.json" "the message names the scene"
run bench scenes/tiny -o rows.json --methods cyclez
expect_rc 2 "an unknown method"
expect_stderr "cycles, cycles5 or cycles5-artist" "the list of methods names the Cycles methods"

blender=${DP_BLENDER:-$(command -v blender || true)}
if [ -z "$blender" ]; then
    echo "note: Blender is not installed; the Cycles render part of this test did not run"
    exit 0
fi
# --artist (Cycles as artists run it in Blender 5) is refused by Blender 3.4: exit 2, a message.
"$blender" -b --factory-startup --python-exit-code 1 -P "$SCRIPT" -- scenes/tiny/scene.json --out artist \
    --artist >artist.log 2>&1
RC=$?
[ "$RC" -eq 2 ] || fail "--artist under $blender: exit code $RC, expected 2: $(tail -5 artist.log)"
grep -q "^error: --artist needs Blender 5 " artist.log || fail "--artist under $blender: no clear message: $(tail -5 artist.log)"
[ ! -e artist/renders.json ] || fail "--artist under $blender rendered"
run bench scenes/tiny -o rows.json --methods cycles --blender "$blender" --max-seconds-standard 0.5 --threads 2
expect_rc 0 "bench --methods cycles with $blender"
python3 - rows.json <<'PY' || fail "Cycles' bench rows are incomplete or wrong"
import json, math, sys
doc = json.load(open(sys.argv[1]))
rows = [r for r in doc["rows"] if r["method"] == "cycles"]
assert len(rows) >= 3, rows
assert [r["passes"] for r in rows] == [2 ** k for k in range(len(rows))], rows
for r in rows:
    for k in ("seconds", "rmse", "rel_rmse", "rel_rmse_changed"):
        assert math.isfinite(r[k]) and r[k] >= 0, (k, r)
    assert r["samples_per_pixel"] == r["passes"] and r["photons"] == 0, r
assert rows[-1]["seconds"] >= 0.5, rows[-1]  # it stops after the render that takes the budget
assert rows[-1]["rel_rmse_changed"] < rows[0]["rel_rmse_changed"], (rows[0], rows[-1])
assert doc["runs"][0]["method"] == "cycles" and doc["runs"][0]["passes"] == rows[-1]["passes"], doc["runs"]
PY

# Lamps: a point and a rect light over the ball and the floor. The conversion carries them
# (their light on the real floor through a second view layer: dp_cycles.setup_lamp_layer), so
# Cycles' composite converges to the truth as the other methods' do; without the lamps the
# floor's change, most of the image's, would stay missing (a relative error near 1).
mkdir -p scenes/lamps
cp photo.exr probe.exr scenes/lamps/
write_project scenes/lamps/scene.json "$BALL" "$FLOOR"
sed -i 's|^  "render"|  "lights": [{"name": "bulb", "type": "point", "transform": {"translation": [1, 1.5, 0.8]}, "power_w": 60},\
             {"name": "panel", "type": "rect", "transform": {"translation": [-1, 1.8, 0.5], "rotation_deg": [0, 0, -30]},\
              "power_w": 100, "size": [0.5, 0.4], "visible": false}],\
  "render"|' scenes/lamps/scene.json
for half in a:11 b:22; do
    run render scenes/lamps/scene.json -o "scenes/lamps/truth-${half%%:*}.exr" --layers \
        --method standard-correlated --passes 64 --seed "${half##*:}"
    expect_rc 0 "lamps: truth half ${half%%:*}"
done
run bench scenes/lamps -o lamps.json --methods cycles --blender "$blender" --max-seconds-standard 2 --threads 2
expect_rc 0 "bench --methods cycles on a scene with lamps"
python3 - lamps.json <<'PY' || fail "Cycles on the scene with lamps"
import json, sys
rows = [r for r in json.load(open(sys.argv[1]))["rows"] if r["method"] == "cycles"]
print("lamps: cycles relative RMSE over the changed pixels:", [round(r["rel_rmse_changed"], 3) for r in rows])
assert rows[-1]["rel_rmse_changed"] < 0.15, rows[-1]
assert rows[-1]["rel_rmse_changed"] < 0.5 * rows[0]["rel_rmse_changed"], (rows[0], rows[-1])
PY

# The `cycles5` and `cycles5-artist` bench methods (Blender 5 as a Python module, PyPI bpy): one
# skip line per method without Blender 5, a clear message when it fails; where .deps/bpy5 (or
# $DP_BPY5_PYTHON) holds Blender 5, a tiny scene rendered at 2 spp by both gives a finite image
# of the photo's size whose mean change to the photo is within 10% of the truth's and of Blender
# 3.4's (where installed), and the bench's rows. Exit 77 (skipped) without Blender 5.
HERE=$(cd "$(dirname "$0")" && pwd)
SOURCE=$(cd "$HERE/../.." && pwd)
source "$HERE/testlib.bash" "$@"
make_inputs
mkdir -p scenes/tiny
cp photo.exr probe.exr scenes/tiny/
write_project scenes/tiny/scene.json "$BALL" "$FLOOR"
for half in a:11 b:22; do
    run render scenes/tiny/scene.json -o "scenes/tiny/truth-${half%%:*}.exr" --layers \
        --method standard-correlated --passes 16 --seed "${half##*:}"
    expect_rc 0 "truth half ${half%%:*}"
done

rows_of() {
    python3 -c 'import json, sys; print(sum(r["method"] == sys.argv[2] for r in json.load(open(sys.argv[1]))["rows"]))' "$1" "$2"
}

# Without Blender 5: one line per method, the other methods go on.
DP_BPY5_PYTHON=/nonexistent run bench scenes/tiny -o rows.json --methods cycles5,differential,cycles5-artist \
    --max-seconds-differential 0.3
expect_rc 0 "\$DP_BPY5_PYTHON pointing nowhere"
for m in cycles5 cycles5-artist; do
    expect_stdout "$m: skipped, Blender 5 not found (\$DP_BPY5_PYTHON /nonexistent is not an executable)" \
        "the skip line of $m"
    [ "$(grep -c "^$m: skipped" stdout.txt)" -eq 1 ] || fail "the skip line of $m is not printed once"
    [ "$(rows_of rows.json "$m")" -eq 0 ] || fail "rows for the skipped $m"
done
[ "$(rows_of rows.json differential)" -ge 1 ] || fail "no differential rows beside the skipped methods"

# A Python that fails: reported on stderr with the method and the scene, the rows still written.
DP_BPY5_PYTHON=/bin/false run bench scenes/tiny -o rows.json --methods cycles5-artist
expect_rc 0 "a failing Blender 5"
expect_stderr "cycles5-artist: " "the message names the method"
expect_stderr "Blender failed (exit code 1)" "message for a failing Blender 5"
expect_stderr "scenes/tiny/scene.json" "the message names the scene"

python=${DP_BPY5_PYTHON:-$SOURCE/.deps/bpy5/bin/python}
if ! "$python" -c 'import sys, bpy; sys.exit(not bpy.app.version_string.startswith("5."))' >/dev/null 2>&1; then
    echo "skipped: Blender 5 is not installed ($python cannot import bpy 5; scripts/install-deps.sh --bench" \
         "makes .deps/bpy5): the Blender 5 renders of this test did not run"
    exit 77
fi
script=$SOURCE/bench/cycles/cycles_render.py
"$python" "$script" scenes/tiny/scene.json --out raw --spp 2 --threads 2 >raw.log 2>&1 ||
    fail "Blender 5, 2 spp: $(tail -5 raw.log)"
"$python" "$script" scenes/tiny/scene.json --out artist --spp 2 --threads 2 --artist >artist.log 2>&1 ||
    fail "Blender 5 --artist, 2 spp: $(tail -5 artist.log)"
grep -q '"artist": true' artist/renders.json || fail "--artist is not recorded in renders.json"
images=(raw/cycles-2.exr artist/cycles-2.exr)
blender=${DP_BLENDER:-$(command -v blender || true)}
if [ -n "$blender" ]; then
    "$blender" -b --factory-startup --python-exit-code 1 -P "$script" -- scenes/tiny/scene.json --out b34 \
        --spp 2 --threads 2 >b34.log 2>&1 || fail "Blender 3.4, 2 spp: $(tail -5 b34.log)"
    images+=(b34/cycles-2.exr)
else
    echo "note: Blender 3.4 is not installed; the Blender 5 renders are compared with the truth only"
fi
# Each image: finite, the photo's size; its mean change to the photo (the ball, its shadow)
# within 10% of the truth's and of Blender 3.4's at the same seed and spp, and its RMSE against
# the truth at most 1.5 times Blender 3.4's.
"$python" - "$SOURCE/bench/cycles" scenes/tiny "${images[@]}" <<'PY' || fail "Blender 5's renders differ"
import math, sys
sys.path.insert(0, sys.argv[1])
from check_conversion import read_exr
scene, paths = sys.argv[2], sys.argv[3:]
def load(p):
    w, h, px = read_exr(p)
    return w, h, list(px)
pw, ph, photo = load(scene + "/photo.exr")
ta, tb = load(scene + "/truth-a.exr")[2], load(scene + "/truth-b.exr")[2]
truth = [0.5 * (a + b) for a, b in zip(ta, tb)]
change = lambda img: sum(x - p for x, p in zip(img, photo)) / len(img)
rmse = lambda img: math.sqrt(sum((x - t) ** 2 for x, t in zip(img, truth)) / len(img))
renders = {}
for p in paths:
    w, h, img = load(p)
    assert (w, h) == (pw, ph), f"{p}: {w}x{h}, the photo is {pw}x{ph}"
    assert all(math.isfinite(x) for x in img), f"{p}: not finite"
    renders[p] = img
refs = {"truth": change(truth)}
if "b34/cycles-2.exr" in renders:
    refs["Blender 3.4"] = change(renders["b34/cycles-2.exr"])
for p in ("raw/cycles-2.exr", "artist/cycles-2.exr"):
    c = change(renders[p])
    print(f"{p}: mean change {c:.5f} (" + ", ".join(f"{k} {v:.5f}" for k, v in refs.items()) +
          f"), RMSE against the truth {rmse(renders[p]):.4f}")
    for k, v in refs.items():
        assert abs(c - v) <= 0.1 * abs(v), f"{p}: mean change {c} against {k}'s {v}"
    if "b34/cycles-2.exr" in renders:
        r34 = rmse(renders["b34/cycles-2.exr"])
        assert rmse(renders[p]) <= 1.5 * r34, f"{p}: RMSE {rmse(renders[p])} against Blender 3.4's {r34}"
PY

# The bench: both methods' rows at 1, 2, 4, ... spp until the budget (2 s: on a loaded machine the
# artist's first render alone took 0.3 s, and a budget that short left it one row).
DP_BPY5_PYTHON=$python run bench scenes/tiny -o rows.json --methods cycles5,cycles5-artist \
    --max-seconds-standard 2 --threads 2
expect_rc 0 "bench --methods cycles5,cycles5-artist"
python3 - rows.json <<'PY' || fail "Blender 5's bench rows are incomplete or wrong"
import json, math, sys
doc = json.load(open(sys.argv[1]))
for m in ("cycles5", "cycles5-artist"):
    rows = [r for r in doc["rows"] if r["method"] == m]
    assert len(rows) >= 2, (m, rows)
    assert [r["passes"] for r in rows] == [2 ** k for k in range(len(rows))], rows
    for r in rows:
        for k in ("seconds", "rmse", "rel_rmse", "rel_rmse_changed"):
            assert math.isfinite(r[k]) and r[k] >= 0, (k, r)
        assert r["samples_per_pixel"] == r["passes"], r
    # It stops at the budget, or where the samples reach their most (2^20): adaptive sampling
    # stops a tiny scene's pixels long before, so more samples cost no more time there.
    assert rows[-1]["seconds"] >= 2 or rows[-1]["passes"] >= 2 ** 20, rows[-1]
    assert rows[-1]["rel_rmse_changed"] < rows[0]["rel_rmse_changed"], (rows[0], rows[-1])
assert [r["method"] for r in doc["runs"]] == ["cycles5", "cycles5-artist"], doc["runs"]
PY

# Lamps: a point and a rect light over the ball and the floor (as bench_cycles.sh for Blender
# 3.4): Cycles 5's composite converges to the truth, the lamps' light on the floor included.
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
DP_BPY5_PYTHON=$python run bench scenes/lamps -o lamps.json --methods cycles5 --max-seconds-standard 2 --threads 2
expect_rc 0 "bench --methods cycles5 on a scene with lamps"
python3 - lamps.json <<'PY' || fail "Cycles 5 on the scene with lamps"
import json, sys
rows = [r for r in json.load(open(sys.argv[1]))["rows"] if r["method"] == "cycles5"]
print("lamps: cycles5 relative RMSE over the changed pixels:", [round(r["rel_rmse_changed"], 3) for r in rows])
assert rows[-1]["rel_rmse_changed"] < 0.15, rows[-1]
assert rows[-1]["rel_rmse_changed"] < 0.5 * rows[0]["rel_rmse_changed"], (rows[0], rows[-1])
PY

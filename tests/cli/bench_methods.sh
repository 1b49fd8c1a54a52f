# The standard method from the command line, and `bench` on a tiny scene with its own truth.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"

run render scene.json -o std.exr --method standard --passes 4 --layers
expect_rc 0 "render --method standard"
expect_stderr "spp/s" "progress of a path-traced method"
compare photo.exr std.exr
is_positive "$MAX_DIFF" || fail "the standard method did not change the photo"
run render scene.json -o std.exr --method standard --pixel 3,3
expect_rc 2 "--pixel with the standard method"
expect_stderr "--method differential" "message naming the method --pixel needs"
run render scene.json -o x.exr --method magic
expect_rc 2 "an unknown method"

# A bench scene: scene.json plus two truth halves (standard method, correlated, two seeds).
mkdir -p scenes/tiny
cp photo.exr probe.exr scenes/tiny/
write_project scenes/tiny/scene.json "$BALL" "$FLOOR"
for half in a:11 b:22; do
    run render scenes/tiny/scene.json -o "scenes/tiny/truth-${half%%:*}.exr" --layers \
        --method standard-correlated --passes 64 --seed "${half##*:}"
    expect_rc 0 "truth half ${half%%:*}"
done
run bench scenes/tiny -o rows.json --max-seconds-differential 3 --max-seconds-standard 1.5
expect_rc 0 "bench"
expect_stdout "wrote rows.json" "bench summary line"
python3 - rows.json <<'PY' || fail "bench rows are incomplete or wrong"
import json, math, sys
doc = json.load(open(sys.argv[1]))
rows = doc["rows"]
assert doc["scenes"][0]["changed_pixels"] > 0, doc["scenes"]
for m in ("differential", "standard", "standard-correlated"):
    mine = [r for r in rows if r["method"] == m]
    assert len(mine) >= 2, (m, len(mine))  # the sanitizer build is ten times slower
    for r in mine:
        for k in ("seconds", "passes", "photons", "rmse", "rel_rmse", "rel_rmse_changed"):
            assert math.isfinite(r[k]) and r[k] >= 0, (m, k, r[k])
    # More time, less error: the last measurement beats the first.
    assert mine[-1]["rel_rmse_changed"] < mine[0]["rel_rmse_changed"], (m, mine[0], mine[-1])
    assert all(a["seconds"] < b["seconds"] for a, b in zip(mine, mine[1:])), m
assert all(r["photons"] == 0 for r in rows if r["method"] != "differential")
PY
run bench scenes/missing -o rows.json
expect_rc 2 "a missing scene folder"
rm scenes/tiny/truth-b.exr
run bench scenes/tiny -o rows.json
expect_rc 2 "a scene without its truth"
expect_stderr "truth-b.exr" "message naming the missing truth"

# `calibrate probe --sun-from-shadow`: a probe whose sun was clipped to a twentieth is flagged
# on load, and restored from a sunlit and a shadowed patch of the floor in a path-traced photo
# (probe.sun_scale); bad patches and a bad sun_scale are refused naming the option or field.
source "$(dirname "$0")/testlib.bash" "$@"

run make-test-image blank.exr --size 128 96 --value 0.5 0.5 0.5
expect_rc 0 "photo size"
SKY=(--value 0.3 0.35 0.4 --sky-zenith 0.15 0.2 0.4 --sun-dir 1 0.8 0 --sun-radius-deg 1.5)
run make-test-image sun.exr --size 512 256 --probe-sun --sun-irradiance 3 "${SKY[@]}"
expect_rc 0 "probe"
run make-test-image clipped.exr --size 512 256 --probe-sun --sun-irradiance 0.15 "${SKY[@]}"
expect_rc 0 "clipped probe"
FX=64 CX=63.5 CY=47.5
# A slab 0.6 above the floor: the sun, 39 deg up along +x, throws its shadow 0.75 towards -x.
REAL="$FLOOR18"', {"name": "slab", "shape": {"type": "box", "size": [0.8, 0.05, 0.8]},
                   "transform": {"translation": [0, 0.6, 0]}, "albedo": [0.18, 0.18, 0.18]}'
write_topdown truth.json blank.exr sun.exr "$REAL" 0 1
run reference truth.json --real-only -o lit.exr --spp 256
expect_rc 0 "synthetic photo"
write_topdown scene.json lit.exr clipped.exr "$REAL" 0 1

# Loading the clipped probe warns; the whole one does not.
expect_warned "clipped sun" "likely clipped" render scene.json --passes 1 -o before.exr
write_topdown whole.json lit.exr sun.exr "$REAL" 0 1
run render whole.json --passes 1 -o whole.exr
expect_rc 0 "whole sun"
grep -q "clipped" stderr.txt && fail "a whole sun was called clipped"

# World (1.2, 0, 0.8) is in sunlight, (-0.9, 0, 0) in the slab's shadow.
run calibrate probe scene.json --sun-from-shadow 79 58 52 47.5
expect_rc 0 "sun from shadow"
expect_stdout "lit / shadowed patch: photo " "contrast summary"
S=$(sed -n 's/^probe sun_scale 1 -> \([^ ]*\) .*/\1/p' stdout.txt)
awk -v s="$S" 'BEGIN { exit !(s > 18 && s < 22) }' || fail "sun_scale $S, expected 20 within 10%"
grep -q '"sun_scale"' scene.json || fail "sun_scale not written to the project"
run render scene.json --passes 1 -o after.exr
expect_rc 0 "restored sun"
grep -q "clipped" stderr.txt && fail "the restored sun is still called clipped"
# A second match finds nothing left to restore.
run calibrate probe scene.json --sun-from-shadow 79 58 52 47.5 -o again.json
expect_rc 0 "second match"
S2=$(sed -n 's/^probe sun_scale [^ ]* -> [^ ]* (x\([^)]*\))$/\1/p' stdout.txt)
awk -v s="$S2" 'BEGIN { exit !(s > 0.97 && s < 1.03) }' || fail "second match x$S2, expected 1"

expect_refused "patch outside" "--sun-from-shadow" calibrate probe scene.json --sun-from-shadow 1 1 52 47.5 -o x.json
expect_stderr "not inside the photo" "patch outside message"
expect_refused "patches on two proxies" "two real proxies" calibrate probe scene.json --sun-from-shadow 79 58 63.5 47.5 -o x.json
sed 's/"sun_scale": [0-9.e+-]*/"sun_scale": 0/' scene.json > zero.json
expect_refused "zero sun_scale" "field 'probe.sun_scale': must be in (0, " render zero.json --passes 1 -o z.exr

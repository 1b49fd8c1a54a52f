# `calibrate albedo`: a synthetic photo of a floor of known albedo, rendered by `reference`,
# gives back that albedo as a texture the project then uses; bad requests exit with code 2.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
FLOOR60='{"name": "floor", "shape": {"type": "plane", "size": [6, 6]}, "albedo": [0.6, 0.4, 0.3]}'
write_project truth.json "" "$FLOOR60"
run reference truth.json --real-only -o synthetic.exr --spp 256
expect_rc 0 "synthetic photo"

# The same scene with the synthetic photo and a wrong albedo, which the estimate replaces.
write_project scene.json "" "$(echo "$FLOOR60" | sed 's/\[0.6, 0.4, 0.3\]/[0.1, 0.1, 0.1]/')" synthetic.exr
run calibrate albedo scene.json --resolution 16 --samples 256
expect_rc 0 "albedo"
expect_stdout "real[0] 'floor': 16x16 texels" "albedo summary"
expect_stdout "wrote scene.json" "albedo writes the project"
[ -s scene_floor_albedo.exr ] || fail "no texture written"
[ -s scene_floor_albedo_mask.exr ] || fail "no mask written"
grep -q '"texture": "scene_floor_albedo.exr"' scene.json || fail "the project does not use the texture"

# mean_albedo (r, g, b): within 5% of the true albedo.
read -r R G B <<<"$(sed -n 's/.*mean_albedo (\([^,]*\), \([^,]*\), \([^)]*\)).*/\1 \2 \3/p' stdout.txt)"
[ -n "$R" ] || fail "no mean_albedo figure"
for pair in "$R 0.6" "$G 0.4" "$B 0.3"; do
    set -- $pair
    awk -v v="$1" -v t="$2" 'BEGIN { d = (v - t) / t; exit !(d < 0.05 && d > -0.05) }' ||
        fail "mean albedo $R $G $B is not within 5% of 0.6 0.4 0.3"
done

run info scene.json
expect_rc 0 "info loads the texture"
expect_stdout "texture 'scene_floor_albedo.exr' (16x16)" "info shows the texture"

run calibrate albedo scene.json --proxy nothing
expect_rc 2 "unknown proxy"
expect_stderr "no real proxy named 'nothing'" "unknown proxy message"

write_project ball.json "" '{"name": "ball", "shape": {"type": "sphere", "radius": 1}}'
run calibrate albedo ball.json
expect_rc 2 "only a sphere"
expect_stderr "no plane, box or mesh proxy" "sphere-only message"

# Seen from behind the camera: the floor is nowhere in the photo.
write_project hidden.json "" '{"name": "floor", "shape": {"type": "plane", "size": [1, 1]},
                              "transform": {"translation": [0, 0, 9]}}'
run calibrate albedo hidden.json --resolution 8
expect_rc 2 "a proxy the photo never sees"
expect_stderr "never sees this proxy" "unseen proxy message"
expect_stderr "real[0]" "unseen proxy field"

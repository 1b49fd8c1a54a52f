# `diffphoton info` prints what a project holds.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
CUBE='{"name": "cube", "shape": {"type": "box", "size": [0.4, 0.4, 0.4]},
       "transform": {"translation": [0.3, 0.6, 0]}, "material": {"type": "mirror"}}'
GLASS='{"name": "far glass", "shape": {"type": "sphere", "radius": 0.2},
        "transform": {"translation": [-3, 0.2, -3]}, "material": {"type": "glass", "ior": 1.33}}'
ESTIMATED='{"name": "floor", "shape": {"type": "plane", "size": [10, 10]}, "albedo": "estimate"}'
write_project scene.json "$BALL, $CUBE, $GLASS" "$ESTIMATED"

run info scene.json
expect_rc 0 "info"
expect_stdout "photo: 'photo.exr'" "photo"
expect_stdout "64x48" "photo size"
expect_stdout "exposure 0" "photo exposure"
expect_stdout "probe: 'probe.exr'" "probe"
expect_stdout "latlong 64x32" "probe size and format"
expect_stdout "intensity 1" "probe intensity"
expect_stdout "camera: lookat" "camera model"
expect_stdout "fx " "intrinsics"
expect_stdout "position (" "camera position"
expect_stdout "'floor': plane 10 x 10, albedo estimated from the photo" "real proxy"
expect_stdout "'ball': sphere radius 0.5, diffuse" "virtual ball"
expect_stdout "'cube': box 0.4 x 0.4 x 0.4, mirror" "virtual cube"
expect_stdout "'far glass': sphere radius 0.2, glass, ior 1.33" "virtual glass"
expect_stdout "render: photons_per_pass 20000, passes 3" "render settings"
expect_stdout "warnings: 0" "warnings"
# The cube overlaps the ball and shares its emission cluster; the far glass ball has its own.
expect_stdout "emission clusters: 2" "clusters"
grep -qE "radius [0-9.]+: 'ball', 'cube'|radius [0-9.]+: 'cube', 'ball'" stdout.txt ||
    fail "ball and cube should share a cluster"

# The same facts as one JSON object for scripts.
run info scene.json --json
expect_rc 0 "info --json"
/usr/bin/python3 - stdout.txt <<'PY' || fail "info --json"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["photo"]["width"] == 64 and d["photo"]["height"] == 48, d["photo"]
assert d["probe"]["width"] == 64, d["probe"]
assert [o["name"] for o in d["objects"]] == ["ball", "cube", "far glass"], d["objects"]
assert d["project"]["render"]["photons_per_pass"] == 20000, d["project"]["render"]
assert d["camera"]["fx"] > 0 and len(d["camera"]["position"]) == 3, d["camera"]
assert len(d["emission_clusters"]) == 2 and d["warnings"] == [], d
PY

# A principled material is described with every parameter.
COPPER='{"name": "copper", "shape": {"type": "sphere", "radius": 0.3},
         "material": {"type": "principled", "base_colour": [0.95, 0.64, 0.54], "metallic": 1, "roughness": 0.3}}'
write_project principled.json "$COPPER" "$ESTIMATED"
run info principled.json
expect_rc 0 "info on a principled material"
expect_stdout "'copper': sphere radius 0.3, principled, base colour (0.95, 0.64, 0.54), metallic 1, roughness 0.3, ior 1.5, specular 1, transmission 0" "the principled material"

run info
expect_rc 2 "info without a project"
echo "PASS"

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

# Lights: each kind with its shape, power and where it shines, and what the renderers make of
# it (a point's intensity P/(4 pi) W/sr, a rect's face of 0.5 x 0.4 m = 0.2 m^2, radiance
# P/(pi A) = 100/(0.2 pi) = 159.155 W/(m^2 sr)).
write_project lights.json "$BALL" "$ESTIMATED"
sed -i 's|^  "render"|  "lights": [{"name": "bulb", "type": "point", "transform": {"translation": [1, 2, 0.5]}, "power_w": 62.8319},\
             {"name": "cone", "type": "spot", "transform": {"translation": [0, 2, 0], "rotation_deg": [90, 0, 0]},\
              "power_w": 200, "spot_angle_deg": 50, "spot_blend": 0.2},\
             {"name": "panel", "type": "rect", "power_w": 100, "size": [0.5, 0.4], "visible": false,\
              "transform": {"translation": [0, 2.5, -1]}},\
             {"type": "disk", "transform": {"translation": [0, 3, 0]}, "size": [0.4]}],\
  "render"|' lights.json
run info lights.json
expect_rc 0 "info with lights"
expect_stdout "virtual lights: 4" "the light count"
expect_stdout "'bulb': point, 62.8319 W, colour (1, 1, 1), shining along (0, -1, 0), intensity (5, 5, 5) W/sr  at (1, 2, 0.5)" "the point light"
expect_stdout "'cone': spot 50 deg, blend 0.2, 200 W, colour (1, 1, 1), shining along (0, 0, -1)" "the spot, turned by its rotation"
expect_stdout "'panel': rect 0.5 x 0.4, 100 W, colour (1, 1, 1), shining along (0, -1, 0), area 0.2 m^2, radiance (159.155, 159.155, 159.155) W/(m^2 sr), hidden from the camera" "the rect light"
expect_stdout "lights[3]: disk diameter 0.4, 100 W" "an unnamed disk light"
run info lights.json --json
expect_rc 0 "info --json with lights"
/usr/bin/python3 - stdout.txt <<'PY' || fail "info --json: the lights"
import json, sys
d = json.load(open(sys.argv[1]))
lights = d["lights"]
assert [l["type"] for l in lights] == ["point", "spot", "rect", "disk"], lights
assert [l["name"] for l in lights] == ["bulb", "cone", "panel", ""], lights
near = lambda a, b: all(abs(x - y) < 1e-4 * max(1, abs(y)) for x, y in zip(a, b))
assert near(lights[0]["position"], [1, 2, 0.5]) and near(lights[0]["intensity"], [5, 5, 5]), lights[0]
assert near(lights[1]["direction"], [0, 0, -1]) and lights[1]["power_w"] == 200, lights[1]
assert near([lights[2]["area"]], [0.2]) and near(lights[2]["radiance"], [159.155] * 3), lights[2]
assert lights[2]["visible"] is False and lights[3]["visible"] is True, lights
assert len(d["project"]["lights"]) == 4, d["project"]
PY
# A project without lights says so.
run info principled.json
expect_stdout "virtual lights: 0" "no lights"

run info
expect_rc 2 "info without a project"
echo "PASS"

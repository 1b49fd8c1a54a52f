# `calibrate fspy`: an fSpy project written here (a Blender camera 5 m in front of the origin,
# 1 m up, looking along +Y) becomes a camera at (0, 1, 5) looking along -Z, in a new project
# whose photo is the extracted image. A portrait project's focal length is across its height;
# the camera parameters fSpy exports as JSON import too.
source "$(dirname "$0")/testlib.bash" "$@"

le32() {  # little-endian uint32
    local v=$1 b
    for b in 0 8 16 24; do printf "\\x$(printf %02x $(((v >> b) & 255)))"; done
}

run make-test-image embedded.png --size 8 6 --value 0.2 0.3 0.4
expect_rc 0 "make the embedded image"
STATE='{"calibrationSettingsBase": {"referenceDistanceAxis": "xPositive", "referenceDistance": 1,
 "referenceDistanceUnit": "Centimeters"},
 "cameraParameters": {"principalPoint": {"x": 0, "y": 0},
  "cameraTransform": {"rows": [[1, 0, 0, 0], [0, 0, -1, -500], [0, 1, 0, 100], [0, 0, 0, 1]]},
  "horizontalFieldOfView": 1.0, "imageWidth": 800, "imageHeight": 600}}'
write_fspy() {  # write_fspy STATE IMAGE
    printf 'fspy'
    le32 1
    le32 ${#1}
    le32 "$(stat -c %s "$2")"
    printf '%s' "$1"
    cat "$2"
}
write_fspy "$STATE" embedded.png >scene.fspy

run calibrate fspy new.json scene.fspy --extract-photo photo.png
expect_rc 0 "import"
cmp -s photo.png embedded.png || fail "the extracted photo differs from the embedded one"
expect_stdout "position: 0.0000 1.0000 5.0000" "camera position in metres, Y up"
expect_stdout "forward: 0.0000 0.0000 -1.0000" "viewing direction"
expect_stdout "rms_px n/a" "fSpy stores no residual"
expect_stdout "cx 399.500 cy 299.500" "centred principal point"
grep -q '"path": "photo.png"' new.json || fail "the new project does not name the extracted photo"
# The photo is written byte for byte: a name of another format is refused, before anything is written.
expect_refused "a PNG extracted under a .jpg name" "--extract-photo" calibrate fspy other.json scene.fspy --extract-photo photo.jpg
expect_stderr "name it photo.png" "the right name suggested"
[ -e photo.jpg ] && fail "a refused --extract-photo wrote photo.jpg"
[ -e other.json ] && fail "a refused --extract-photo wrote the project"

# Portrait, 600x900: fSpy's relative focal length 2 is two half heights, 900 px; its
# "horizontal" field of view, 2 atan(1/2), is across the height too. No unit: no unknown unit.
CAMERA='{"principalPoint": {"x": 0, "y": 0},
  "cameraTransform": {"rows": [[1, 0, 0, 0], [0, 0, -1, -5], [0, 1, 0, 1], [0, 0, 0, 1]]},
  "horizontalFieldOfView": 0.9272952180016122, "relativeFocalLength": 2,
  "imageWidth": 600, "imageHeight": 900}'
PORTRAIT='{"calibrationSettingsBase": {"referenceDistanceAxis": "xPositive", "referenceDistance": 1,
 "referenceDistanceUnit": "No unit"}, "cameraParameters": '"$CAMERA"'}'
write_fspy "$PORTRAIT" embedded.png >portrait.fspy
run calibrate fspy portrait.json portrait.fspy
expect_rc 0 "import a portrait project"
expect_stdout "fx 900.000 fy 900.000 cx 299.500 cy 449.500" "focal length across the height"
expect_stderr "has no unit" "a reference distance without a unit"
grep -qF "unknown distance unit" stderr.txt && fail "'No unit' is read as an unknown unit"

# The same camera exported as JSON (File > Export > Camera parameters as JSON).
printf '%s\n' "$CAMERA" >camera-parameters.json
run calibrate fspy exported.json camera-parameters.json
expect_rc 0 "import the exported camera parameters"
expect_stdout "fspy: exported camera parameters" "told apart by content"
expect_stdout "fx 900.000 fy 900.000 cx 299.500 cy 449.500" "the same camera as the project's"
expect_stdout "position: 0.0000 1.0000 5.0000" "position in the file's lengths"
expect_stderr "no distance unit" "the export has no unit"
run calibrate fspy exported.json camera-parameters.json --extract-photo p.png
expect_rc 2 "no photo to extract from the JSON"
expect_stderr "hold no photo" "no photo to extract from the JSON"

head -c 40 scene.fspy >truncated.fspy
run calibrate fspy new.json truncated.fspy
expect_rc 2 "truncated file"
expect_stderr "truncated" "truncated file"
echo PASS

# `calibrate fspy`: an fSpy project written here (a Blender camera 5 m in front of the origin,
# 1 m up, looking along +Y) becomes a camera at (0, 1, 5) looking along -Z, in a new project
# whose photo is the extracted image.
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
{
    printf 'fspy'
    le32 1
    le32 ${#STATE}
    le32 "$(stat -c %s embedded.png)"
    printf '%s' "$STATE"
    cat embedded.png
} >scene.fspy

run calibrate fspy new.json scene.fspy --extract-photo photo.png
expect_rc 0 "import"
cmp -s photo.png embedded.png || fail "the extracted photo differs from the embedded one"
expect_stdout "position: 0.0000 1.0000 5.0000" "camera position in metres, Y up"
expect_stdout "forward: 0.0000 0.0000 -1.0000" "viewing direction"
expect_stdout "rms_px n/a" "fSpy stores no residual"
expect_stdout "cx 399.500 cy 299.500" "centred principal point"
grep -q '"path": "photo.png"' new.json || fail "the new project does not name the extracted photo"

head -c 40 scene.fspy >truncated.fspy
run calibrate fspy new.json truncated.fspy
expect_rc 2 "truncated file"
expect_stderr "truncated" "truncated file"
echo PASS

# Every kind of bad input ends with exit code 2 and a message naming the file and the field;
# none crashes.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs

# expect_bad DESCRIPTION PROJECT TEXT...: render and info both fail with code 2, and stderr
# names every TEXT.
expect_bad() {
    local what=$1 project=$2
    shift 2
    for cmd in render info; do
        if [ "$cmd" = render ]; then
            run render "$project" -o out.exr --passes 1
        else
            run info "$project"
        fi
        expect_rc 2 "$what ($cmd)"
        expect_stderr "error: " "$what ($cmd)"
        for text in "$@"; do expect_stderr "$text" "$what ($cmd)"; done
    done
}

write_project missing.json "$BALL" "$FLOOR" nothing_here.exr
expect_bad "missing photo file" missing.json nothing_here.exr photo.path "not found"

printf 'this is not a PNG file, only some garbage bytes\n' >garbage.png
write_project corrupt.json "$BALL" "$FLOOR" garbage.png
expect_bad "corrupt PNG" corrupt.json garbage.png photo.path

head -c 200 photo.exr >truncated.exr
write_project truncated.json "$BALL" "$FLOOR" truncated.exr
expect_bad "truncated EXR" truncated.json truncated.exr photo.path

: >empty.png
write_project empty.json "$BALL" "$FLOOR" empty.png
expect_bad "zero-size image file" empty.json empty.png photo.path

printf '{"schema_version": 1, "photo": {"path": "photo.exr"},,}\n' >invalid.json
expect_bad "invalid JSON" invalid.json invalid.json "invalid JSON"

write_project velvet.json "$(echo "$BALL" | sed 's/"diffuse"/"velvet"/')" "$FLOOR"
expect_bad "unknown material type" velvet.json velvet.json objects[0].material.type velvet

printf 'v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n' >collinear.obj
MESH='{"name": "line", "shape": {"type": "mesh", "path": "collinear.obj"}}'
write_project degenerate.json "$MESH" "$FLOOR"
expect_bad "degenerate mesh" degenerate.json collinear.obj objects[0].shape.path

write_project nomesh.json '{"shape": {"type": "mesh", "path": "gone.obj"}}' "$FLOOR"
expect_bad "missing mesh file" nomesh.json gone.obj objects[0].shape.path

# The camera (eye at (0, 1.5, 4)) inside a real box.
ROOM='{"name": "closet", "shape": {"type": "box", "size": [2, 2, 2]},
       "transform": {"translation": [0, 1.5, 4]}}'
write_project inside.json "$BALL" "$FLOOR, $ROOM"
expect_bad "camera inside geometry" inside.json inside.json camera.eye \
    "the camera is inside real geometry 'closet'"
# A box in front of the camera is fine.
WALL='{"name": "wall", "shape": {"type": "box", "size": [6, 3, 0.1]},
       "transform": {"translation": [0, 1.5, -2]}}'
write_project outside.json "$BALL" "$FLOOR, $WALL"
run info outside.json
expect_rc 0 "camera outside a box"

run render no_such_project.json -o out.exr
expect_rc 2 "missing project file"
expect_stderr "no_such_project.json" "missing project file"

run convert truncated.exr out.png
expect_rc 2 "convert of a truncated EXR"
expect_stderr "truncated.exr" "convert of a truncated EXR"
run compare photo.exr garbage.png
expect_rc 2 "compare with a corrupt PNG"
run make-test-image small.exr --size 8 8
run compare photo.exr small.exr
expect_rc 2 "compare of different sizes"
expect_stderr "small.exr" "compare of different sizes"
echo "PASS"

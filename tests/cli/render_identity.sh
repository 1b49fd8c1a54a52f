# Without (visible) virtual objects the output is the photo, bit for bit.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs

write_project none.json "" "$FLOOR"
run render none.json -o none.exr --passes 2
expect_rc 0 "render without objects"
compare photo.exr none.exr
is_zero "$MAX_DIFF" || fail "no objects: output differs from the photo (max_diff $MAX_DIFF)"

HIDDEN='{"name": "off", "shape": {"type": "sphere", "radius": 0.5},
         "transform": {"translation": [0, 0.5, 0]}, "visible": false}'
write_project hidden.json "$HIDDEN" "$FLOOR"
run render hidden.json -o hidden.exr --passes 2
expect_rc 0 "render with a hidden object"
compare photo.exr hidden.exr
is_zero "$MAX_DIFF" || fail "hidden object: output differs from the photo (max_diff $MAX_DIFF)"

# A PNG photo: the EXR output holds its linear decoding, unchanged.
run make-test-image photo.png --size 64 48 --value 0.2 0.4 0.6
expect_rc 0 "make-test-image png"
write_project png.json "" "$FLOOR" photo.png
run render png.json -o png.exr --passes 1
expect_rc 0 "render with a PNG photo"
compare photo.png png.exr
is_zero "$MAX_DIFF" || fail "PNG photo: output differs from the photo (max_diff $MAX_DIFF)"
echo "PASS"

# render --match-plate: the photo's grain and softness measured and said; an EXR keeps the render
# as its main layer with the matched image and the grain beside it, a PNG is the matched image;
# the project's display.match_plate switches it on; a bad value is refused naming the option.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
# A grainy photo with edges (a checkerboard), so its grain and softness can be measured.
run make-test-image photo.exr --size 160 120 --checker 5 --value 0.5 0.5 0.5 --value2 0.2 0.2 0.2 --noise 0.02
expect_rc 0 "checker photo"
write_project scene.json "$BALL" "$FLOOR"

run render scene.json -o off.exr --passes 2 --photons 20000 --match-plate off
expect_rc 0 "render without plate match"
grep -q "^plate:" stderr.txt && fail "--match-plate off measured the plate"
run render scene.json -o on.exr --passes 2 --photons 20000 --match-plate on
expect_rc 0 "render --match-plate on"
expect_stderr "plate: grain " "the measured grain and softness"
expect_stderr "softness " "the measured softness"

compare on.exr off.exr
is_zero "$MAX_DIFF" || fail "--match-plate changed the main layer (max_diff $MAX_DIFF)"
compare on.exr off.exr --layer-a matched
is_positive "$MAX_DIFF" || fail "the matched layer equals the render (nothing blurred)"
compare on.exr on.exr --layer grain
is_zero "$MAX_DIFF" || fail "no grain layer"

# A PNG is the matched image: it differs from the plain PNG.
run render scene.json -o on.png --passes 2 --photons 20000 --match-plate on
expect_rc 0 "matched PNG"
run render scene.json -o off.png --passes 2 --photons 20000
expect_rc 0 "plain PNG"
compare on.png off.png
is_positive "$MAX_DIFF" || fail "the matched PNG equals the plain one"
# The project's switch does the same.
sed 's|"display": {|"display": {"match_plate": true, |' scene.json > matched.json
grep -q '"match_plate": true' matched.json || sed 's|"render":|"display": {"match_plate": true},\n  "render":|' scene.json > matched.json
run render matched.json -o proj.png --passes 2 --photons 20000
expect_rc 0 "display.match_plate"
expect_stderr "plate: grain " "display.match_plate measures the plate"
compare proj.png on.png
is_zero "$MAX_DIFF" || fail "display.match_plate differs from --match-plate on ($MAX_DIFF)"

expect_refused "bad value" "--match-plate" render scene.json -o x.png --match-plate maybe
sed 's|"match_plate": true|"match_plate": 1|' matched.json > bad.json
expect_refused "a number for the switch" "field 'display.match_plate'" render bad.json -o x.png --passes 1

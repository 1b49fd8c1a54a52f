# `calibrate holdout`: a board in the photo cut out by GrabCut from a loose rectangle, its depth
# from the floor under a pixel; a mask covering the whole frame leaves the photo exactly as it
# was; bad options are refused naming them.
source "$(dirname "$0")/testlib.bash" "$@"

# A grey floor with a red board over [50, 80) x [30, 66), seen from 5 m straight above.
run make-test-image photo.png --size 128 96 --value 0.3 0.3 0.3 --value2 0.5 0.06 0.04 --box 50 30 80 66
expect_rc 0 "photo"
run make-test-image sun.exr --size 256 128 --probe-sun --sun-irradiance 3 --value 0.3 0.35 0.4 --sun-dir 1 2 0
expect_rc 0 "probe"
FX=64 CX=63.5 CY=47.5
write_topdown scene.json photo.png sun.exr "$FLOOR18" 0 1
# A ball on the floor under the board, and a render of it as the photo shows it without a holdout.
sed 's|"real": \[|"objects": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.5}, "transform": {"translation": [0, 0.5, 0]}, "material": {"type": "diffuse", "albedo": [0.1, 0.2, 0.8]}}],\n  "real": [|' scene.json > ball.json
run render ball.json --passes 1 --photons 20000 -o plain.exr
expect_rc 0 "render without a holdout"
compare plain.exr photo.png
is_positive "$MAX_DIFF" || fail "the ball changed nothing ($MAX_DIFF)"

run calibrate holdout ball.json --rect 46 26 84 70 --depth-at 10 10 --name board
expect_rc 0 "cut"
expect_stdout "added holdout 'board': " "cut summary"
N=$(sed -n "s/^added holdout 'board': \([0-9]*\) pixels.*/\1/p" stdout.txt)
awk -v n="$N" 'BEGIN { exit !(n > 1000 && n < 1160) }' || fail "cut $N pixels, the board has 1080"
grep -q "depth 5 m" stdout.txt || fail "depth under pixel (10, 10): expected 5 m"
M=$(sed -n 's/.*mask \(ball.holdouts\/board-[0-9a-f]*\.png\)$/\1/p' stdout.txt)
[ -f "$M" ] || fail "mask '$M' not written beside the project"
grep -q '"holdouts"' ball.json || fail "holdout not written to the project"

# A white mask over the whole frame, 2 m off (the floor is 5 m): the photo stands, exactly.
run make-test-image white.png --size 64 48 --value 1 1 1
expect_rc 0 "white mask"
run calibrate holdout ball.json --mask white.png --depth 2 --name board -o all.json
expect_rc 0 "mask"
expect_stdout "replaced holdout 'board': 12288 pixels (100.0% of the photo), depth 2 m, mask white.png" "mask summary"
run render all.json --passes 1 --photons 20000 -o held.exr
expect_rc 0 "render held out"
compare held.exr photo.png
is_zero "$MAX_DIFF" || fail "a frame held out in front of everything still changed ($MAX_DIFF)"
# Farther than the ball (6 m), the ball shows again.
run calibrate holdout ball.json --mask white.png --depth 6 --name board -o far.json
expect_rc 0 "far mask"
run render far.json --passes 1 --photons 20000 -o far.exr
compare far.exr photo.png
is_positive "$MAX_DIFF" || fail "a ball nearer than the occluder was hidden"

expect_refused "neither rect nor mask" "--rect" calibrate holdout ball.json --depth 2 -o x.json
expect_refused "no depth" "--depth" calibrate holdout ball.json --mask white.png -o x.json
expect_refused "strokes without a cut" "--occluder" calibrate holdout ball.json --mask white.png --depth 2 --occluder 1 2 -o x.json
expect_refused "missing mask" "--mask" calibrate holdout ball.json --mask nothere.png --depth 2 -o x.json
expect_refused "nothing under the pixel" "--depth-at" calibrate holdout ball.json --mask white.png --depth-at -100 -100 -o x.json
expect_refused "rect over everything" "--rect" calibrate holdout ball.json --rect -10 -10 500 500 --depth 2 -o x.json
sed 's/"depth": 2/"depth": -1/' all.json > neg.json
expect_refused "negative depth" "field 'holdouts[0].depth'" render neg.json --passes 1 -o n.exr

# `calibrate chessboard` on OpenCV's real chessboard photos (opencv-doc): the lens from 13
# photos, the pose from one, the project's other contents kept, a missing board rejected.
source "$(dirname "$0")/testlib.bash" "$@"
DATA=/usr/share/doc/opencv-doc/examples/data
[ -f $DATA/left01.jpg ] || fail "OpenCV's sample photos are missing: run scripts/install-deps.sh"
PHOTOS=$(ls $DATA/left0[1-9].jpg $DATA/left1[0-4].jpg)

# A new project from the photos.
run calibrate chessboard new.json $PHOTOS --board 9x6 --square 0.025
expect_rc 0 "calibrate 13 photos"
RMS=$(field rms_px)
at_most "$RMS" 0.5 || fail "RMS reprojection error $RMS px over 0.5 px"
grep -q '"model": "opencv"' new.json || fail "no OpenCV camera written"
grep -q 'left01.jpg' new.json || fail "the new project does not name the first photo"
expect_stdout "photo $DATA/left05.jpg: rms_px" "every photo's pose printed"
grep -qE '^uncertainty: fx [0-9.]+ ± 0\.[0-9]+ px' stdout.txt || fail "no lens uncertainty"

# A project whose photo is in the set keeps that photo's pose; --poses writes all of them.
run calibrate chessboard pick.json $DATA/left05.jpg --board 9x6 --square 0.025 --focal 533
expect_rc 0 "a project of left05"
run calibrate chessboard pick.json $PHOTOS --board 9x6 --square 0.025 --poses poses.json
expect_rc 0 "the set with --poses"
expect_stdout "13 photos (pose of left05.jpg)" "the project's own photo's pose"
expect_stdout "wrote every photo's pose to poses.json" "--poses"
[ "$(grep -c '"photo":' poses.json)" -eq 13 ] || fail "poses.json does not list the 13 photos"
P5=$(awk '$2 == "'$DATA'/left05.jpg:" { print $6, $7, $8 }' stdout.txt)
P=$(awk '/^position:/ { print $2, $3, $4 }' stdout.txt)
[ "$P5" = "$P" ] || fail "the project's camera is at $P, left05's pose at $P5"
run calibrate chessboard one.json $DATA/left05.jpg --square 0.025 --focal 533 --poses p.json
expect_rc 2 "--poses with one photo"
expect_stderr "writes the poses of several photos" "--poses with one photo"

# An existing project: the camera changes, the objects stay; its 64x48 photo has the samples'
# 4:3 aspect, so the intrinsics are scaled to it.
make_inputs
write_project scene.json "$BALL" "$FLOOR"
run calibrate chessboard scene.json $DATA/left02.jpg --board 9x6 --square 0.025 --focal 533
expect_rc 0 "pose from one photo"
expect_stdout "intrinsics scaled to the project's 64x48 photo" "scaling to the project's photo"
run info scene.json
expect_rc 0 "the updated project loads"
expect_stdout "camera: opencv" "the camera was replaced"
expect_stdout "'ball'" "the objects were kept"
expect_stdout "fx 53.3" "fx scaled from 533 px at 640 wide to 64 wide"

# A photo without the board.
run calibrate chessboard scene.json $DATA/HappyFish.jpg --square 0.025
expect_rc 2 "no board"
expect_stderr "no chessboard with 9x6 inner corners found" "no board"
echo PASS

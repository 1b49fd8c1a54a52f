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

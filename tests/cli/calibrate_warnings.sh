# Well-formed but wrong input to `calibrate`: a warning naming the problem and exit code 0
# where the camera is still usable, exit code 2 (and the project untouched) where it is not.
# Image points of a known camera: 1000x750, f = 800 px, at (1.5, 1.6, 2.5) looking at
# (0.3, 0, -0.2), as in calibrate_points.sh.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
run make-test-image photo1000.png --size 1000 750 --value 0.5 0.5 0.5
write_project scene.json "$BALL" "$FLOOR" photo1000.png

# expect_refused WHAT TEXT -- ARGS...: exit code 2, TEXT on stderr, the project unchanged.
expect_refused() {
    local what=$1 text=$2
    shift 3
    cp scene.json scene.before.json
    run calibrate "$@"
    expect_rc 2 "$what"
    expect_stderr "$text" "$what"
    cmp -s scene.json scene.before.json || fail "$what: the project was changed"
}
# expect_warned WHAT TEXT -- ARGS...: exit code 0 and "warning: ...TEXT" on stderr.
expect_warned() {
    local what=$1 text=$2
    shift 3
    run calibrate "$@"
    expect_rc 0 "$what"
    grep -q "^warning: .*$text" stderr.txt || fail "$what: no warning with '$text'"
}

RECT="--size 1000x750 --corners 413.518,381.519 549.410,412.026 508.295,466.634 360.722,428.922"
expect_refused "a rectangle of another aspect" "the corners fit a rectangle of aspect 1.50" -- \
    rectangle scene.json $RECT --focal 800 --width 0.6 --height 0.6
expect_refused "width and height swapped" "width and height swapped?" -- \
    rectangle scene.json $RECT --focal 800 --width 0.4 --height 0.6
expect_refused "a corner 121 px off" "a corner is misplaced" -- \
    rectangle scene.json --size 1000x750 --focal 800 --width 0.6 --height 0.4 \
    --corners 413.518,381.519 549.410,412.026 629.295,466.634 360.722,428.922
expect_warned "the focal length from a 60 px rectangle" "the focal length is uncertain" -- \
    rectangle scene.json --size 1000x750 --width 0.3 --height 0.2 \
    --corners 413.518,381.519 479.189,396.261 456.729,420.325 388.469,404.009

LINES="--x 313.041,358.962,650.975,434.827 --x 253.016,401.398,620.047,495.192
    --z 475.916,325.495,345.697,442.412 --z 597.218,348.529,496.481,482.324
    --y 446.174,375.654,443.965,314.488 --y 582.363,405.326,586.041,341.114"
# shellcheck disable=SC2086
expect_warned "a vertical length given as a distance" "give them as a vertical length" -- \
    vanishing scene.json --size 1000x750 $LINES --origin 413.518,381.519 \
    --distance 582.363,405.326,586.041,341.114,0.28
HEIGHT=$(awk '/^position:/ { print $3 }' stdout.txt)
at_most "$HEIGHT" 1.0 || fail "a vertical taken as a distance gives a wrong height, not $HEIGHT"
# shellcheck disable=SC2086
expect_refused "a line in the wrong group" "wrong group" -- \
    vanishing scene.json --size 1000x750 $LINES --x 475.916,325.495,345.697,442.412 \
    --origin 413.518,381.519 --camera-height 1.6

# Lines parallel in the image are an observation: with the focal length given they suffice.
run calibrate vanishing scene.json --size 1000x750 --focal 800 \
    --x 100,300,600,300 --x 100,400,600,400 \
    --z 475.916,325.495,345.697,442.412 --z 597.218,348.529,496.481,482.324 \
    --origin 413.518,381.519 --camera-height 1.5
expect_rc 0 "parallel lines with a focal length"

# The same photo twice in a chessboard set: left out of the lens fit, every pose written.
DATA=/usr/share/doc/opencv-doc/examples/data
[ -f $DATA/left01.jpg ] || fail "OpenCV's sample photos are missing: run scripts/install-deps.sh"
PHOTOS=$(ls $DATA/left0[1-9].jpg $DATA/left1[0-4].jpg)
expect_warned "a duplicate photo" "duplicate photos: $DATA/left03.jpg" -- \
    chessboard board.json $PHOTOS $DATA/left03.jpg --square 0.025 --poses poses.json
expect_stdout "left03.jpg: rms_px" "the duplicate's pose"
expect_stdout "(duplicate, not in the lens fit)" "the duplicate marked"
[ "$(grep -c '"photo":' poses.json)" -eq 14 ] || fail "poses.json does not list all 14 photos"
echo PASS

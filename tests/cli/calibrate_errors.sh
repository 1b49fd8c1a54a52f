# Bad input to `calibrate` ends with exit code 2 and a message that says what is wrong.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"
cp scene.json scene.orig.json

# expect_bad WHAT TEXT -- ARGS...: `calibrate ARGS` fails with code 2 and TEXT on stderr, and
# the project is unchanged.
expect_bad() {
    local what=$1 text=$2
    shift 3
    run calibrate "$@"
    expect_rc 2 "$what"
    expect_stderr "error: " "$what"
    expect_stderr "$text" "$what"
    cmp -s scene.json scene.orig.json || fail "$what: the project was changed"
}

RECT="--width 0.6 --height 0.4 --size 64x48"
expect_bad "fewer than four points" "need at least 4 rectangle corners, got 3" -- \
    rectangle scene.json $RECT --focal 50 --corners 10,10 50,12 48,40
expect_bad "collinear points" "collinear" -- \
    rectangle scene.json $RECT --focal 50 --corners 10,10 20,20 30,30 40,40
expect_bad "three collinear corners" "three of the rectangle corners are collinear" -- \
    rectangle scene.json $RECT --focal 50 --corners 10,10 30,10 50,10 30,40
expect_bad "a focal length of 0" "the focal length must be > 0" -- \
    rectangle scene.json $RECT --focal 0 --corners 10,10 50,12 48,40 12,38
expect_bad "points: fewer than four" "need at least 4 points, got 2" -- \
    points scene.json --size 64x48 --focal 50 --point 0,0,0,10,10 --point 1,0,0,20,10
expect_bad "parallel vanishing lines" "parallel in the image" -- \
    vanishing scene.json --size 64x48 --x 0,10,60,10 --x 0,20,60,20 \
    --z 20,40,25,10 --z 40,40,35,10 --origin 30,40 --camera-height 1.5
expect_bad "directions that cannot be orthogonal" "cannot be orthogonal" -- \
    vanishing scene.json --size 64x48 --x 0,30,20,34 --x 0,40,20,42 \
    --z 40,30,60,34 --z 40,40,60,42 --origin 30,40 --camera-height 1.5
expect_bad "a point that is not a point" "'1,x' is not a list of numbers" -- \
    rectangle scene.json $RECT --focal 50 --corners 1,x 50,12 48,40 12,38

# EXIF where EXIF is required.
run make-test-image plain.jpg --size 64 48 --value 0.5 0.5 0.5
expect_rc 0 "make a JPEG"
run make-test-image plain.png --size 64 48 --value 0.5 0.5 0.5
expect_rc 0 "make a PNG"
expect_bad "a photo without EXIF" "plain.png: the file has no EXIF data" -- exif scene.json plain.png
# Our JPEGs carry EXIF (the software that wrote them), but no lens.
expect_bad "a photo without a focal length" "has no focal length" -- exif scene.json plain.jpg
printf 'not an image\n' >garbage.jpg
expect_bad "an unreadable photo" "garbage.jpg: cannot read the file's metadata" -- \
    exif scene.json garbage.jpg
expect_bad "--exif with a photo without EXIF" "no EXIF data" -- \
    rectangle scene.json $RECT --photo plain.png --exif --corners 10,10 50,12 48,40 12,38
expect_bad "a missing photo" "nothing.jpg: file not found" -- exif scene.json nothing.jpg

# Chessboard and fSpy input.
expect_bad "no board in the photo" "no chessboard with 9x6 inner corners found" -- \
    chessboard scene.json plain.jpg --square 0.03
expect_bad "a square size of 0" "the square size must be > 0" -- \
    chessboard scene.json plain.jpg --square 0
expect_bad "not an fSpy file" "not an fSpy project file" -- fspy scene.json garbage.jpg
echo PASS

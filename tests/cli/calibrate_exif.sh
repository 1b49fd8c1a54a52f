# `calibrate exif`: a JPEG with a hand-written EXIF block (focal length 4.25 mm, 26 mm in 35 mm
# terms) sets fx = fy = 26 * (image diagonal) / 43.27 mm and keeps the project's pose.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"
run make-test-image plain.jpg --size 64 48 --value 0.5 0.5 0.5
expect_rc 0 "make a JPEG"

# APP1 "Exif": little-endian TIFF header, IFD0 pointing to the Exif IFD, which holds
# FocalLength (0x920a, rational 425/100) and FocalLengthIn35mmFilm (0xa405, short 26).
{
    printf '\xff\xd8'                                  # SOI
    printf '\xff\xe1\x00\x48Exif\x00\x00'              # APP1, 72 bytes
    printf 'II\x2a\x00\x08\x00\x00\x00'                # TIFF header, IFD0 at 8
    printf '\x01\x00'                                  # IFD0: one entry
    printf '\x69\x87\x04\x00\x01\x00\x00\x00\x1a\x00\x00\x00'  # Exif IFD at 26
    printf '\x00\x00\x00\x00'                          # no next IFD
    printf '\x02\x00'                                  # Exif IFD: two entries
    printf '\x0a\x92\x05\x00\x01\x00\x00\x00\x38\x00\x00\x00'  # FocalLength at 56
    printf '\x05\xa4\x03\x00\x01\x00\x00\x00\x1a\x00\x00\x00'  # FocalLengthIn35mmFilm 26
    printf '\x00\x00\x00\x00'                          # no next IFD
    printf '\xa9\x01\x00\x00\x64\x00\x00\x00'          # 425/100
    tail -c +3 plain.jpg                               # the rest of the JPEG after its SOI
} >exif.jpg

run calibrate exif scene.json exif.jpg
expect_rc 0 "focal length from EXIF"
# 26 mm * 80 px / 43.2666 mm = 48.074 px for the 64x48 image.
expect_stdout "fx 48.074 fy 48.074 cx 31.500 cy 23.500" "focal length in pixels"
expect_stdout "35 mm equivalent focal length 26" "how it was derived"
expect_stdout "position: 0.0000 1.5000 4.0000" "the look-at camera's position is kept"
run info scene.json
expect_rc 0 "the project loads"
expect_stdout "camera: opencv" "the camera is now an OpenCV camera"
echo PASS

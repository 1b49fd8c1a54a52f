# `calibrate exif`, `calibrate rectangle --exif` and `--focal-mm` on a phone's portrait photo:
# the JPEG is stored landscape (64x48) with EXIF orientation 6 or 8, loads upright (48x64), and
# keeps the landscape's focal length in pixels, 26 mm * 80 px / 43.27 mm = 48.074 px.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs  # probe.exr, which the new projects name
run make-test-image plain.jpg --size 64 48 --value 0.5 0.5 0.5
expect_rc 0 "make a JPEG"

# exif_jpeg ORIENTATION: APP1 "Exif" with a little-endian TIFF block: IFD0 holds Orientation
# (0x0112, short) and the Exif IFD's offset (38), which holds FocalLength (0x920a, rational
# 425/100 at 68) and FocalLengthIn35mmFilm (0xa405, short 26).
exif_jpeg() {
    printf '\xff\xd8'                                  # SOI
    printf '\xff\xe1\x00\x54Exif\x00\x00'              # APP1, 84 bytes
    printf 'II\x2a\x00\x08\x00\x00\x00'                # TIFF header, IFD0 at 8
    printf '\x02\x00'                                  # IFD0: two entries
    printf "\\x12\\x01\\x03\\x00\\x01\\x00\\x00\\x00\\x0$1\\x00\\x00\\x00"  # Orientation
    printf '\x69\x87\x04\x00\x01\x00\x00\x00\x26\x00\x00\x00'  # Exif IFD at 38
    printf '\x00\x00\x00\x00'                          # no next IFD
    printf '\x02\x00'                                  # Exif IFD: two entries
    printf '\x0a\x92\x05\x00\x01\x00\x00\x00\x44\x00\x00\x00'  # FocalLength at 68
    printf '\x05\xa4\x03\x00\x01\x00\x00\x00\x1a\x00\x00\x00'  # FocalLengthIn35mmFilm 26
    printf '\x00\x00\x00\x00'                          # no next IFD
    printf '\xa9\x01\x00\x00\x64\x00\x00\x00'          # 425/100
    tail -c +3 plain.jpg                               # the rest of the JPEG after its SOI
}

for o in 6 8; do
    exif_jpeg $o >portrait$o.jpg
    run calibrate exif new$o.json portrait$o.jpg
    expect_rc 0 "orientation $o: focal length from EXIF"
    expect_stdout "image: 48x64" "orientation $o: the photo's upright size"
    expect_stdout "fx 48.074 fy 48.074 cx 23.500 cy 31.500" "orientation $o: the landscape's focal length"
    expect_stdout "EXIF orientation $o" "orientation $o: says it turned the photo"
    # Again, on the project it made: its photo is the same picture, the same way up.
    run calibrate exif new$o.json portrait$o.jpg
    expect_rc 0 "orientation $o: on a project whose photo it is"
    grep -qF "scaled" stdout.txt && fail "orientation $o: the camera was scaled to its own photo"
    run info new$o.json
    expect_rc 0 "orientation $o: the project loads"

    # A rectangle on the ground of the upright photo, the focal length from EXIF.
    run calibrate rectangle new$o.json --photo portrait$o.jpg --exif --width 0.6 --height 0.4 \
        --corners 10,40 38,40 34,28 14,28
    expect_rc 0 "orientation $o: rectangle with --exif"
    expect_stdout "-> 48.07 px" "orientation $o: --exif reads the landscape's focal length"
    expect_stdout "fx 48.074 fy 48.074 cx 23.500 cy 31.500" "orientation $o: rectangle intrinsics"
    # Millimetres on a sensor 8 mm across its rows, which run down the upright photo: 6 mm is
    # 6 * 64 / 8 = 48 px, as for the landscape.
    run calibrate rectangle new$o.json --photo portrait$o.jpg --focal-mm 6 --sensor-width 8 \
        --width 0.6 --height 0.4 --corners 10,40 38,40 34,28 14,28
    expect_rc 0 "orientation $o: rectangle with --focal-mm"
    expect_stdout "fx 48.000 fy 48.000" "orientation $o: --sensor-width across the sensor's rows"
done
echo PASS

# `calibrate probe`: intensity by hand and from a grey card, rotation from a shadow cue, the
# mirror ball's field of view; bad requests exit with code 2.
source "$(dirname "$0")/testlib.bash" "$@"

# --- Shadow cue: a 1 m pole at the origin under the sun of the probe (direction 0.3 0.9 0.3).
run make-test-image big.exr --size 640 480 --value 0.5 0.5 0.5
expect_rc 0 "photo"
run make-test-image sun.exr --size 512 256 --probe-sun --sun-dir 0.3 0.9 0.3 --value 0.05 0.05 0.05
expect_rc 0 "probe"
FX=320 CX=319.5 CY=239.5
write_topdown pole.json big.exr sun.exr "$FLOOR18" 40 1
# Shadow tip = top - sun / sun.y = (-1/3, 0, -1/3); its pixel is (fx (-1/3) / 5 + cx, ...).
TIP=$(awk -v f=$FX -v cx=$CX -v cy=$CY 'BEGIN { printf "%.2f %.2f", cx - f / 15, cy - f / 15 }')
run calibrate probe pole.json --shadow $CX $CY $TIP --object-height 1 --object-base
expect_rc 0 "shadow cue"
expect_stdout "probe rotation_deg (0, 40, 0) -> " "shadow summary"
# The probe was turned 40 degrees off; the cue turns it back to about 0 (the probe's sun is the
# centre of one pixel of 0.7 degrees, so a little off the exact direction).
YAW=$(sed -n 's/^probe rotation_deg .* -> ([^,]*, \([^,]*\), .*/\1/p' stdout.txt)
[ -n "$YAW" ] || fail "no new rotation printed"
awk -v y="$YAW" 'BEGIN { exit !(y < 2 && y > -2) }' || fail "probe yaw $YAW after the cue, expected about 0"
MISMATCH=$(field elevation_mismatch_deg)
awk -v m="$MISMATCH" 'BEGIN { exit !(m < 2 && m > -2) }' || fail "elevation mismatch $MISMATCH"

run calibrate probe pole.json --shadow $CX $CY $TIP
expect_rc 2 "shadow without a height"
expect_stderr "--object-height" "missing height message"

# --- Grey card: the photo was lit by the probe at 2x; the project says 1.
run make-test-image small.exr --size 64 48 --value 0.5 0.5 0.5
FX=32 CX=31.5 CY=23.5
write_topdown truth.json small.exr sun.exr "$FLOOR18" 0 2
run reference truth.json --real-only -o lit.exr --spp 64
expect_rc 0 "synthetic photo"
write_topdown card.json lit.exr sun.exr "$FLOOR18" 0 1
run calibrate probe card.json --grey-card 20 16 43 31 --reflectance 0.18
expect_rc 0 "grey card"
expect_stdout "probe intensity 1 -> " "grey card summary"
K=$(sed -n 's/^probe intensity 1 -> \([^ ]*\) .*/\1/p' stdout.txt)
awk -v k="$K" 'BEGIN { exit !(k > 1.94 && k < 2.06) }' || fail "grey card gave intensity $K, expected 2 within 3%"
grep -q '"intensity": 2' card.json || grep -q "\"intensity\": $K" card.json || fail "intensity not written"

run calibrate probe card.json --grey-card 20 16 200 31
expect_rc 2 "card outside the photo"
expect_stderr "not inside the photo" "card outside message"

# --- By hand, and the mirror ball's field of view.
run calibrate probe card.json --intensity 3.5 -o hand.json
expect_rc 0 "intensity by hand"
run info hand.json
expect_stdout "intensity 3.5" "info shows the new intensity"
run calibrate probe card.json --fov 30
expect_rc 2 "field of view of a lat-long probe"
expect_stderr "not a mirror ball" "fov message"
sed 's/"format": "latlong"/"format": "mirrorball"/' card.json >ball.json
run calibrate probe ball.json --fov 30
expect_rc 0 "field of view"
grep -q '"mirror_ball_fov_deg": 30' ball.json || fail "field of view not written"
run calibrate probe ball.json --fov 200
expect_rc 2 "field of view out of range"
run calibrate probe ball.json
expect_rc 2 "nothing to do"
expect_stderr "nothing to do" "nothing to do message"
run calibrate probe ball.json --intensity 2 --grey-card 1 1 2 2
expect_rc 2 "intensity and grey card together"

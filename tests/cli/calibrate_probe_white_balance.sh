# `calibrate probe --grey-card ... --white-balance`: the probe's intensity and white balance from
# a grey card photographed under a probe of another white balance; --white-balance alone is
# refused.
source "$(dirname "$0")/testlib.bash" "$@"

run make-test-image small.exr --size 64 48 --value 0.5 0.5 0.5
expect_rc 0 "photo"
run make-test-image sun.exr --size 512 256 --probe-sun --sun-dir 0.3 0.9 0.3 --value 0.05 0.05 0.05
expect_rc 0 "probe"
FX=32 CX=31.5 CY=23.5

# The photo was lit by the probe at 2x with a warm white balance; the project says neutral, 1.
write_topdown truth.json small.exr sun.exr "$FLOOR18" 0 2 "[1.2, 1, 0.7]"
run reference truth.json --real-only -o lit.exr --spp 64
expect_rc 0 "synthetic photo"
write_topdown card.json lit.exr sun.exr "$FLOOR18" 0 1
run calibrate probe card.json --grey-card 20 16 43 31 --reflectance 0.18 --white-balance
expect_rc 0 "grey card with white balance"
expect_stdout "probe white_balance (1, 1, 1) -> (" "white balance summary"
expect_stdout "card chromaticity: photo (" "chromaticity summary"
# The gain 2 x (1.2, 1, 0.7) is intensity 2.0417 (its luminance) times (1.1755, 0.9796, 0.6857).
K=$(sed -n 's/^probe intensity 1 -> \([^ ]*\) .*/\1/p' stdout.txt)
awk -v k="$K" 'BEGIN { exit !(k > 1.98 && k < 2.10) }' || fail "intensity $K, expected 2.04 within 3%"
WB=$(sed -n 's/^probe white_balance (1, 1, 1) -> (\(.*\))$/\1/p' stdout.txt | tr -d ',')
[ -n "$WB" ] || fail "no white balance printed"
echo "$WB" | awk '{ exit !($1 > 1.140 && $1 < 1.211 && $2 > 0.950 && $2 < 1.009 &&
                           $3 > 0.665 && $3 < 0.706) }' ||
    fail "white balance ($WB), expected (1.1755 0.9796 0.6857) within 3%"
# Written into the project: `info` shows it.
run info card.json
expect_rc 0 "info"
expect_stdout ", white balance (" "info shows the white balance"

# Matched again, the card is the photo's colour already: the balance stays.
run calibrate probe card.json --grey-card 20 16 43 31 --white-balance -o again.json
expect_rc 0 "second match"
WB2=$(sed -n 's/^probe white_balance (\(.*\)) -> (\(.*\))$/\1 \2/p' stdout.txt | tr -d ',')
echo "$WB2" | awk '{ for (i = 1; i <= 3; ++i) if ($i - $(i + 3) > 1e-3 || $(i + 3) - $i > 1e-3) exit 1 }' ||
    fail "a second match changed the white balance: $WB2"

# Without --white-balance only the intensity is matched, the white balance left as it is.
run calibrate probe card.json --grey-card 20 16 43 31 -o exposure_only.json
expect_rc 0 "grey card alone"
grep -q "white_balance" stdout.txt && fail "the luminance match printed a white balance"
run info exposure_only.json
expect_stdout ", white balance (" "the luminance match keeps the white balance"

run calibrate probe card.json --white-balance
expect_rc 2 "white balance without a grey card"
expect_stderr "--grey-card" "white balance without a card message"

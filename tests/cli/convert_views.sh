# Outputs through view transforms, in 16 bits, half floats and with metadata; layers and colour
# spaces on the way in.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"
run render scene.json -o layered.exr --passes 2 --layers
expect_rc 0 "render with layers"
# The header says what made the file (EXR headers are not compressed).
grep -qa "diffphoton:passes" layered.exr || fail "no diffphoton:passes attribute in the EXR"
grep -qa "Software" layered.exr || fail "no Software attribute in the EXR"

run convert layered.exr standard.png
expect_rc 0 "convert through Standard"
if run convert layered.exr filmic.png --view Filmic && [ "$RC" -eq 0 ]; then
    cmp -s standard.png filmic.png && fail "Filmic wrote the same bytes as Standard"
else
    expect_stderr "Standard" "the config's views are listed when Filmic is missing"
fi
expect_refused "an unknown view" "Standard" convert layered.exr x.png --view Cinematic
expect_refused "an unknown look" "look" convert layered.exr x.png --look "Extra Punchy"

run convert layered.exr deep.tif --bits 16
expect_rc 0 "16-bit TIFF"
head -c 2 deep.tif | grep -q "II\|MM" || fail "deep.tif is not a TIFF"
run convert layered.exr shallow.tif --bits 8
expect_rc 0 "8-bit TIFF"
[ "$(stat -c %s deep.tif)" -gt "$(stat -c %s shallow.tif)" ] || fail "the 16-bit TIFF is not larger than the 8-bit one"
expect_refused "16 bits in a JPEG" "8 bits" convert layered.exr x.jpg --bits 16
expect_refused "--bits on an EXR render" "EXR" render scene.json -o x.exr --passes 1 --bits 16
expect_refused "--half on a PNG render" "EXR" render scene.json -o x.png --passes 1 --half

run render scene.json -o half.exr --passes 2 --half
expect_rc 0 "half-float render"
[ "$(stat -c %s half.exr)" -lt "$(stat -c %s layered.exr)" ] || fail "the half-float EXR is not smaller"

# A layer of a multilayer file is read by name; an unknown one is refused with the list.
run convert layered.exr dl.exr --layer dL
expect_rc 0 "convert --layer dL"
compare layered.exr dl.exr --layer-a dL
is_zero "$MAX_DIFF" || fail "the dL layer read by convert differs from the file's (max_diff $MAX_DIFF)"
expect_refused "an unknown layer" "catcher" convert layered.exr x.png --layer nope

# A colour space override: the same codes read as linear are darker than read as sRGB.
run convert standard.png as_linear.exr --colorspace linear
expect_rc 0 "convert --colorspace linear"
run convert standard.png as_srgb.exr
expect_rc 0 "convert (auto)"
compare as_linear.exr as_srgb.exr
is_positive "$MAX_DIFF" || fail "--colorspace linear changed nothing"
echo "PASS"

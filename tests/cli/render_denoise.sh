# render --denoise: the raw image stays the main layer, the denoised image and change are layers
# beside it, a PNG is the denoised image, and a missing library is a bad input that says how to
# get it (exit 2, before any pass).
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"

DP_OIDN_LIBRARY=/nonexistent/libOpenImageDenoise.so.2 expect_refused "--denoise without the library" \
    "run scripts/install-deps.sh, or set DP_OIDN_LIBRARY" render scene.json -o none.exr --denoise
[ -e none.exr ] && fail "a refused --denoise wrote an output"
expect_stderr "/nonexistent/libOpenImageDenoise.so.2" "--denoise without the library"

run render scene.json -o raw.exr --passes 2 --photons 20000 --layers
expect_rc 0 "render without --denoise"
run render scene.json -o out.exr --passes 2 --photons 20000 --layers --denoise
if [ "$RC" -eq 2 ] && grep -qF "Open Image Denoise is missing" stderr.txt; then
    echo "SKIP: $(cat stderr.txt)"  # only where scripts/install-deps.sh has not run
    exit 0
fi
expect_rc 0 "render --denoise"

compare out.exr raw.exr
is_zero "$MAX_DIFF" || fail "--denoise changed the raw main layer (max_diff $MAX_DIFF)"
compare out.exr raw.exr --layer dL
is_zero "$MAX_DIFF" || fail "--denoise changed the raw dL layer (max_diff $MAX_DIFF)"
compare out.exr raw.exr --layer-a denoised
is_positive "$MAX_DIFF" || fail "the denoised layer equals the raw image"
compare out.exr raw.exr --layer-a dL_denoised --layer dL
is_positive "$MAX_DIFF" || fail "the dL_denoised layer equals the raw dL"
# Denoising removes noise, not the objects: the denoised image is closer to the raw one than the
# raw one is to the photo.
compare out.exr photo.exr
CHANGE=$RMSE
compare out.exr raw.exr --layer-a denoised
awk -v a="$RMSE" -v b="$CHANGE" 'BEGIN { exit !(a < b) }' || fail "denoised vs raw $RMSE >= raw vs photo $CHANGE"

run render scene.json -o out.png --passes 1 --photons 20000 --denoise
expect_rc 0 "render --denoise to PNG"
[ -s out.png ] || fail "out.png missing"
echo "PASS"

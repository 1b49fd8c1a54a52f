# The reference path tracer (with and without the virtual objects) and EXR -> PNG conversion.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"

run reference scene.json -o synthetic.exr --spp 2 --real-only --seed 3 --threads 2
expect_rc 0 "reference --real-only"
[ -s synthetic.exr ] || fail "synthetic.exr missing"
expect_stdout "wrote synthetic.exr" "final line"
expect_stderr "rows 48/48" "row progress"
run reference scene.json -o with_ball.exr --spp 2 --seed 3
expect_rc 0 "reference with the ball"
compare synthetic.exr with_ball.exr
is_positive "$MAX_DIFF" || fail "the ball does not show in the reference"
# The image depends on the options only, not on the thread count.
run reference scene.json -o one_thread.exr --spp 2 --seed 3 --threads 1
expect_rc 0 "reference on one thread"
compare with_ball.exr one_thread.exr
is_zero "$MAX_DIFF" || fail "reference differs between thread counts (max_diff $MAX_DIFF)"

# A synthetic photograph made this way can be used as the photo of a differential render.
write_project synthetic.json "$BALL" "$FLOOR" synthetic.exr
run render synthetic.json -o augmented.exr --passes 2
expect_rc 0 "render over the synthetic photo"

run convert with_ball.exr with_ball.png --exposure 0.5
expect_rc 0 "convert"
[ -s with_ball.png ] || fail "with_ball.png missing"
run convert with_ball.exr with_ball.exr
expect_rc 2 "convert to EXR"
run convert missing.exr x.png
expect_rc 2 "convert of a missing file"
expect_stderr "missing.exr" "convert of a missing file"
run reference scene.json -o ref.exr --spp 0
expect_rc 2 "reference --spp 0"
echo "PASS"

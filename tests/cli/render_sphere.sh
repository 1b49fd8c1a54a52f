# A diffuse sphere over a real floor: renders, writes every layer, and changes the photo.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"

run render scene.json -o out.exr --layers --passes 3 --photons 20000
expect_rc 0 "render"
[ -s out.exr ] || fail "render: out.exr missing or empty"
expect_stdout "wrote out.exr" "final line"
expect_stdout "passes 3" "final line"
expect_stdout "skipped pixels" "final line"
# stderr is not a terminal here: one plain line per pass.
expect_stderr "pass 1/3  photons/s" "plain progress"
expect_stderr "pass 3/3" "plain progress"
grep -q $'\r' stderr.txt && fail "plain progress must not redraw with carriage returns"

compare photo.exr out.exr
is_positive "$MAX_DIFF" || fail "the sphere did not change the photo (max_diff $MAX_DIFF)"

# Layers: compared with those of an empty scene (all zero), which must exist too.
write_project empty.json "" "$FLOOR"
run render empty.json -o black.exr --layers --passes 1
expect_rc 0 "render of the empty scene"
compare out.exr black.exr --layer shadow
is_positive "$MAX_DIFF" || fail "shadow matte is empty"
at_most "$MAX_DIFF" 1 || fail "shadow matte exceeds 1: $MAX_DIFF"
compare out.exr black.exr --layer alpha
is_positive "$MAX_DIFF" || fail "alpha is empty although the ball is in view"
at_most "$MAX_DIFF" 1 || fail "alpha exceeds 1: $MAX_DIFF"
compare out.exr black.exr --layer dL
is_positive "$MAX_DIFF" || fail "dL is empty although the ball shadows the floor"
run compare out.exr photo.exr --layer dL
expect_rc 2 "compare of a layer the photo lacks"
expect_stderr "photo.exr" "missing layer message"

# Same seed, same image, whatever the thread count; another seed, another image.
run render scene.json -o again.exr --passes 3 --photons 20000 --threads 1
expect_rc 0 "render with one thread"
compare out.exr again.exr
is_zero "$MAX_DIFF" || fail "one thread vs all threads differ (max_diff $MAX_DIFF)"
run render scene.json -o seed2.exr --passes 3 --photons 20000 --seed 2
expect_rc 0 "render with seed 2"
compare out.exr seed2.exr
is_positive "$MAX_DIFF" || fail "another seed gave the identical image"

# 8-bit output with exposure.
run render scene.json -o out.png --passes 1 --exposure -1
expect_rc 0 "render to PNG"
[ -s out.png ] || fail "out.png missing"

# A time budget instead of passes.
run render scene.json -o timed.exr --time 0.3
expect_rc 0 "render --time"
grep -qE 'elapsed [0-9.]+s/0\.3s' stderr.txt || fail "time-budget progress shows no budget"

# One pixel of one pass, for debugging.
run render scene.json --pixel 32,30 --pass 2
expect_rc 0 "render --pixel"
for word in photo change dL alpha result; do expect_stdout "  $word " "--pixel output"; done
echo "PASS"

# NaN pixels in the photograph are replaced and reported, not fatal.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
run make-test-image nan.exr --size 64 48 --value 0.5 0.5 0.5 --nan 7
expect_rc 0 "make-test-image with NaN"
write_project nan.json "$BALL" "$FLOOR" nan.exr

run render nan.json -o out.exr --passes 2
expect_rc 0 "render with NaN pixels"
expect_stderr "warning: " "NaN warning"
grep -F "warning: " stderr.txt | grep -F "NaN" | grep -qF "7" ||
    fail "the warning should mention NaN and the count 7"
# Nothing non-finite reaches the output: convert would warn if it found any.
run convert out.exr out.png
expect_rc 0 "convert of the output"
grep -qF "NaN" stderr.txt && fail "the output still holds NaN/Inf values"

run info nan.json
expect_rc 0 "info with NaN pixels"
expect_stdout "NaN" "info lists the NaN warning"
echo "PASS"

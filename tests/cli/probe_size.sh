# A probe's shape and size on the command line: a non-2:1 lat-long is said, probe.max_width and
# --probe-max-width shrink a wide probe on load (said, with its new size), bad widths are refused.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"

# A 3:1 "lat-long" (a cropped panorama or a mirror ball given the wrong format).
run make-test-image probe.exr --size 96 32 --probe-sun --value 0.1 0.1 0.12
expect_rc 0 "make-test-image 3:1 probe"
run info scene.json
expect_rc 0 "info with a 3:1 probe"
expect_stdout "not 2:1" "info lists the non-2:1 warning"

# A 2:1 probe wider than the project's max_width is shrunk on load, its proportions kept.
run make-test-image probe.exr --size 256 128 --probe-sun --value 0.1 0.1 0.12
expect_rc 0 "make-test-image 256x128 probe"
sed 's/"probe": {"path": "probe.exr"}/"probe": {"path": "probe.exr", "max_width": 64}/' scene.json >narrow.json
grep -qF '"max_width": 64' narrow.json || fail "the test could not set probe.max_width"
run info narrow.json --json
expect_rc 0 "info with probe.max_width 64"
/usr/bin/python3 -c 'import json, sys; p = json.load(open("stdout.txt"))["probe"]; sys.exit(p["width"] != 64 or p["height"] != 32)' ||
    fail "info should describe the probe as 64x32"
expect_stdout "256x128 probe is reduced to 64x32" "info lists the reduction"

# The command line overrides the project for one render.
run render scene.json -o out.exr --passes 1 --photons 2000 --probe-max-width 128
expect_rc 0 "render with --probe-max-width"
expect_stderr "256x128 probe is reduced to 128x64" "render says the probe was reduced"
run render scene.json -o out.exr --passes 1 --photons 2000
expect_rc 0 "render without --probe-max-width"
grep -qF "reduced" stderr.txt && fail "a probe narrower than the automatic width is not reduced"

expect_refused "--probe-max-width below 64" "--probe-max-width" render scene.json -o out.exr --probe-max-width 32
sed 's/"probe": {"path": "probe.exr"}/"probe": {"path": "probe.exr", "max_width": 10}/' scene.json >bad.json
expect_refused "probe.max_width below 64" "probe.max_width" info bad.json
echo "PASS"

# `calibrate proxy`: the ground, a wall and a box from image points go into the project, which
# still loads; bad points end with exit code 2 and a message naming the project and the field.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "" ""

run calibrate proxy scene.json ground
expect_rc 0 "ground"
expect_stdout "added real proxy 'ground': plane" "ground summary"
expect_stdout "wrote scene.json" "ground writes the project"

# The look-at camera of write_project sees the ground below about row 14 of its 64x48 photo.
run calibrate proxy scene.json box --points 20 40 44 40 40 30 24 30 --height 0.5 --name crate
expect_rc 0 "box"
expect_stdout "added real proxy 'crate': box" "box summary"
RMS=$(field rms_error_px)
[ -n "$RMS" ] || fail "box: no rms_error_px figure"
at_most "$RMS" 5 || fail "box: rms_error_px $RMS for a nearly rectangular footprint"

run calibrate proxy scene.json wall --points 5 30 60 30 --height 2 -o walled.json
expect_rc 0 "wall"
expect_stdout "wrote walled.json" "wall writes to --output"

run info walled.json
expect_rc 0 "info on the updated project"
expect_stdout "'ground'" "info lists the ground"
expect_stdout "'crate'" "info lists the box"
expect_stdout "'wall'" "info lists the wall"

# The same name replaces the proxy instead of adding one.
run calibrate proxy scene.json box --points 20 44 44 44 40 34 --height 0.3 --name crate
expect_rc 0 "box replaced"
expect_stdout "replaced real proxy 'crate'" "replacing summary"
[ "$(grep -c '"name": "crate"' scene.json)" -eq 1 ] || fail "the box was added twice"

expect_bad() {  # expect_bad DESCRIPTION TEXT ARGS...
    local what=$1 text=$2
    shift 2
    run calibrate proxy "$@"
    expect_rc 2 "$what"
    expect_stderr "error: " "$what"
    expect_stderr "$text" "$what"
}
expect_bad "point above the horizon" "above the horizon" scene.json box --points 20 2 44 40 40 30 --height 1
expect_bad "two points for a box" "3 or 4" scene.json box --points 20 40 44 40 --height 1
expect_bad "collinear footprint" "collinear" scene.json box --points 10 40 30 40 50 40 --height 1
expect_bad "crossing footprint" "in order" scene.json box --points 20 40 40 30 44 40 24 30 --height 1
expect_bad "no height" "height" scene.json box --points 20 40 44 40 40 30
expect_bad "one point for a wall" "two image points" scene.json wall --points 20 40 --height 1
expect_bad "unknown kind" "kind" scene.json tower
expect_bad "missing project" "nothing.json" nothing.json ground
grep -q "scene.json" stderr.txt || true
run calibrate proxy scene.json box --points 20 2 44 40 40 30 --height 1
expect_stderr "scene.json" "the message names the project"
expect_stderr "points[0]" "the message names the point"

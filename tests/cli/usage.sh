# Command-line mistakes: exit code 2 with a message, never a crash; help exits 0.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
write_project scene.json "$BALL" "$FLOOR"

run --help
expect_rc 0 "--help"
expect_stdout "render" "--help lists render"
grep -qF "make-test-image" stdout.txt && fail "--help shows the hidden test command"
run render --help
expect_rc 0 "render --help"
expect_stdout "--passes" "render --help"

bad() {  # bad DESCRIPTION ARGS...: exit 2 and an "error:" line
    local what=$1
    shift
    run "$@"
    expect_rc 2 "$what"
    expect_stderr "error: " "$what"
}
bad "no subcommand"
bad "unknown subcommand" paint scene.json
expect_stderr "unknown command 'paint'" "the unknown command named"
bad "a mistyped subcommand" rendr scene.json -o out.exr
expect_stderr "did you mean 'render'?" "the closest command suggested"
bad "unknown flag" render scene.json -o out.exr --sparkle
bad "no output" render scene.json
bad "passes and time together" render scene.json -o out.exr --passes 2 --time 1
bad "zero passes" render scene.json -o out.exr --passes 0
bad "negative time" render scene.json -o out.exr --time -1
expect_stderr "must be greater than 0" "a readable range message"
awk 'length > 200 { exit 1 }' stderr.txt || fail "a range message of more than 200 characters"
bad "nan exposure" render scene.json -o out.png --exposure nan
bad "negative threads" render scene.json -o out.exr --threads -2
bad "text for a number" render scene.json -o out.exr --photons lots
bad "a negative seed" render scene.json -o out.exr --seed -1
expect_stderr "must be a whole number" "the seed's range"
bad "unknown output format" render scene.json -o out.tga
expect_stderr "out.tga" "unknown output format"
bad "missing output folder" render scene.json -o no/such/folder/out.exr
expect_stderr "no/such/folder" "missing output folder"
bad "layers into a PNG" render scene.json -o out.png --layers
expect_stderr "--layers" "layers into a PNG"
bad "pass without pixel" render scene.json -o out.exr --pass 2
bad "malformed pixel" render scene.json --pixel 3x4
expect_stderr "--pixel" "malformed pixel"
bad "pixel outside the photo" render scene.json --pixel 64,0
expect_stderr "outside" "pixel outside the photo"
[ ! -e out.exr ] || fail "a failed command left out.exr behind"
echo "PASS"

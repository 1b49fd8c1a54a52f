# docs/compositing.md's recipe in Blender's compositor: plate x catcher with the premultiplied
# objects over it rebuilds the beauty. Skipped with a note where Blender is not installed.
SRC=$(cd "$(dirname "$0")/../.." && pwd)  # before testlib.bash moves into the scratch folder
source "$(dirname "$0")/testlib.bash" "$@"
blender=${DP_BLENDER:-$(command -v blender || true)}
if [ -z "$blender" ]; then
    echo "note: Blender is not installed; the layers were not recomposited in its compositor"
    exit 0
fi
make_inputs
write_project scene.json "$BALL" "$FLOOR"
run render scene.json -o layered.exr --passes 4 --layers --threads 2
expect_rc 0 "render with layers"
"$blender" -b --factory-startup --python-exit-code 1 --python "$SRC/tests/cli/compositing_blender.py" -- \
    "$PWD/layered.exr" "$PWD/photo.exr" "$PWD/blender.exr" 64 48 >blender.txt 2>&1 || {
    cat blender.txt >&2
    fail "Blender's compositor failed"
}
[ -s blender.exr ] || { cat blender.txt >&2; fail "Blender wrote no blender.exr"; }
compare blender.exr layered.exr
# Blender's compositor works in 32-bit floats like us: the same sums, rounded alike.
at_most "$MAX_DIFF" 1e-5 || fail "Blender's recomposite differs from the beauty by up to $MAX_DIFF (rmse $RMSE)"
echo "PASS"

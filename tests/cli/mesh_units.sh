# A mesh whose size once placed looks off by 100x or 1000x is named, with the unit_scale that
# would fix it, by `info` (listed with the warnings, and on stderr as every command says them).
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs

# cube FILE SIZE: an OBJ cube SIZE units across, standing on y = 0.
cube() {
    local s=$2
    {
        for i in 0 1 2 3 4 5 6 7; do
            local x=0 y=0 z=0
            (( i & 1 )) && x=$s
            (( i & 2 )) && y=$s
            (( i & 4 )) && z=$s
            echo "v $x $y $z"
        done
        printf 'f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n'
    } >"$1"
}
chair() {  # chair SHAPE_EXTRA SCALE: the object, with extra shape keys and a uniform scale
    echo "{\"name\": \"chair\", \"shape\": {\"type\": \"mesh\", \"path\": \"chair.obj\"$1},
           \"transform\": {\"scale\": [$2, $2, $2]}}"
}
cube chair.obj 180  # a 1.8 m wardrobe, modelled in centimetres

write_project cm.json "$(chair '' 1)" "$FLOOR"
run info cm.json
expect_rc 0 "info on a chair in centimetres read as metres"
expect_stdout "warnings: 1" "one warning"
expect_stdout "objects[0].shape.unit_scale: 'chair' is 180 m across once placed: its file looks like centimetres: set unit_scale 0.01" \
    "the warning names the object and the fix"

# The suggested fix silences it, and info shows the unit.
write_project fixed.json "$(chair ', "unit_scale": 0.01' 1)" "$FLOOR"
run info fixed.json
expect_rc 0 "info with unit_scale 0.01"
expect_stdout "warnings: 0" "no warning once the unit is set"
expect_stdout "'chair': mesh 'chair.obj' (12 triangles), unit_scale 0.01" "the unit in the shape's line"

# The transform's scale counts too: scaled down by 100 in the transform, the chair is fine.
write_project scaled.json "$(chair '' 0.01)" "$FLOOR"
run info scaled.json
expect_stdout "warnings: 0" "no warning for a chair scaled down by its transform"

# Millimetres: 900 units.
cube chair.obj 900
write_project mm.json "$(chair ', "up_axis": "z"' 1)" "$FLOOR"
run info mm.json
expect_stdout "its file looks like millimetres: set unit_scale 0.001" "millimetres"
expect_stdout "up axis z" "the up axis in the shape's line"

# Too small: a metre chair given a millimetre unit.
cube chair.obj 0.9
write_project small.json "$(chair ', "unit_scale": 0.001' 1)" "$FLOOR"
run info small.json
expect_stdout "'chair' is 0.0009 m across once placed: it looks 1000 times too small: set unit_scale 1" "too small"

# render says it on stderr, and still renders.
cube chair.obj 180
expect_warned "render warns" "its file looks like centimetres: set unit_scale 0.01" \
    render cm.json -o out.exr --passes 1 --photons 2000
echo "PASS"

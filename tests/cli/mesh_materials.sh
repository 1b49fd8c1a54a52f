# A mesh drawn with its file's materials: `info` lists them, and says which texture it could
# not read (its material keeps its colour).
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
run make-test-image wood.png --size 4 4 --value 0.6 0.4 0.2
expect_rc 0 "make-test-image texture"
cat >cup.mtl <<'MTL'
newmtl glaze
Kd 0.9 0.9 0.85
newmtl wood
Kd 0.8 0.8 0.8
map_Kd wood.png
newmtl label
Kd 0.2 0.3 0.8
map_Kd C:\Users\someone\label.png
MTL
cat >cup.obj <<'OBJ'
mtllib cup.mtl
v -0.1 0 0
v 0.1 0 0
v 0.1 0.2 0
v -0.1 0.2 0
v 0 0.3 0
vt 0 0
vt 1 0
vt 1 1
usemtl glaze
f 1/1 2/2 3/3
usemtl wood
f 1/1 3/2 4/3
usemtl label
f 4/1 3/2 5/3
OBJ
CUP='{"name": "cup", "shape": {"type": "mesh", "path": "cup.obj"}, "material_source": "file",
      "material": {"type": "mirror"}}'
write_project cup.json "$CUP" "$FLOOR"
run info cup.json
expect_rc 0 "info on a mesh with its file's materials"
expect_stdout "'cup': mesh 'cup.obj' (3 triangles), materials from the file, elsewhere mirror" "the object's line"
expect_stdout "file material 'glaze': diffuse, albedo (0.9, 0.9, 0.85)" "a colour from the MTL"
expect_stdout "file material 'wood': diffuse, albedo texture '" "a texture beside the mesh"
expect_stdout "wood.png' (4x4)" "the texture's size"
expect_stdout "file material 'label': diffuse, albedo (0.2, 0.3, 0.8)" "a lost texture's material keeps its colour"
expect_stdout "objects[0].shape.path: material 'label': its texture cannot be read (" "the warning"

# The project's own material: no file material is read, nothing is said.
write_project own.json "${CUP/\"file\"/\"project\"}" "$FLOOR"
run info own.json
expect_rc 0 "info with the project's material"
expect_stdout "'cup': mesh 'cup.obj' (3 triangles), mirror" "the project's material"
expect_stdout "warnings: 0" "no warning about the file's textures"

# "file" on a sphere is refused.
write_project bad.json '{"shape": {"type": "sphere", "radius": 0.2}, "material_source": "file"}' "$FLOOR"
expect_refused "file materials on a sphere" "field 'objects[0].material_source': \"file\" takes the materials of a mesh file" \
    info bad.json
echo "PASS"

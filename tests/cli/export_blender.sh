# `export blender`: the script compiles, carries the converter verbatim and the project with
# absolute paths to files that exist; bad projects are refused with exit 2. Where Blender is
# installed, the exported scene is rendered and its object and shadow masks are compared with
# ours (IoU); without Blender that part is skipped with a note.
SRC=$(cd "$(dirname "$0")/../.." && pwd)  # before testlib.bash moves into the scratch folder
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs

# A project in a folder of its own whose files are named relative to it (one a level up), with
# a textured proxy, a mesh object and an estimated albedo.
mkdir -p proj/meshes
run make-test-image proj/tex.png --size 8 8 --value 0.3 0.6 0.2
expect_rc 0 "make-test-image texture"
printf 'v 0 0 0\nv 0.4 0 0\nv 0 0.4 0\nv 0 0 0.4\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >proj/meshes/tet.obj
cat >proj/scene.json <<'JSON'
{
  "schema_version": 1,
  "photo": {"path": "../photo.exr"},
  "probe": {"path": "../probe.exr", "rotation_deg": [0, 30, 0]},
  "camera": {"model": "lookat", "eye": [0, 1.5, 4], "target": [0, 0.4, 0], "vfov_deg": 40},
  "real": [{"name": "floor", "shape": {"type": "plane", "size": [10, 10]}, "albedo": "estimate"},
           {"name": "mat", "shape": {"type": "plane", "size": [1, 1]},
            "transform": {"translation": [1, 0.001, 0]}, "albedo": {"texture": "tex.png"},
            "gloss": {"specular": 0.05, "roughness": 0.2}}],
  "objects": [{"name": "tet", "shape": {"type": "mesh", "path": "meshes/tet.obj"},
               "transform": {"translation": [-1, 0, 0]}}],
  "render": {"photons_per_pass": 20000, "passes": 3, "seed": 7}
}
JSON

# check_script SCRIPT [BLEND]: compiles; holds dp_cycles.py verbatim; every path in its project
# is absolute and names an existing file; no "estimate" is left; BLEND is the .blend it saves.
check_script() {
    python3 -m py_compile "$1" || fail "$1 does not compile"
    python3 - "$1" "$SRC/bench/cycles/dp_cycles.py" "${2:-}" <<'PY' || fail "$1: the script's content is wrong"
import ast, json, os, re, sys
script, converter, blend = sys.argv[1:4]
src = open(script).read()
assert open(converter).read() in src, "dp_cycles.py is not embedded verbatim"
def literal(name, pattern):
    m = re.search(r"^" + name + r" = " + pattern, src, re.S | re.M)
    assert m, f"no {name} in the script"
    return ast.literal_eval(m.group(1)).decode()
project = json.loads(literal("PROJECT", r"json\.loads\((b'''.*?''')\.decode\(\)\)$"))
assert literal("BLEND", r"(b'.*?')\.decode\(\)$") == blend, "BLEND"
paths = [project["photo"]["path"], project["probe"]["path"]]
for e in project.get("real", []) + project.get("objects", []):
    if e["shape"]["type"] == "mesh":
        paths.append(e["shape"]["path"])
    albedo = e.get("albedo", e.get("material", {}).get("albedo"))
    assert albedo != "estimate", "an albedo left as 'estimate'"
    if isinstance(albedo, dict):
        paths.append(albedo["texture"])
for p in paths:
    assert os.path.isabs(p) and os.path.isfile(p), f"not an absolute path to a file: {p}"
print(len(paths), "paths")
PY
}

# From another folder, so that nothing resolves by accident against the working directory.
mkdir -p elsewhere
(cd elsewhere && "$DP" export blender ../proj/scene.json -o ../proj.py >../stdout.txt 2>../stderr.txt)
RC=$?
expect_rc 0 "export blender of a project in its own folder"
expect_stdout "wrote ../proj.py" "the written script"
check_script proj.py >paths.txt
grep -qx "4 paths" paths.txt || fail "expected 4 paths (photo, probe, texture, mesh), got: $(cat paths.txt)"

# Quotes, a backslash, non-ASCII letters and a line break in the paths survive the literals.
odd=$'odd \'q\' "dq" \\ \u00fc\nline'
oddpy="$odd/x"$'\n'".py"
cp -r proj "$odd"
run export blender "$odd/scene.json" -o "$oddpy"
expect_rc 0 "export blender from a folder with an odd name"
check_script "$oddpy" >paths.txt
grep -qx "4 paths" paths.txt || fail "odd names: expected 4 paths, got: $(cat paths.txt)"

run export blender proj/scene.json -o withblend.py --blend out/scene.blend
expect_rc 2 "--blend into a missing folder"
expect_stderr "--blend" "the message names --blend"
mkdir -p out
run export blender proj/scene.json -o withblend.py --blend out/scene.blend --samples 16
expect_rc 0 "export blender --blend"
check_script withblend.py "$PWD/out/scene.blend"
grep -qx "SAMPLES = 16" withblend.py || fail "--samples 16 is not the script's SAMPLES"

# The bundled sample names Blender's own city probe: it loads where Blender is installed.
sample_probe=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["probe"]["path"])' \
    "$SRC/resources/sample/sample.json")
if [ -f "$sample_probe" ]; then
    run export blender "$SRC/resources/sample/sample.json" -o sample.py
    expect_rc 0 "export blender of the bundled sample"
    check_script sample.py
else
    echo "note: $sample_probe is missing (it comes with Blender); the bundled sample was not exported"
fi

# Lights of every kind travel in the script's project (placed by the converter when it runs).
sed 's|^  "render"|  "lights": [{"name": "bulb", "type": "point", "transform": {"translation": [1, 2, 0.5]}, "colour": [1, 0.5, 0.25], "power_w": 60},\
             {"name": "cone", "type": "spot", "transform": {"translation": [-1, 2, 0], "rotation_deg": [30, 0, 0]},\
              "power_w": 200, "spot_angle_deg": 50, "spot_blend": 0.2},\
             {"name": "panel", "type": "rect", "power_w": 300, "colour": [1, 0.5, 0.5], "size": [0.5, 0.3], "visible": false,\
              "transform": {"translation": [0, 2.5, -1], "rotation_deg": [10, 20, 90], "scale": [2, 1, 1]}},\
             {"name": "round", "type": "disk", "transform": {"translation": [0, 3, 0]}, "size": [0.4]},\
             {"name": "oval", "type": "disk", "transform": {"translation": [0.5, 3, 0], "scale": [1, 1, 2]}, "size": [0.4]}],\
  "render"|' proj/scene.json >proj/lights.json
run export blender proj/lights.json -o lights.py --blend "$PWD/lights.blend"
expect_rc 0 "export blender of a project with lights"
check_script lights.py "$PWD/lights.blend" >/dev/null
python3 - lights.py <<'PY' || fail "the script's project lacks the lights"
import ast, json, re, sys
src = open(sys.argv[1]).read()
m = re.search(r"^PROJECT = json\.loads\((b'''.*?''')\.decode\(\)\)$", src, re.S | re.M)
lights = json.loads(ast.literal_eval(m.group(1)).decode())["lights"]
assert [l["type"] for l in lights] == ["point", "spot", "rect", "disk", "disk"], lights
assert lights[2]["visible"] is False and lights[1]["spot_angle_deg"] == 50, lights
PY

# Bad input: exit 2 naming the file and the field.
echo '{"schema_version": 1, "photo": ' >broken.json
expect_refused "invalid JSON" "broken.json" export blender broken.json -o x.py
write_project nophoto.json "$BALL" "$FLOOR" gone.exr
expect_refused "missing photo" "photo.path" export blender nophoto.json -o x.py
[ ! -e x.py ] || fail "a script was written for a bad project"
expect_refused "not a .py output" "-o" export blender proj/scene.json -o x.txt
expect_refused "output in a missing folder" "-o" export blender proj/scene.json -o nowhere/x.py
run make-test-image ball.exr --size 32 32 --value 0.5 0.5 0.5
sed 's/"probe": {"path": "probe.exr"}/"probe": {"path": "ball.exr", "format": "mirrorball"}/' nophoto.json |
    sed 's/gone.exr/photo.exr/' >ball.json
expect_refused "a mirror-ball probe" "probe.format" export blender ball.json -o x.py
expect_stderr "ball.json" "the message names the project"
cat >distorted.json <<'JSON'
{
  "schema_version": 1, "photo": {"path": "photo.exr"}, "probe": {"path": "probe.exr"},
  "camera": {"model": "opencv", "fx": 60, "fy": 60, "cx": 31.5, "cy": 23.5,
             "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "translation": [0, 1, 4],
             "distortion": [-0.1, 0, 0, 0, 0]},
  "real": [], "objects": []
}
JSON
expect_refused "lens distortion" "camera.distortion" export blender distorted.json -o x.py
run export blender
expect_rc 2 "no project"

blender=${DP_BLENDER:-$(command -v blender || true)}
if [ -z "$blender" ]; then
    echo "note: Blender is not installed; the exported scene was not rendered"
    exit 0
fi

# The exported scene against ours, at 128 x 72: a ball on a grey floor under a sky with a sun.
run make-test-image plate.exr --size 128 72 --value 0.5 0.5 0.5
expect_rc 0 "make-test-image plate"
write_project small.json "$BALL" "$FLOOR" plate.exr
sed -i 's/"probe": {"path": "probe.exr"}/"probe": {"path": "probe.exr", "rotation_deg": [0, 30, 0]}/' small.json
run export blender small.json -o small.py --blend "$PWD/small.blend" --samples 64
expect_rc 0 "export blender small.json"
run_blender() {  # run_blender ARGS...: Blender 3.4 headless; output in blender.txt
    "$blender" -b --python-exit-code 1 "$@" >blender.txt 2>&1 || {
        cat blender.txt >&2
        fail "Blender failed: $*"
    }
}
# Each check below runs in Blender 3.4 and, where .deps/bpy5 (or $DP_BPY5_PYTHON) holds it, in
# Blender 5 as a Python module.
bpy5=${DP_BPY5_PYTHON:-$SRC/.deps/bpy5/bin/python}
blenders=(3.4)
if [ -x "$bpy5" ]; then
    blenders+=(5)
else
    echo "note: no Blender 5 at $bpy5; the hand-off was checked in Blender 3.4 only"
fi
# hand_off VERSION SCRIPT [ARGS...]: an exported script (or a check taking ARGS after --) run
# headless in that Blender; output in blender.txt.
hand_off() {
    local version=$1 script=$2
    shift 2
    if [ "$version" = 3.4 ]; then
        "$blender" -b --factory-startup --python-exit-code 1 --python "$script" -- "$@" >blender.txt 2>&1
    else
        "$bpy5" "$script" -- "$@" >blender.txt 2>&1
    fi || { cat blender.txt >&2; fail "Blender $version: $script $*"; }
}
# in_blend VERSION BLEND CHECK: runs the Python file CHECK with BLEND open; output in blender.txt.
in_blend() {
    if [ "$1" = 3.4 ]; then
        "$blender" -b "$2" --python-exit-code 1 --python "$3" >blender.txt 2>&1
    else
        "$bpy5" -c 'import bpy, runpy, sys; bpy.ops.wm.open_mainfile(filepath=sys.argv[1]); runpy.run_path(sys.argv[2])' \
            "$2" "$3" >blender.txt 2>&1
    fi || { cat blender.txt >&2; fail "Blender $1: $3 on $2"; }
}

run render small.json -o ours.exr --layers --passes 32 --threads 2
expect_rc 0 "render small.json"
run reference small.json -o real-only.exr --real-only --spp 16 --threads 2
expect_rc 0 "reference --real-only small.json"
# masks VERSION CYCLES.exr: sets OBJECTS_IOU and SHADOW_IOU against ours.
masks() {
    hand_off "$1" "$SRC/tests/cli/export_blender_masks.py" "$2" ours.exr real-only.exr
    echo "Blender $1: $(grep objects_iou blender.txt)"
    OBJECTS_IOU=$(awk '$1 == "objects_iou" { print $2 }' blender.txt)
    SHADOW_IOU=$(awk '$1 == "objects_iou" { print $4 }' blender.txt)
    [ -n "$OBJECTS_IOU" ] && [ -n "$SHADOW_IOU" ] || fail "no IoUs from export_blender_masks.py"
}

# Meshes of every format the renderer reads, all the same 2 x 1.6 m quad from y 0.2 to 1.8
# (ours' axes) raised 0.5 m by the object's transform: glTF (Y up, like ours), STL (no axes:
# written in ours'), and FBX written by Blender with Z up, in metres and in centimetres (its
# declared axis and unit apply with no up_axis or unit_scale in the project).
printf '%s' '{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}]}],
  "buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64,AACAv83MTD4AAAAAAACAP83MTD4AAAAAAACAP2Zm5j8AAAAAAACAv2Zm5j8AAAAAAAAAAAAAgD8AAIA/AACAPwAAgD8AAAAAAAAAAAAAAAAAAAEAAgAAAAIAAwA="}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                  {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0.2, 0], "max": [1, 1.8, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]}' >quad.gltf
cat >quad.stl <<'STL'
solid quad
facet normal 0 0 1
outer loop
vertex -1 0.2 0
vertex 1 0.2 0
vertex 1 1.8 0
endloop
endfacet
facet normal 0 0 1
outer loop
vertex -1 0.2 0
vertex 1 1.8 0
vertex -1 1.8 0
endloop
endfacet
endsolid quad
STL
cat >make_fbx.py <<'PY'
import bpy, sys
out, unit = sys.argv[sys.argv.index("--") + 1:][:2]
bpy.ops.wm.read_factory_settings(use_empty=True)
scale = 100.0 if unit == "cm" else 1.0
bpy.context.scene.unit_settings.scale_length = 1 / scale
mesh = bpy.data.meshes.new("quad")  # standing in Blender's xz plane, Z up
mesh.from_pydata([(-scale, 0, 0.2 * scale), (scale, 0, 0.2 * scale), (scale, 0, 1.8 * scale), (-scale, 0, 1.8 * scale)],
                 [], [(0, 1, 2, 3)])
bpy.context.scene.collection.objects.link(bpy.data.objects.new("quad", mesh))
bpy.ops.export_scene.fbx(filepath=out, axis_forward="Y", axis_up="Z", apply_unit_scale=True, bake_space_transform=True)
PY
hand_off 3.4 make_fbx.py "$PWD/quad_m.fbx" m
hand_off 3.4 make_fbx.py "$PWD/quad_cm.fbx" cm
cat >check_gltf.py <<'PY'
import bpy, math
# Blender is Z-up: our height is its z; the scene is turned about it by the probe's frame.
verts = [o.matrix_world @ v.co for o in bpy.data.objects if o.type == "MESH" for v in o.data.vertices]
quad = [v for v in verts if 0.69 < v.z < 2.31]
assert len(quad) == 4, [tuple(round(c, 3) for c in v) for v in verts]
assert abs(min(v.z for v in quad) - 0.7) < 1e-4 and abs(max(v.z for v in quad) - 2.3) < 1e-4
width = max(math.hypot(a.x - b.x, a.y - b.y) for a in quad for b in quad)
assert abs(width - 2) < 1e-4 and abs(sum(v.x for v in quad)) < 1e-4 and abs(sum(v.y for v in quad)) < 1e-4, width
print("gltf_ok")
PY
mesh_files=(quad.gltf quad.stl quad_m.fbx quad_cm.fbx)
# Ours sees the same quad from each file: the objects' masks agree pixel for pixel (glTF's as
# the reference), and the render finds no size to warn about.
for m in "${mesh_files[@]}"; do
    sed 's/"shape": {"type": "sphere", "radius": 0.5}/"shape": {"type": "mesh", "path": "'"$m"'"}/' small.json >"$m.json"
    grep -q "$m" "$m.json" || fail "the $m project was not written"
    run render "$m.json" -o "$m.exr" --layers --passes 1 --threads 2
    expect_rc 0 "render $m.json"
    ! grep -q "unit_scale" stderr.txt || fail "$m: a size warning: $(cat stderr.txt)"
    run export blender "$m.json" -o "$m.py"
    expect_rc 0 "export blender $m.json"
done
for m in quad.stl quad_m.fbx quad_cm.fbx; do
    compare quad.gltf.exr "$m.exr" --layer alpha
    echo "$m against quad.gltf: alpha RMSE $RMSE"
    at_most "$RMSE" 0.02 || fail "ours places the quad from $m unlike glTF's (alpha RMSE $RMSE)"
done
# The comparison can tell: the metre FBX with its declared Z up overridden by a Y up lies flat.
sed 's/"path": "quad_m.fbx"}/"path": "quad_m.fbx", "up_axis": "y"}/' quad_m.fbx.json >flat.json
run render flat.json -o flat.exr --layers --passes 1 --threads 2
expect_rc 0 "render flat.json"
compare quad.gltf.exr flat.exr --layer alpha
awk -v v="$RMSE" 'BEGIN { exit !(v > 0.1) }' || fail "an FBX turned by its up_axis still matches (alpha RMSE $RMSE)"

# An OBJ whose faces use two materials of its MTL file, drawn with "material_source": "file".
printf 'mtllib tet.mtl\nv 0 0 0\nv 0.4 0 0\nv 0 0 0.4\nv 0 0.4 0\nusemtl red\nf 1 3 2\nf 1 2 4\nusemtl blue\nf 1 4 3\nf 2 3 4\n' >tet.obj
printf 'newmtl red\nKd 0.8 0.1 0.1\nnewmtl blue\nKd 0.1 0.1 0.8\n' >tet.mtl
sed 's/"shape": {"type": "sphere", "radius": 0.5}/"shape": {"type": "mesh", "path": "tet.obj"}, "material_source": "file"/' small.json >file.json
run export blender file.json -o file.py
expect_rc 0 "export blender file.json"
cat >check_file_materials.py <<'PY'
import bpy
tet = [o for o in bpy.data.objects if o.type == "MESH" and o.name.startswith("object 0")]
assert len(tet) == 1, [o.name for o in bpy.data.objects]
colours = set()
for m in tet[0].data.materials:
    bsdf = next(n for n in m.node_tree.nodes if n.type in ("BSDF_PRINCIPLED", "BSDF_DIFFUSE"))
    colours.add(tuple(round(c, 3) for c in bsdf.inputs["Base Color" if bsdf.type == "BSDF_PRINCIPLED" else "Color"].default_value[:3]))
assert colours == {(0.8, 0.1, 0.1), (0.1, 0.1, 0.8)}, colours
print("file_materials_ok")
PY

for version in "${blenders[@]}"; do
    # The lights arrive as Blender lights of their kind, power, colour, place and direction.
    rm -f lights.blend
    hand_off "$version" lights.py
    grep -q "saved $PWD/lights.blend" blender.txt || fail "Blender $version: lights.py did not save lights.blend"
    grep -q "in Blender $version" blender.txt || fail "Blender $version: the script did not name the Blender it runs in"
    hand_off "$version" "$SRC/tests/cli/export_blender_lights.py" lights.blend proj/lights.json
    grep -qx "lights_ok 5" blender.txt || fail "the lights in Blender $version: $(tail -3 blender.txt)"

    # The scene renders, and its objects' and shadow's masks are ours' (Blender 5 writes its
    # multilayer EXR as one part per layer).
    rm -f small.blend cycles.exr
    hand_off "$version" small.py --render cycles.exr --threads 2
    [ -s small.blend ] || fail "Blender $version: the script did not save small.blend (exported with --blend)"
    [ -s cycles.exr ] || fail "Blender $version: the script did not write cycles.exr (--render)"
    masks "$version" cycles.exr
    awk -v v="$OBJECTS_IOU" 'BEGIN { exit !(v > 0.95) }' || fail "Blender $version: objects' IoU $OBJECTS_IOU <= 0.95"
    awk -v v="$SHADOW_IOU" 'BEGIN { exit !(v > 0.8) }' || fail "Blender $version: shadow's IoU $SHADOW_IOU <= 0.8"
    # The saved .blend names the photo and probe by absolute paths, as docs/cycles.md says.
    cat >check_paths.py <<'PY'
import bpy
files = [i.filepath for i in bpy.data.images if i.source == "FILE" and i.packed_file is None]
assert files and all(f.startswith("/") for f in files), files
print("paths_ok", len(files))
PY
    in_blend "$version" small.blend check_paths.py
    grep -q "paths_ok" blender.txt || fail "Blender $version: the .blend's image paths are not absolute: $(tail -2 blender.txt)"

    # Every mesh format: the quad where ours puts it.
    for m in "${mesh_files[@]}"; do
        rm -f quad.blend
        hand_off "$version" "$m.py" --blend "$PWD/quad.blend"
        in_blend "$version" quad.blend check_gltf.py
        grep -q gltf_ok blender.txt || fail "Blender $version: the quad from $m is not where the project puts it"
    done
    rm -f file.blend
    hand_off "$version" file.py --blend "$PWD/file.blend"
    in_blend "$version" file.blend check_file_materials.py
    grep -q file_materials_ok blender.txt || fail "Blender $version: the OBJ's own materials did not arrive"
done

# The comparison can tell: with the probe turned a further 90 degrees in the exported scene
# only, the sun and so the shadow move, and the shadow's IoU falls (Blender 3.4).
sed 's/"rotation_deg": \[0, 30, 0\]/"rotation_deg": [0, 120, 0]/' small.json >turned.json
run export blender turned.json -o turned.py --samples 64
expect_rc 0 "export blender turned.json"
hand_off 3.4 turned.py --render turned.exr --threads 2
masks 3.4 turned.exr
awk -v v="$SHADOW_IOU" 'BEGIN { exit !(v < 0.5) }' ||
    fail "a probe turned by 90 degrees still gives a shadow IoU of $SHADOW_IOU"

# docs/cycles.md's Mapping-node rotation for a scene rebuilt in Blender's axes: the shadow stays
# where the exported frame puts it; with the sign of the rotation flipped it moves.
run_blender --factory-startup --python "$SRC/tests/cli/export_blender_mapping.py" -- small.json "$PWD"
grep documented_iou blender.txt
DOCUMENTED=$(awk '$1 == "documented_iou" { print $2 }' blender.txt)
WRONG=$(awk '$1 == "documented_iou" { print $4 }' blender.txt)
awk -v v="$DOCUMENTED" 'BEGIN { exit !(v > 0.9) }' || fail "documented Mapping rotation: shadow IoU '$DOCUMENTED' <= 0.9"
awk -v v="$WRONG" 'BEGIN { exit !(v < 0.6) }' || fail "the rotation's sign flipped: shadow IoU '$WRONG' >= 0.6"

# A principled ball becomes a Principled BSDF with the project's numbers, by the input names of
# the Blender that runs the script (3.4: Specular as F0 / 0.08, Transmission, Emission; 4 and
# later: Specular IOR Level, Transmission Weight, Emission Color).
sed 's/"material": {"type": "diffuse", "albedo": \[0.8, 0.3, 0.2\]}/"material": {"type": "principled", "base_colour": [0.9, 0.5, 0.25], "metallic": 1, "roughness": 0.3, "ior": 1.8, "specular": 0.5, "transmission": 0.25, "emission": [0, 1, 2]}/' \
    small.json >principled.json
grep -q principled principled.json || fail "the principled project was not written"
run export blender principled.json -o principled.py --blend "$PWD/principled.blend"
expect_rc 0 "export blender principled.json"
cat >check_principled.py <<'PY'
import bpy
nodes = [n for m in bpy.data.materials if m.node_tree for n in m.node_tree.nodes if n.type == "BSDF_PRINCIPLED"]
assert len(nodes) == 1, len(nodes)
i = nodes[0].inputs
def near(name, want):
    got = i[name].default_value
    got = list(got)[:3] if hasattr(got, "__len__") else [got]
    want = want if isinstance(want, list) else [want]
    assert all(abs(g - w) < 1e-4 for g, w in zip(got, want)), (name, got, want)
near("Base Color", [0.9, 0.5, 0.25])
near("Metallic", 1.0)
near("Roughness", 0.3)
near("IOR", 1.8)
if "Specular IOR Level" in i:
    near("Specular IOR Level", 0.25)
    near("Transmission Weight", 0.25)
    near("Emission Color", [0, 1, 2])
else:
    near("Specular", 0.5 * ((1.8 - 1) / (1.8 + 1)) ** 2 / 0.08)
    near("Transmission", 0.25)
    near("Emission", [0, 1, 2])
print("principled_ok")
PY
for version in "${blenders[@]}"; do
    rm -f principled.blend
    hand_off "$version" principled.py
    in_blend "$version" principled.blend check_principled.py
    grep -q principled_ok blender.txt || fail "Blender $version: the Principled BSDF does not carry the project's numbers"
done

# Its metallic-roughness texture: a Non-Color image whose green and blue multiply the
# roughness and the metallic. A normal map on a built-in sphere is refused, naming the field.
run make-test-image mr.png --size 8 8 --value 0 0.5 1
sed 's/"emission": \[0, 1, 2\]}/"emission": [0, 1, 2], "metallic_roughness_texture": "mr.png"}/' principled.json >textured.json
grep -q metallic_roughness_texture textured.json || fail "the textured project was not written"
run export blender textured.json -o textured.py --blend "$PWD/textured.blend"
expect_rc 0 "export blender textured.json"
cat >check_textured.py <<'PY'
import bpy
trees = [m.node_tree for m in bpy.data.materials if m.node_tree]
tree = next(t for t in trees if any(n.type == "BSDF_PRINCIPLED" for n in t.nodes))
bsdf = next(n for n in tree.nodes if n.type == "BSDF_PRINCIPLED")
images = [n.image for n in tree.nodes if n.type == "TEX_IMAGE"]
assert any(i.name == "mr.png" and i.colorspace_settings.name == "Non-Color" for i in images), [(i.name, i.colorspace_settings.name) for i in images]
def factor_into(name):
    link = next(l for l in tree.links if l.to_socket == bsdf.inputs[name])
    times = link.from_node
    assert times.type == "MATH" and times.operation == "MULTIPLY", times.type
    channel = next(l for l in tree.links if l.to_socket == times.inputs[0]).from_socket.name
    return channel, times.inputs[1].default_value
rough, metal = factor_into("Roughness"), factor_into("Metallic")
assert rough[0] == "Green" and abs(rough[1] - 0.3) < 1e-6, rough
assert metal[0] == "Blue" and abs(metal[1] - 1.0) < 1e-6, metal
print("textured_ok")
PY
for version in "${blenders[@]}"; do
    rm -f textured.blend
    hand_off "$version" textured.py
    in_blend "$version" textured.blend check_textured.py
    grep -q textured_ok blender.txt || fail "Blender $version: the metallic-roughness texture is not wired into the Principled BSDF"
done
sed 's/"emission": \[0, 1, 2\]}/"emission": [0, 1, 2], "normal_texture": "mr.png"}/' principled.json >normal.json
run export blender normal.json -o normal.py
expect_rc 2 "export blender normal.json (a normal map on a sphere)"
expect_stderr "objects[0].material.normal_texture" "the refusal of a normal map on a sphere"

echo "ok"

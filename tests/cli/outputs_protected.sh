# Nothing lost, whatever the file: no command writes onto a file it reads (the project, its
# photo and probe, its meshes and the files they name, textures), however the output is spelled;
# a read-only output is replaced only with --force; a full file system (space or inodes) is
# found before the work; names up to the file system's limit save; a calibration the project
# loader would refuse is not written. Every refusal is exit code 2 with one line naming the
# output, the option and the input, and every input's bytes are checked after each command.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs

# ---- the inputs: an OBJ with a material file and a texture, a glTF with a buffer and an image
run make-test-image tex.png --size 4 4 --value 0.6 0.4 0.2
expect_rc 0 "make the OBJ's texture"
run make-test-image "img a.png" --size 4 4 --value 0.2 0.4 0.6
expect_rc 0 "make the glTF's image"
printf 'newmtl wood\nKd 0.8 0.8 0.8\nmap_Kd -s 1 1 1 tex.png\n' >tri.mtl
printf 'mtllib tri.mtl\nv -0.3 0.2 0\nv 0.3 0.2 0\nv 0 0.8 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl wood\nf 1/1 2/2 3/3\n' >tri.obj
f32() { for v in "$@"; do case $v in 0) printf '\x00\x00\x00\x00' ;; 1) printf '\x00\x00\x80\x3f' ;; esac; done; }
{ f32 0 0 0 1 0 0 0 1 0; f32 0 0 1 0 0 1; } >tri.bin
cat >tri.gltf <<'JSON'
{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
 "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
 "textures": [{"source": 0}], "images": [{"uri": "img%20a.png"}],
 "buffers": [{"uri": "tri.bin", "byteLength": 60}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
               {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}]}
JSON
OBJ_MESH='{"name": "tri", "shape": {"type": "mesh", "path": "tri.obj"}, "material_source": "file",
           "material": {"type": "diffuse"}}'
GLTF_MESH='{"name": "leaf", "shape": {"type": "mesh", "path": "tri.gltf"}, "material_source": "file",
            "transform": {"translation": [0.5, 0, 0]}, "material": {"type": "diffuse"}}'
write_project scene.json "$BALL, $OBJ_MESH, $GLTF_MESH" "$FLOOR"
sed -i 's/"passes": 3/"passes": 1/' scene.json

INPUTS=(photo.exr probe.exr scene.json tri.obj tri.mtl tex.png tri.gltf tri.bin "img a.png")
sha256sum "${INPUTS[@]}" >inputs.sha256
inputs_unchanged() {  # inputs_unchanged DESCRIPTION
    sha256sum --quiet -c inputs.sha256 >check.txt 2>&1 || { cat check.txt >&2; fail "$1: an input's bytes changed"; }
}
# refused DESCRIPTION TEXT COMMAND...: exit code 2, one line holding TEXT, before any work (the
# renders asked for would take minutes), every input as it was.
refused() {
    local what=$1 start=$SECONDS
    expect_refused "$@"
    [ "$(wc -l <stderr.txt)" -eq 1 ] || fail "$what: the refusal is not one line"
    [ $((SECONDS - start)) -lt 20 ] || fail "$what: refused only after the work"
    inputs_unchanged "$what"
}

run render scene.json -o first.exr
expect_rc 0 "the scene renders (its meshes and the files they name read)"
inputs_unchanged "a render"

# ---- outputs onto the files the project's meshes name ---------------------------------------
refused "render onto the texture an OBJ's material file names" \
    "tex.png: field '--output': is the texture named by mesh tri.obj's material file tri.mtl (objects[1].shape.path)" \
    render scene.json -o tex.png --passes 100000
refused "calibrate proxy -o onto the OBJ's material file" \
    "tri.mtl: field '--output': is the material file of mesh tri.obj (objects[1].shape.path)" \
    calibrate proxy scene.json ground -o tri.mtl
refused "render onto a glTF's image (a URI with %20)" \
    "img a.png: field '--output': is the image named by glTF mesh tri.gltf (objects[2].shape.path)" \
    render scene.json -o "img a.png" --passes 100000
refused "calibrate proxy -o onto a glTF's buffer" "is the buffer of glTF mesh tri.gltf" \
    calibrate proxy scene.json ground -o tri.bin
refused "reference onto the OBJ's texture" "field '--output': is the texture named by mesh tri.obj" \
    reference scene.json -o tex.png --spp 100000
refused "convert onto the texture" "is the input image itself" convert tex.png tex.png

# By identity: a symbolic link, a hard link and another spelling are the file itself.
ln -s tex.png link.png
refused "render onto a symbolic link to the texture" "link.png: field '--output': is 'tex.png', the texture named by mesh tri.obj's material file tri.mtl (objects[1].shape.path)" \
    render scene.json -o link.png --passes 100000
ln tex.png hard.png
refused "render onto a hard link to the texture" "hard.png: field '--output': is 'tex.png', the texture named by mesh tri.obj" \
    render scene.json -o hard.png --passes 100000
mkdir -p sub
refused "render onto the photo spelled another way" "is the project's photo (photo.path" \
    render scene.json -o ./sub/../photo.exr --passes 100000
refused "render onto the probe" "probe.exr: field '--output': is the project's light probe (probe.path)" \
    render scene.json -o probe.exr --passes 100000
write_project shard.dpp "$BALL" "$FLOOR"
sha256sum shard.dpp >>inputs.sha256
refused "a render shard onto its project file" "shard.dpp: field '--output': is the project file itself" \
    render shard.dpp --pass-range 0:100000 -o shard.dpp
refused "a render shard onto the OBJ's material file, linked" "mtl.dpp: field '--output': is 'tri.mtl', the material file of mesh tri.obj" \
    render scene.json --pass-range 0:100000 -o "$(ln -s tri.mtl mtl.dpp && echo mtl.dpp)"
write_project scene.py "$BALL" "$FLOOR"
sha256sum scene.py >>inputs.sha256
refused "export onto its project file" "scene.py: field '-o': is the project file itself" \
    export blender scene.py -o scene.py
refused "export --blend onto an input" "photo.blend: field '--blend': is 'photo.exr', the project's photo (photo.path)" \
    export blender scene.json -o out.py --blend "$(ln -s photo.exr photo.blend && echo photo.blend)"
run render scene.json --pass-range 0:1 -o part.dpp
expect_rc 0 "a shard"
sha256sum part.dpp >>inputs.sha256
refused "merge onto a shard" "part.exr: field '--output': is 'part.dpp', one of the shards being merged" \
    merge part.dpp -o "$(ln -s part.dpp part.exr && echo part.exr)"

# ---- calibrations: the project updated in place, nothing else replaced ----------------------
refused "calibrate proxy -o onto the photo" "photo.exr: field '--output': is the project's photo (photo.path)" \
    calibrate proxy scene.json ground -o photo.exr
refused "calibrate probe -o onto the probe" "is the project's light probe (probe.path)" \
    calibrate probe scene.json --intensity 2 -o probe.exr
write_project albedo.json "" "$FLOOR" albedo_floor_albedo.exr
cp photo.exr albedo_floor_albedo.exr
sha256sum albedo.json albedo_floor_albedo.exr >>inputs.sha256
refused "calibrate albedo's texture onto the photo" \
    "albedo_floor_albedo.exr: field 'real[0].albedo.texture': is the project's photo (photo.path)" \
    calibrate albedo albedo.json --samples 100000
refused "calibrate chessboard --poses onto its photo" "photo.exr: field '--poses': is a photo being calibrated" \
    calibrate chessboard new.json photo.exr --square 0.1 --poses photo.exr
[ -e new.json ] && fail "a refused chessboard calibration created its project"

# fSpy: the embedded photo never replaces the project, its photo or the fSpy file.
le32() { local v=$1 b; for b in 0 8 16 24; do printf "\\x$(printf %02x $(((v >> b) & 255)))"; done; }
run make-test-image embedded.png --size 8 6 --value 0.2 0.3 0.4
STATE='{"calibrationSettingsBase": {"referenceDistanceAxis": "xPositive", "referenceDistance": 1,
 "referenceDistanceUnit": "Meters"}, "cameraParameters": {"principalPoint": {"x": 0, "y": 0},
  "cameraTransform": {"rows": [[1, 0, 0, 0], [0, 0, -1, -5], [0, 1, 0, 1], [0, 0, 0, 1]]},
  "horizontalFieldOfView": 1.0, "imageWidth": 800, "imageHeight": 600}}'
{ printf 'fspy'; le32 1; le32 ${#STATE}; le32 "$(stat -c %s embedded.png)"; printf '%s' "$STATE"; cat embedded.png; } >scene.fspy
sha256sum scene.fspy >>inputs.sha256
refused "--extract-photo onto the project file" "scene.json: field '--extract-photo': is the project file itself" \
    calibrate fspy scene.json scene.fspy --extract-photo scene.json
refused "--extract-photo onto the project's photo" "photo.exr: field '--extract-photo': is the project's photo (photo.path)" \
    calibrate fspy scene.json scene.fspy --extract-photo photo.exr
refused "--extract-photo onto the fSpy file" "field '--extract-photo': is the fSpy file being read" \
    calibrate fspy fresh.json scene.fspy --extract-photo scene.fspy
refused "--extract-photo onto a new project's own file" "fresh.json: field '--extract-photo': is also the output of project" \
    calibrate fspy fresh.json scene.fspy --extract-photo fresh.json
[ -e fresh.json ] && fail "a refused fSpy import created a file"
run calibrate fspy fresh.json scene.fspy --extract-photo fresh.png
expect_rc 0 "an fSpy import with its photo"
cmp -s fresh.png embedded.png || fail "the extracted photo differs from the embedded one"

# ---- read-only outputs: kept unless --force ---------------------------------------------------
run render scene.json -o kept.exr
expect_rc 0 "an output to protect"
chmod 444 kept.exr
sha256sum kept.exr >kept.sha256
expect_refused "render onto a read-only output" "kept.exr: field '--output': is read-only: pass --force to replace it" \
    render scene.json -o kept.exr --passes 100000
sha256sum --quiet -c kept.sha256 || fail "the read-only output was replaced"
expect_refused "convert onto a read-only output" "is read-only" convert photo.exr kept.exr
cp scene.json locked.json && chmod 444 locked.json && sha256sum locked.json >locked.sha256
expect_refused "calibrate proxy on a read-only project" "locked.json: field 'project': is read-only" \
    calibrate proxy locked.json ground
sha256sum --quiet -c locked.sha256 || fail "the read-only project was replaced"
run render scene.json -o kept.exr --seed 9 --force
expect_rc 0 "render --force onto a read-only output"
sha256sum --quiet -c kept.sha256 >/dev/null 2>&1 && fail "--force did not replace the read-only output"
run calibrate proxy locked.json ground --force
expect_rc 0 "calibrate proxy --force on a read-only project"
mkdir shut && chmod 555 shut
if [ "$(id -u)" -eq 0 ]; then  # root may write anywhere: the folder's mode is the intent
    expect_refused "render into a read-only folder" "folder 'shut' is read-only: pass --force" \
        render scene.json -o shut/out.exr --passes 100000
    run render scene.json -o shut/out.exr --force
    expect_rc 0 "render --force into a read-only folder"
else
    expect_refused "render into a read-only folder" "folder 'shut' is not writable" \
        render scene.json -o shut/out.exr --passes 100000 --force
fi
chmod 755 shut
inputs_unchanged "the read-only cases"

# ---- names up to the file system's limit: a project that opens and saves, an output ----------
for length in 246 250 255; do
    name=$(head -c $((length - 5)) /dev/zero | tr '\0' 'n').json
    write_project "$name" "$BALL" "$FLOOR"
    run info "$name"
    expect_rc 0 "info on a project named with $length bytes"
    run calibrate proxy "$name" ground
    expect_rc 0 "saving a project named with $length bytes"
    run info "$name"
    expect_rc 0 "opening the saved project named with $length bytes"
    ls -a | grep -q '\.tmp-' && fail "a temporary file was left behind ($length bytes)"
done
long_out=$(head -c 251 /dev/zero | tr '\0' 'o').exr
run render scene.json -o "$long_out"
expect_rc 0 "render to an output named with 255 bytes"
refused "an output name beyond the limit" "its name is 256 bytes long, more than the 255" \
    render scene.json -o "o$long_out" --passes 100000

# ---- calibration results the loader refuses are not written ----------------------------------
cp scene.json tall.json
sha256sum tall.json >>inputs.sha256
refused "a box 1e38 high" "tall.json: field 'real[1]" \
    calibrate proxy tall.json box --points 20 40 44 40 40 30 24 30 --height 1e38
expect_stderr "the project would not load again, so it was not saved" "a box 1e38 high"

# ---- full file systems: found before the work ------------------------------------------------
if mkdir -p small inodes && mount -t tmpfs -o size=1m tmpfs small 2>/dev/null; then
    trap 'umount "$SCRATCH/small" "$SCRATCH/inodes" 2>/dev/null' EXIT
    run make-test-image plate.exr --size 256 256 --value 0.5 0.5 0.5
    write_project plate.json "$BALL" "$FLOOR" plate.exr
    sha256sum plate.exr plate.json >>inputs.sha256
    # 256 x 256 x 3 samples: 192 KiB at 8 bits fits in 1 MiB, 768 KiB of 32-bit floats with
    # the headers' room does not.
    run render plate.json -o small/fits.png --passes 1
    expect_rc 0 "an 8-bit TIFF-sized output that fits"
    rm -f small/fits.png
    refused "a 32-bit float TIFF beyond the free space" "small/out.tif: field '--output': the output needs up to" \
        render plate.json -o small/out.tif --bits 32 --passes 100000
    refused "a render shard beyond the free space" "small/part.dpp: field '--output': the output needs up to" \
        render plate.json --pass-range 0:100000 -o small/part.dpp
    refused "a float TIFF conversion beyond the free space" "has only" convert plate.exr small/out.tif --bits 32
    [ -z "$(ls -A small)" ] || fail "something was written to the full file system"
    if mount -t tmpfs -o size=1m,nr_inodes=4 tmpfs inodes 2>/dev/null; then
        for i in 1 2 3 4 5 6; do { : >"inodes/f$i"; } 2>/dev/null; done
        refused "no free inode" "inodes/out.png: field '--output': its folder 'inodes' is on a file system with no free inode" \
            render scene.json -o inodes/out.png --passes 100000
    fi
else
    echo "note: cannot mount a tmpfs here; the full file system cases are skipped"
fi
inputs_unchanged "the whole test"
echo "outputs_protected: all passed"

# Files meant to hang or exhaust the readers: zero-filled and misnamed images, headers declaring
# more than the file holds, FIFOs and devices named inside mesh files or given as shards, files
# of gigabytes (sparse), meshes over the limits. Each case ends within its time bound (a hang
# fails the test instead of blocking it), with its exit code and a message naming the file and
# what is wrong, and leaves every input as it was.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs

# The state of every input in the scratch folder: name, type, size and time, and the bytes of
# those under 64 MB (the sparse giants are compared by size and time alone).
inputs_state() {
    find . -path ./stdout.txt -prune -o -path ./stderr.txt -prune -o -path ./out -prune -o \
        -printf '%p %y %s %T@\n' | sort
    find . -path ./out -prune -o -type f -size -64M ! -name stdout.txt ! -name stderr.txt -exec md5sum {} + | sort
}

# within SECONDS CODE DESCRIPTION TEXT ARGS...: runs diffphoton under `timeout 10`; it must exit
# with CODE in at most SECONDS, its stderr holding TEXT (unless empty), every input unchanged. DP_ENV, when
# set, is put before the command (an environment variable for one case).
within() {
    local limit=$1 code=$2 what=$3 text=$4 before start end
    shift 4
    before=$(inputs_state)
    start=$(date +%s%N)
    env ${DP_ENV:-} timeout 10 "$DP" "$@" >stdout.txt 2>stderr.txt
    RC=$?
    end=$(date +%s%N)
    [ "$RC" -ne 124 ] || fail "$what: still running after 10 s"
    expect_rc "$code" "$what"
    [ -z "$text" ] || expect_stderr "$text" "$what"
    awk -v ns=$((end - start)) -v s="$limit" 'BEGIN { exit !(ns <= s * 1e9) }' ||
        fail "$what: took $(((end - start) / 1000000)) ms, more than $limit s"
    [ "$(inputs_state)" = "$before" ] || fail "$what: an input changed"
    grep -q "OpenCV(\|Assertion\|internal error" stderr.txt && fail "$what: a library's own text reached the user"
    return 0
}
mkdir out

# ---- Images: the format from the name, confirmed by the first bytes, decoded within bounds. ----
truncate -s 200M zeros.png
truncate -s 200M zeros.exr
write_project zeros_png.json "$BALL" "$FLOOR" zeros.png
write_project zeros_exr.json "$BALL" "$FLOOR" zeros.exr
within 3 2 "200 MB of zeros as a .png photo" "zeros.png: field 'photo.path': not a PNG file (its first bytes are 00 00 00 00" \
    info zeros_png.json
within 3 2 "200 MB of zeros as an .exr photo" "zeros.exr: field 'photo.path': not an OpenEXR file (its first bytes are 00" \
    render zeros_exr.json -o out/a.exr --passes 1
within 3 2 "200 MB of zeros to convert" "not a PNG file" convert zeros.png out/a.png
truncate -s 10G huge.exr
write_project huge_exr.json "$BALL" "$FLOOR" huge.exr
within 3 2 "10 GB (sparse) as the photo" "huge.exr: field 'photo.path': is 10.7 GB, more than the 8.6 GB an image may have" \
    info huge_exr.json
cp photo.exr misnamed.png
write_project misnamed.json "$BALL" "$FLOOR" misnamed.png
within 3 2 "an EXR named .png" "not a PNG file (its first bytes are 76 2f 31 01" info misnamed.json
expect_stderr "those of an OpenEXR file: name it .exr" "an EXR named .png: its right name"
run make-test-image real.png --size 8 8 --value 0.5 0.5 0.5
cp real.png picture.dat
write_project dat.json "$BALL" "$FLOOR" picture.dat
within 3 2 "a PNG named .dat" "unrecognised extension '.dat': images are read as .exr, .hdr, .png" info dat.json

# Headers declaring more than the file holds or the machine decodes: refused before decoding.
# A baseline JPEG's frame header (16000 x 16000, 4:2:0) in a kilobyte.
{ printf '\xff\xd8\xff\xc0\x00\x11\x08\x3e\x80\x3e\x80\x03\x01\x22\x00\x02\x11\x01\x03\x11\x01'
  head -c 1000 /dev/zero; printf '\xff\xd9'; } >bomb.jpg
write_project bomb_jpg.json "$BALL" "$FLOOR" bomb.jpg
within 3 2 "a 1 kB JPEG declaring 16000 x 16000" "bomb.jpg: field 'photo.path': " info bomb_jpg.json
expect_stderr "16000 x 16000 pixels" "the JPEG's declared size"
grep -q "more than the limit\|a complete JPEG of that size takes at least" stderr.txt || fail "the JPEG bomb's limit is not given"
# A TIFF whose first IFD (complete: one uncompressed grey strip) declares 100000 x 100000.
python3 - <<'PY'
import struct
def entry(tag, typ, value):
    return struct.pack("<HHI", tag, typ, 1) + (struct.pack("<HH", value, 0) if typ == 3 else struct.pack("<I", value))
tags = [(256, 4, 100000), (257, 4, 100000), (258, 3, 8), (259, 3, 1), (262, 3, 1), (273, 4, 130), (277, 3, 1),
        (278, 4, 100000), (279, 4, 1 << 31)]
ifd = struct.pack("<H", len(tags)) + b"".join(entry(*t) for t in tags) + struct.pack("<I", 0)
open("bomb.tif", "wb").write(b"II*\0" + struct.pack("<I", 8) + ifd)
PY
within 3 2 "a TIFF declaring 100000 x 100000" "the image is 100000 x 100000 pixels" convert bomb.tif out/a.png
expect_stderr "more than the limit" "the TIFF bomb's limit"
# One whose IFD lacks the tags a reader needs is refused as corrupt, from its header alone.
{ printf 'II*\x00\x08\x00\x00\x00\x02\x00'
  printf '\x00\x01\x04\x00\x01\x00\x00\x00\xa0\x86\x01\x00'
  printf '\x01\x01\x04\x00\x01\x00\x00\x00\xa0\x86\x01\x00\x00\x00\x00\x00'; } >broken.tif
within 3 2 "a TIFF with an incomplete IFD" "corrupt image: its header gives no valid size" convert broken.tif out/a.png

# ---- FIFOs, devices and folders, wherever they are named. ----
mkfifo pipe.bin pipe.mtl pipe.png pipe.dpp
printf 'mtllib pipe.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >fifo_mtl.obj
M='{"name": "m", "shape": {"type": "mesh", "path": "fifo_mtl.obj"}, "material": {"type": "diffuse"}}'
write_project fifo_mtl.json "$M" "$FLOOR"
within 5 2 "a FIFO as an OBJ's MTL" "pipe.mtl: field 'objects[0].shape.path': is a FIFO (named pipe), not a file mesh 'fifo_mtl.obj' reads" \
    info fifo_mtl.json
within 5 2 "a FIFO as an OBJ's MTL (render)" "is a FIFO" render fifo_mtl.json -o out/a.exr --passes 1
ln -s /dev/zero zero.mtl
printf 'mtllib zero.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >zero_mtl.obj
write_project zero_mtl.json "${M/fifo_mtl.obj/zero_mtl.obj}" "$FLOOR"
within 5 2 "/dev/zero as an OBJ's MTL" "zero.mtl: field 'objects[0].shape.path': is a character device" info zero_mtl.json
cat >fifo_bin.gltf <<'GLTF'
{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 0]}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "buffers": [{"uri": "pipe.bin", "byteLength": 36}]}
GLTF
write_project fifo_bin.json "${M/fifo_mtl.obj/fifo_bin.gltf}" "$FLOOR"
within 5 2 "a FIFO as a glTF's buffer" "pipe.bin: field 'objects[0].shape.path': is a FIFO (named pipe), not a file mesh 'fifo_bin.gltf' reads" \
    info fifo_bin.json
mkdir folder.bin
sed 's/pipe.bin/folder.bin/' fifo_bin.gltf >folder_bin.gltf
write_project folder_bin.json "${M/fifo_mtl.obj/folder_bin.gltf}" "$FLOOR"
within 5 2 "a folder as a glTF's buffer" "folder.bin: field 'objects[0].shape.path': is a folder" info folder_bin.json
# A texture a mesh's material names is refused like any input of its kind, by every command
# that reads the mesh's materials; only a missing or corrupt one leaves its material its colour
# (mesh_materials.sh).
printf 'newmtl t\nmap_Kd pipe.png\n' >tex.mtl
printf 'mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl t\nf 1/1 2/2 3/3\n' >fifo_tex.obj
TEX='{"name": "m", "shape": {"type": "mesh", "path": "fifo_tex.obj"}, "material_source": "file", "material": {"type": "diffuse"}}'
write_project fifo_tex.json "$TEX" "$FLOOR"
FIFO_TEX="pipe.png: field 'objects[0].shape.path': is a FIFO (named pipe), not a texture: material 't' of mesh 'fifo_tex.obj' names it"
within 5 2 "a FIFO as a texture an MTL names" "$FIFO_TEX" info fifo_tex.json
within 5 2 "a FIFO as a texture an MTL names (render)" "$FIFO_TEX" render fifo_tex.json -o out/a.exr --passes 1
within 5 2 "a FIFO as a texture an MTL names (shard)" "$FIFO_TEX" render fifo_tex.json --pass-range 0:1 -o out/a.dpp
within 5 2 "a FIFO as a texture an MTL names (reference)" "$FIFO_TEX" reference fifo_tex.json -o out/a.exr --spp 1
within 5 2 "a FIFO as a texture an MTL names (export)" "$FIFO_TEX" export blender fifo_tex.json -o out/a.py
cat >fifo_tex.gltf <<'GLTF'
{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
 "materials": [{"name": "g", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
 "textures": [{"source": 0}], "images": [{"uri": "pipe.png"}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 0]}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "buffers": [{"uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA",
              "byteLength": 36}]}
GLTF
write_project fifo_tex_gltf.json "${TEX/fifo_tex.obj/fifo_tex.gltf}" "$FLOOR"
FIFO_IMAGE="pipe.png: field 'objects[0].shape.path': is a FIFO (named pipe), not a texture: material 'g' of mesh 'fifo_tex.gltf' names it"
within 5 2 "a FIFO as a glTF's texture" "$FIFO_IMAGE" info fifo_tex_gltf.json
within 5 2 "a FIFO as a glTF's texture (render)" "$FIFO_IMAGE" render fifo_tex_gltf.json -o out/a.exr --passes 1
mkdir folder.png
sed 's/pipe.png/folder.png/' fifo_tex.gltf >folder_tex.gltf
write_project folder_tex.json "${TEX/fifo_tex.obj/folder_tex.gltf}" "$FLOOR"
within 5 2 "a folder as a glTF's texture" "folder.png: field 'objects[0].shape.path': is a folder, not a texture" \
    info folder_tex.json
ln -s /dev/zero zero.png
sed 's/pipe.png/zero.png/' tex.mtl >zero_tex.mtl
sed 's/tex.mtl/zero_tex.mtl/' fifo_tex.obj >zero_tex.obj
write_project zero_tex.json "${TEX/fifo_tex.obj/zero_tex.obj}" "$FLOOR"
within 5 2 "/dev/zero as a texture an MTL names" "zero.png: field 'objects[0].shape.path': is a character device, not a texture" \
    render zero_tex.json -o out/a.exr --passes 1
[ -z "$(ls out)" ] || fail "a refused texture let a command write"

# ---- Meshes: bytes and triangles bounded, out of memory said as such. ----
truncate -s 10G huge.obj
write_project huge_obj.json "${M/fifo_mtl.obj/huge.obj}" "$FLOOR"
within 3 2 "a 10 GB (sparse) OBJ" "huge.obj: field 'objects[0].shape.path': is 10.7 GB, more than the 4.3 GB a mesh file may have" \
    info huge_obj.json
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1000000000000\nproperty list uchar int vertex_indices\nend_header\n' >faces.ply
write_project faces.json "${M/fifo_mtl.obj/faces.ply}" "$FLOOR"
within 3 2 "a PLY declaring 10^12 faces" "faces.ply: field 'objects[0].shape.path': the mesh has 1000000000000 faces (declared in its header), more than the limit of" \
    info faces.json
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 3 4\nf 1 2 4\n' >four.obj
write_project four.json "${M/fifo_mtl.obj/four.obj}" "$FLOOR"
DP_ENV="DP_MAX_MESH_TRIANGLES=3" within 5 2 "4 triangles over a limit of 3" \
    "four.obj: field 'objects[0].shape.path': the mesh has 4 triangles, more than the limit of 3 triangles" info four.json
DP_ENV="DP_MAX_MESH_TRIANGLES=4" within 5 0 "4 triangles within a limit of 4" "" info four.json
expect_stdout "mesh 'four.obj' (4 triangles)" "4 triangles within a limit of 4"
# A binary STL of 8 million (zero) triangles under a 1.2 GB address space: Assimp's allocation
# fails, which is out of memory (exit 1), not a corrupt file.
truncate -s 400000084 big.stl
printf '\x00\x12\x7a\x00' | dd of=big.stl bs=1 seek=80 conv=notrunc status=none
write_project big_stl.json "${M/fifo_mtl.obj/big.stl}" "$FLOOR"
if (ulimit -v 1200000 && "$DP" --version) >/dev/null 2>&1; then
    before=$(inputs_state)
    (ulimit -v 1200000 && exec timeout 10 "$DP" info big_stl.json) >stdout.txt 2>stderr.txt
    RC=$?
    expect_rc 1 "a mesh beyond the memory there is"
    expect_stderr "error: out of memory allocating the mesh of '" "the mesh's out-of-memory message"
    expect_stderr "big.stl' (a 400.0 MB file); this machine has" "the mesh's out-of-memory figures"
    grep -q "cannot read mesh" stderr.txt && fail "out of memory was said as an unreadable mesh"
    [ "$(inputs_state)" = "$before" ] || fail "the STL changed"
else
    echo "note: this build cannot run under a memory limit (a sanitizer); the mesh out-of-memory case is skipped"
fi

# ---- Shards: `merge` refuses what is not a regular file of a shard's size, at once. ----
write_project scene.json "$BALL" "$FLOOR"
run render scene.json --pass-range 0:1 -o part.dpp
expect_rc 0 "a shard to merge"
within 3 2 "/dev/zero as a shard" "/dev/zero: is a character device, not a render shard" merge part.dpp /dev/zero -o out/m.exr
within 3 2 "a FIFO as a shard" "pipe.dpp: is a FIFO (named pipe), not a render shard" merge part.dpp pipe.dpp -o out/m.exr
mkdir folder.dpp
within 3 2 "a folder as a shard" "folder.dpp: is a folder, not a render shard" merge folder.dpp part.dpp -o out/m.exr
truncate -s 10G zeros.dpp
within 3 2 "10 GB of zeros as a shard" "zeros.dpp: " merge part.dpp zeros.dpp -o out/m.exr
grep -q "not a render shard\|a render shard may have" stderr.txt || fail "10 GB of zeros: no reason given"
cp part.dpp long.dpp
truncate -s 600M long.dpp
within 3 2 "a shard grown to 600 MB" "long.dpp: is 629145600 bytes, more than a shard of 64 x 48 pixels can be" \
    merge part.dpp long.dpp -o out/m.exr
[ -z "$(ls out)" ] || fail "a refused merge wrote something"

# ---- Messages: the mesh and the project file named, flags reported as typed, clicks explained. ----
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >tri.obj
GIANT='{"name": "giant", "shape": {"type": "mesh", "path": "tri.obj"},
        "transform": {"scale": [1e30, 1e30, 1e30]}, "material": {"type": "diffuse"}}'
write_project giant.json "$GIANT" "$FLOOR"
within 5 2 "a mesh scaled beyond 1e9 m" "giant.json: field 'objects[0]': 'giant' reaches beyond 1e9 m" info giant.json
expect_stderr "(mesh 'tri.obj')" "the far mesh's file"
within 5 2 "--photons beyond the machine" "field '--photons': 1000000000000 photons per pass need about" \
    render scene.json -o out/a.exr --photons 1000000000000
grep -q "render.photons_per_pass" stderr.txt && fail "--photons was reported under the project's field"
within 5 2 "--photons beyond the machine (shard)" "field '--photons'" render scene.json --pass-range 0:1 -o out/a.dpp --photons 1000000000000
PTS="--point 0,0,0,413.518,381.519 --point 0.6,0,0,549.410,412.026 --point 0.6,0,0.4,508.295,466.634 --point 0,0,0.4,360.722,428.922 --point 0.3,0.5,0.2,453.093,298.624"
# shellcheck disable=SC2086
within 5 2 "a click far off the photo" "field 'points': point 6 at (1e+09, 5) is far outside the 1000x750 photo" \
    calibrate points out/far.json --size 1000x750 $PTS --point 0.1,0.8,-0.3,1e9,5
[ "$(wc -l <stderr.txt)" -eq 1 ] || fail "a far-off click: more than one line"
# Clicks near the photo that no camera fits: OpenCV's solver gives up, said in one line.
within 5 2 "points no camera fits" "field 'points': no camera fits these points" calibrate points out/deg.json \
    --size 1000x750 --point 0,0,0,-999,-749 --point 1,0,0,1999,-749 --point 0,1,0,-999,1499 \
    --point 0,0,1,1999,1499 --point 1,1,1,0,0 --point 2,1,3,1000,750
[ "$(wc -l <stderr.txt)" -eq 1 ] || fail "points no camera fits: more than one line"
[ -z "$(ls out)" ] || fail "a refused calibration wrote a project"
echo "PASS"

# Render shards (render --pass-range) merged by `diffphoton merge` equal one render of all the
# passes bit for bit, whatever the split and thread counts; parts that cannot be merged exactly
# are refused with exit 2 and nothing is written.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs
GLASS='{"name": "glass", "shape": {"type": "sphere", "radius": 0.3},
        "transform": {"translation": [0.7, 0.3, 0.4]}, "material": {"type": "glass", "ior": 1.5}}'
write_project scene.json "$BALL, $GLASS" "$FLOOR"

same() {  # same A B WHAT: the two files are identical, byte for byte
    cmp -s "$1" "$2" || fail "$3: $1 and $2 differ"
}

# The single-process renders: one and two threads give the same bits.
run render scene.json -o single1.exr --passes 12 --adaptive off --threads 1
expect_rc 0 "single render, one thread"
run render scene.json -o single2.exr --passes 12 --adaptive off --threads 2
expect_rc 0 "single render, two threads"
same single1.exr single2.exr "single renders at one and two threads"
run render scene.json -o layers.exr --passes 12 --adaptive off --layers
expect_rc 0 "single render with layers"

# shards SPLITS...: renders each A:B alternately with one and two threads, into shard-A-B.dpp.
shards() {
    local threads=1 r
    PARTS=()
    for r in "$@"; do
        run render scene.json --pass-range "$r" -o "shard-${r/:/-}.dpp" --threads $threads
        expect_rc 0 "shard $r"
        expect_stdout "passes $r" "shard $r"
        PARTS+=("shard-${r/:/-}.dpp")
        threads=$((3 - threads))
    done
}

shards 0:12
run merge "${PARTS[@]}" -o merged1.exr
expect_rc 0 "merge of one shard"
expect_stdout "passes 12" "merge of one shard"
same single1.exr merged1.exr "one shard"

shards 0:5 5:12
run merge "${PARTS[1]}" "${PARTS[0]}" -o merged2.exr
expect_rc 0 "merge of two shards"
same single1.exr merged2.exr "two uneven shards, merged in reverse order"

shards 0:1 1:3 3:4 4:6 6:9 9:11 11:12
run merge "${PARTS[@]}" -o merged7.exr
expect_rc 0 "merge of seven shards"
same single1.exr merged7.exr "seven uneven shards"
run merge "${PARTS[@]}" -o merged7-layers.exr --layers
expect_rc 0 "merge with layers"
same layers.exr merged7-layers.exr "seven uneven shards, every layer"

# refused WHAT TEXT PARTS...: merge exits 2 naming the problem and writes nothing.
refused() {
    local what=$1 text=$2
    shift 2
    rm -f refused.exr
    expect_refused "$what" "$text" merge "$@" -o refused.exr
    [ -e refused.exr ] && fail "$what: an output was written"
    ls .refused*.exr >/dev/null 2>&1 && fail "$what: a temporary file was left"
    true
}

shards 4:12
refused "overlapping shards" "overlap" shard-0-5.dpp shard-4-12.dpp
refused "a gap" "are in no shard" shard-0-1.dpp shard-3-4.dpp
refused "missing first passes" "0:1 are in no shard" shard-1-3.dpp
run render scene.json --pass-range 5:12 -o seed7.dpp --seed 7
expect_rc 0 "shard with another seed"
refused "another seed" "seed 7" shard-0-5.dpp seed7.dpp
write_project other.json "$BALL" "$FLOOR"
run render other.json --pass-range 5:12 -o other.dpp
expect_rc 0 "shard of another project"
refused "another project" "belongs to another project" shard-0-5.dpp other.dpp

# The same project reached by other paths (its own folder, the photo by an absolute path, the
# probe through a symbolic link, as a shared folder mounted elsewhere or an unpacked bundle
# would give) merges with these shards bit for bit: files count by their contents.
mkdir -p elsewhere
ln -s "$PWD" linked
sed "s|\"photo.exr\"|\"$PWD/photo.exr\"|; s|\"probe.exr\"|\"../linked/probe.exr\"|" scene.json >elsewhere/scene.json
grep -q linked/probe.exr elsewhere/scene.json || fail "elsewhere/scene.json was not written"
run render elsewhere/scene.json --pass-range 5:12 -o spelt.dpp
expect_rc 0 "shard of the project spelt otherwise"
run merge shard-0-5.dpp spelt.dpp -o spelt.exr --project scene.json
expect_rc 0 "merge of shards from two spellings of one project"
same single1.exr spelt.exr "shards from two spellings of one project"
# ...and a changed input does not: the probe copied and brightened under the same name.
mkdir -p brighter
sed 's|"probe.exr"|"../brighter/probe.exr"|; s|"photo.exr"|"../photo.exr"|' scene.json >brighter/scene.json
run make-test-image brighter/probe.exr --size 32 16 --value 2 2 2
expect_rc 0 "make-test-image brighter probe"
run render brighter/scene.json --pass-range 5:12 -o brighter.dpp
expect_rc 0 "shard of the project with another probe"
refused "another probe under the same name" "was rendered from other files than" shard-0-5.dpp brighter.dpp
head -c 2000 shard-5-12.dpp > truncated.dpp
refused "a truncated shard" "truncated" shard-0-5.dpp truncated.dpp
cp shard-5-12.dpp damaged.dpp
printf 'X' | dd of=damaged.dpp bs=1 seek=900 conv=notrunc 2>/dev/null
refused "a damaged shard" "damaged" shard-0-5.dpp damaged.dpp
refused "a file that is no shard" "not a render shard" shard-0-5.dpp photo.exr

# A mesh's material file, buffer or texture changed between two shards makes them unmergeable,
# as the mesh itself would; unchanged, they merge.
run make-test-image wood.png --size 4 4 --value 0.6 0.4 0.2
expect_rc 0 "make-test-image texture"
printf 'newmtl wood\nKd 0.8 0.8 0.8\nmap_Kd wood.png\n' >cup.mtl
printf 'mtllib cup.mtl\nv -0.3 0 0\nv 0.3 0 0\nv 0 0.5 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl wood\nf 1/1 2/2 3/3\n' >cup.obj
printf '\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0' >tri.bin
cat >tri.gltf <<'GLTF'
{"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 0]}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "buffers": [{"uri": "tri.bin", "byteLength": 36}]}
GLTF
CUP='{"name": "cup", "shape": {"type": "mesh", "path": "cup.obj"}, "material_source": "file",
      "material": {"type": "diffuse"}, "transform": {"translation": [0, 0.01, 0.5]}}'
TRI='{"name": "tri", "shape": {"type": "mesh", "path": "tri.gltf"}, "material": {"type": "diffuse"},
      "transform": {"translation": [-0.5, 0.01, 0]}}'
write_project meshes.json "$CUP, $TRI" "$FLOOR"
# changed WHAT COMMAND...: renders passes 0:1, runs COMMAND (which changes a side file), renders
# passes 1:2; the shards are refused, and so is the first alone against the changed project.
changed() {
    local what=$1
    shift
    run render meshes.json --pass-range 0:1 -o side-a.dpp
    expect_rc 0 "$what: first shard"
    "$@"
    run render meshes.json --pass-range 1:2 -o side-b.dpp
    expect_rc 0 "$what: second shard"
    refused "$what between shards" "side-b.dpp: was rendered from other files than side-a.dpp" side-a.dpp side-b.dpp
    expect_stderr "a file a mesh names (material file, buffer, texture)" "$what: the files named"
    refused "$what since the shard" "meshes.json: its files (photo, probe, meshes and the files they name, textures) are not those" side-a.dpp
}
run render meshes.json --pass-range 0:1 -o side-0.dpp
expect_rc 0 "shard of a textured mesh"
run render meshes.json --pass-range 1:2 -o side-1.dpp
expect_rc 0 "second shard of a textured mesh"
run merge side-0.dpp side-1.dpp -o side.exr
expect_rc 0 "shards of unchanged side files merge"
changed "a texture changed" run make-test-image wood.png --size 4 4 --value 0.2 0.4 0.6
changed "a material file changed" sed -i 's/Kd 0.8/Kd 0.7/' cup.mtl
lower_corner() {  # the triangle's third corner from y = 1 to y = 0.5
    printf '\0\0\0\x3f' | dd of=tri.bin bs=1 seek=28 conv=notrunc status=none
}
changed "a glTF buffer changed" lower_corner

# What would make a shard's passes depend on passes it does not render is refused.
expect_refused "adaptive shard" "without adaptive sampling" render scene.json --pass-range 0:4 -o a.dpp --adaptive on
expect_refused "empty range" "is empty" render scene.json --pass-range 4:4 -o a.dpp
expect_refused "malformed range" "expected A:B" render scene.json --pass-range 4 -o a.dpp
expect_refused "shard to an image" ".dpp" render scene.json --pass-range 0:4 -o a.exr
expect_refused "shard with --passes" "excludes" render scene.json --pass-range 0:4 --passes 4 -o a.dpp
expect_refused "shard of another method" "differential" render scene.json --pass-range 0:4 --method standard -o a.dpp
[ -e a.dpp ] && fail "a refused shard was written"
echo "PASS"

# Inputs beyond sane ranges or resources: absurd camera intrinsics, albedo textures outside
# [0, 1], clipped photos, decompression bombs, outputs that cannot be written, out of memory,
# huge paths and times, images too small to calibrate from. Each is refused up front (exit 2)
# or warned about, with a message naming the field and the figures.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs

# write_opencv FILE FX FY CX CY: the scene of write_project seen by an opencv camera.
write_opencv() {
    cat >"$1" <<JSON
{"schema_version": 1, "photo": {"path": "photo.exr"}, "probe": {"path": "probe.exr"},
 "camera": {"model": "opencv", "fx": $2, "fy": $3, "cx": $4, "cy": $5,
            "rotation": [[1, 0, 0], [0, -1, 0], [0, 0, -1]], "translation": [0, 1.5, 4]},
 "real": [$FLOOR], "objects": [$BALL], "render": {"photons_per_pass": 2000, "passes": 1}}
JSON
}

# Camera intrinsics: refused where the scene is built, by info and render alike.
write_opencv camera_ok.json 60 60 31.5 23.5
run info camera_ok.json
expect_rc 0 "a sane opencv camera"
run render camera_ok.json -o camera_ok.exr
expect_rc 0 "rendering with a sane opencv camera"
write_opencv tiny_fx.json 1e-38 60 31.5 23.5
expect_refused "fx 1e-38 (info)" "field 'camera.fx'" info tiny_fx.json
expect_stderr "field of view of 180 degrees" "fx 1e-38: the figure"
expect_refused "fx 1e-38 (render)" "field 'camera.fx'" render tiny_fx.json -o out.exr
write_opencv huge_fy.json 60 1e38 31.5 23.5
expect_refused "fy 1e38" "field 'camera.fy'" info huge_fy.json
write_opencv far_cx.json 60 60 1e38 23.5
expect_refused "cx 1e38 (info)" "field 'camera.cx'" info far_cx.json
expect_stderr "at most 10 image sizes (640 pixels)" "cx 1e38: the limit"
expect_refused "cx 1e38 (render)" "field 'camera.cx'" render far_cx.json -o out.exr
expect_refused "cx 1e38 (reference)" "field 'camera.cx'" reference far_cx.json -o out.exr --spp 1
write_opencv far_cy.json 60 60 31.5 -5000
expect_refused "cy -5000" "field 'camera.cy'" info far_cy.json
write_project wide.json "$BALL" "$FLOOR"
sed -i 's/"vfov_deg": 40/"vfov_deg": 179.95/' wide.json
expect_refused "vfov 179.95" "field 'camera.vfov_deg'" info wide.json
write_project narrow.json "$BALL" "$FLOOR"
sed -i 's/"vfov_deg": 40/"vfov_deg": 1e-6/' narrow.json
expect_refused "vfov 1e-6" "must be within 0.001 to 179.9 degrees" render narrow.json -o out.exr

# Albedo textures outside [0, 1]: said, with the texture and the share of its texels.
TEX_FLOOR='{"name": "floor", "shape": {"type": "plane", "size": [10, 10]}, "albedo": {"texture": "tex.exr"}}'
write_project textured.json "$BALL" "$TEX_FLOOR"
for value in -5 1e30; do
    run make-test-image tex.exr --size 8 8 --value "$value" 0.5 0.5
    expect_rc 0 "make the texture"
    expect_warned "albedo $value (info)" "real[0].albedo.texture 'tex.exr': 100% of the texels are outside the albedo range [0, 1]" info textured.json
    expect_warned "albedo $value (render)" "of the texels are outside the albedo range" render textured.json -o out.exr --passes 1
done
run make-test-image tex.exr --size 8 8 --value 0.5 0.5 0.5 --nan 3
expect_warned "NaN in an albedo texture" "3 NaN/Inf values replaced by 0" info textured.json
run make-test-image tex.exr --size 8 8 --value 0.5 0.5 0.5
run info textured.json
expect_rc 0 "a clean texture"
grep -q "albedo range" stderr.txt && fail "a texture within [0, 1] was warned about"

# Clipped highlights: warned where a visible share of the photo is at the top code value.
run make-test-image clipped.png --size 64 48 --value 1 1 1
write_project clipped.json "$BALL" "$FLOOR" clipped.png
expect_warned "a clipped photo (info)" "100% of the photo's pixels are clipped" info clipped.json
expect_warned "a clipped photo (render)" "of the photo's pixels are clipped" render clipped.json -o out.exr --passes 1
run make-test-image unclipped.png --size 64 48 --value 0.5 0.5 0.5
write_project unclipped.json "$BALL" "$FLOOR" unclipped.png
run info unclipped.json
grep -q "clipped" stderr.txt && fail "a photo without clipping was warned about"

# Decompression bombs: a few bytes declaring 10^10 pixels, refused from the header.
python3 - <<'PY'
import struct, zlib
ihdr = b"IHDR" + struct.pack(">II", 100000, 100000) + bytes([8, 2, 0, 0, 0])
open("bomb.png", "wb").write(b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + ihdr + struct.pack(">I", zlib.crc32(ihdr)) +
                            struct.pack(">I", 16) + b"IDAT" + bytes(16))
PY
write_project bomb.json "$BALL" "$FLOOR" bomb.png
expect_refused "a PNG bomb as the photo" "100000 x 100000 pixels" info bomb.json
expect_stderr "of memory, more than the limit" "the PNG bomb's limit"
printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16384 +X 32768\n' >huge.hdr
write_project huge_probe.json "$BALL" "$FLOOR"
sed -i 's/"probe.exr"/"huge.hdr"/' huge_probe.json
expect_refused "a 32768 x 16384 probe" "field 'probe.path': the image is 32768 x 16384 pixels" render huge_probe.json -o out.exr
expect_refused "a PNG bomb to convert" "100000 x 100000 pixels" convert bomb.png out.png

# Outputs that cannot be written are refused before the render starts.
run make-test-image big.exr --size 1024 768 --value 0.5 0.5 0.5
write_project big.json "$BALL" "$FLOOR" big.exr
expect_refused "a missing output folder" "does not exist" render big.json -o missing/out.exr --passes 1
if mkdir -p full ro && mount -t tmpfs -o size=256k tmpfs full 2>/dev/null; then
    trap 'umount "$SCRATCH/full" "$SCRATCH/ro" 2>/dev/null' EXIT
    mount -t tmpfs -o ro,size=256k tmpfs ro
    start=$SECONDS
    expect_refused "a full disk (render)" "but its folder 'full' has only" render big.json -o full/out.exr --layers --passes 100000
    [ $((SECONDS - start)) -lt 30 ] || fail "the full disk was found only after rendering"
    # 1024 x 768 pixels of 20 float channels (the RGBA image and its layers) and the headers' room.
    expect_stderr "the output needs up to 63.8 MB" "the output's size"
    expect_refused "a full disk (reference)" "has only" reference big.json -o full/out.exr --spp 1
    expect_refused "a full disk (convert)" "has only" convert big.exr full/out.png
    expect_refused "a read-only folder" "is not writable" render big.json -o ro/out.exr --passes 100000
    [ -z "$(find full ro -mindepth 1)" ] || fail "something was written to the full or read-only folder"
else
    echo "note: cannot mount a tmpfs here; the full-disk and read-only cases are skipped"
fi

# Out of memory is said as such, with the machine's memory, never as a corrupt file.
if (ulimit -v 1500000 && "$DP" --version) >/dev/null 2>&1; then
    (ulimit -v 1500000 && exec "$DP" make-test-image oom.exr --size 16384 16384) >stdout.txt 2>stderr.txt
    RC=$?
    expect_rc 1 "an allocation beyond the memory limit"
    expect_stderr "error: out of memory allocating an image of 16384 x 16384 pixels (3.2 GB); this machine has" \
        "the out-of-memory message"
else
    echo "note: this build cannot run under a memory limit (a sanitizer); the out-of-memory case is skipped"
fi

# Long paths are shortened in messages: the start and the end stay, the message stays short.
LONG=$(head -c 1000000 /dev/zero | tr '\0' 'd')
printf '{"schema_version": 1, "photo": {"path": "%s/photo.exr"}, "probe": {"path": "probe.exr"},
 "camera": {"model": "lookat", "eye": [0, 1.5, 4], "target": [0, 0.4, 0]}}' "$LONG" >long_photo.json
expect_refused "a photo path of a million characters" "/photo.exr: field 'photo.path': cannot read it: File name too long" info long_photo.json
[ "$(wc -c <stderr.txt)" -lt 600 ] || fail "the message naming a 1 MB path is $(wc -c <stderr.txt) bytes"
LONG_OUT=$(head -c 100000 /dev/zero | tr '\0' 'o')
expect_refused "an output path of 100000 characters" "does not exist" render big.json -o "$LONG_OUT/out.exr" --passes 1
[ "$(wc -c <stderr.txt)" -lt 1000 ] || fail "the message naming a 100 kB path is $(wc -c <stderr.txt) bytes"

# Huge times: refused on the command line; a budget of 1e300 s in the file shows no negative ETA.
write_project scene.json "$BALL" "$FLOOR"
expect_refused "--time 1e300" "at most 31536000 (a year)" render scene.json -o out.exr --time 1e300
expect_refused "--time 0" "greater than 0" render scene.json -o out.exr --time 0
sed 's/"passes": 3/"time_budget_s": 1e300/' scene.json >forever.json
# Interrupted once its first pass is in (a sanitizer build takes seconds for it), so there is an output.
"$DP" render forever.json -o forever.exr >stdout.txt 2>stderr.txt &
pid=$!
for _ in $(seq 1 1200); do grep -q "^pass 1 " stderr.txt && break; sleep 0.1; done
sleep 0.5
kill -INT "$pid"
wait "$pid"
RC=$?
expect_rc 130 "a render to a budget of 1e300 s, interrupted"
expect_stderr "eta >30 years" "the ETA of a budget of 1e300 s"
grep -q "eta -" stderr.txt && fail "a negative ETA was shown"
run compare photo.exr forever.exr
expect_rc 0 "the interrupted render's output"

# Calibrating from images too small for the board: a message, not OpenCV's assertion text.
run make-test-image tiny.png --size 1 1 --value 0.5 0.5 0.5
expect_refused "a chessboard in a 1x1 image" "the image is 1x1 pixels: too small to show a board of 9x6 inner corners" \
    calibrate chessboard tiny_calib.json tiny.png --square 0.03
grep -q "Assertion\|OpenCV(" stderr.txt && fail "OpenCV's own text reached the user"
run make-test-image strip.png --size 400 3 --value 0.5 0.5 0.5
expect_refused "a chessboard in a 400x3 strip" "too small to show a board" calibrate chessboard tiny_calib.json strip.png --square 0.03
echo "PASS"

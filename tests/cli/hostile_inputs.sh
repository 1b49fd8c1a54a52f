# Inputs meant to hurt: special files, sizes beyond float's reach, overwritten outputs. Each
# ends with exit code 2 and a message that names the problem; none crashes, hangs or destroys.
source "$(dirname "$0")/testlib.bash" "$@"
make_inputs

# A FIFO would block a reader forever; a device would feed it without end.
mkfifo pipe.json pipe.exr
expect_refused "a FIFO as the project" "is a FIFO" info pipe.json
write_project fifo_photo.json "$BALL" "$FLOOR" pipe.exr
expect_refused "a FIFO as the photo" "is a FIFO" render fifo_photo.json -o out.exr --passes 1
expect_refused "/dev/zero as the project" "is a character device" info /dev/zero
mkdir folder.obj
MESH_IN_FOLDER='{"name": "m", "shape": {"type": "mesh", "path": "folder.obj"}, "material": {"type": "diffuse"}}'
write_project folder_mesh.json "$MESH_IN_FOLDER" "$FLOOR"
expect_refused "a folder as a mesh" "is a folder" render folder_mesh.json -o out.exr --passes 1
head -c 20000000 /dev/zero | tr '\0' ' ' >huge.json
expect_refused "a 20 MB project file" "more than the" info huge.json

# Sizes whose ray arithmetic would overflow float: refused before any ray, the object named.
HUGE_BALL='{"name": "moon", "shape": {"type": "sphere", "radius": 1e20},
            "material": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}}'
write_project huge_ball.json "$HUGE_BALL" "$FLOOR"
expect_refused "a sphere of radius 1e20 (render)" "'moon' reaches beyond" render huge_ball.json -o out.exr --passes 1
expect_refused "a sphere of radius 1e20 (info)" "objects[0]" info huge_ball.json
FAR_BALL='{"name": "far", "shape": {"type": "sphere", "radius": 0.5},
           "transform": {"translation": [3e38, 0, 0]},
           "material": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}}'
write_project far_ball.json "$FAR_BALL" "$FLOOR"
expect_refused "a sphere at x = 3e38" "'far' reaches beyond" render far_ball.json -o out.exr --passes 1
printf 'v 0 0 0\nv 1e30 0 0\nv 0 1 0\nf 1 2 3\n' >far.obj
FAR_MESH='{"name": "shard", "shape": {"type": "mesh", "path": "far.obj"}, "material": {"type": "diffuse"}}'
write_project far_mesh.json "$FAR_MESH" "$FLOOR"
expect_refused "an OBJ vertex at 1e30" "objects[0].shape.path" render far_mesh.json -o out.exr --passes 1
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >tri.obj
SCALED_MESH='{"name": "giant", "shape": {"type": "mesh", "path": "tri.obj"},
              "transform": {"scale": [1e30, 1e30, 1e30]}, "material": {"type": "diffuse"}}'
write_project scaled_mesh.json "$SCALED_MESH" "$FLOOR"
expect_refused "a mesh scaled by 1e30" "'giant' reaches beyond" render scaled_mesh.json -o out.exr --passes 1

# Settings beyond the machine or the scene: refused up front, with the figure.
cat >many_photons.json <<JSON
{"schema_version": 1, "photo": {"path": "photo.exr"}, "probe": {"path": "probe.exr"},
 "camera": {"model": "lookat", "eye": [0, 1.5, 4], "target": [0, 0.4, 0], "vfov_deg": 40},
 "real": [$FLOOR], "objects": [$BALL], "render": {"photons_per_pass": 1000000000000, "passes": 1}}
JSON
expect_refused "1e12 photons per pass (info)" "of memory" info many_photons.json
expect_refused "1e12 photons per pass (render)" "of memory" render many_photons.json -o out.exr
for radius in 1e30 1e-30; do
    write_project radius.json "$BALL" "$FLOOR"
    sed -i "s/\"passes\": 3/\"passes\": 1, \"initial_radius\": $radius/" radius.json
    expect_refused "initial_radius $radius" "render.initial_radius" render radius.json -o out.exr
done
write_project scene.json "$BALL" "$FLOOR"
run render scene.json -o threads.exr --passes 1 --threads 100000
expect_rc 0 "--threads 100000"
expect_stderr "cores of this machine" "the clamped thread count"

# An output that is one of the render's own inputs is refused, through a symlink too.
cp photo.exr photo-before.exr
expect_refused "the photo as the output" "photo.path" render scene.json -o photo.exr --passes 1
ln -s photo.exr link.exr
expect_refused "a symlink to the photo as the output" "photo.path" render scene.json -o link.exr --passes 1
write_project project.exr "$BALL" "$FLOOR"  # a project file may have any name
expect_refused "the project file as the output" "project file itself" render project.exr -o project.exr --passes 1
compare photo-before.exr photo.exr
is_zero "$MAX_DIFF" || fail "the photo was changed"
run convert photo.exr photo.exr
expect_rc 2 "convert onto its input"
run make-test-image in.png --size 8 8
expect_refused "convert onto its own input" "input image itself" convert in.png in.png

# Outputs are written whole or not at all: two renders to one path leave one readable file.
"$DP" render scene.json -o same.exr --passes 2 --seed 1 2>/dev/null &
"$DP" render scene.json -o same.exr --passes 2 --seed 2 2>/dev/null
wait
compare photo.exr same.exr
ls -a | grep -q '\.tmp-' && fail "a temporary output file was left behind"
# SIGKILL at random moments of renders that write a large layered EXR: the output is always the
# previous complete file or the new complete one (a killed writer may leave its hidden
# temporary file, never a broken output).
run make-test-image big.exr --size 1024 768 --value 0.5 0.5 0.5
write_project big.json "$BALL" "$FLOOR" big.exr
run render big.json -o kill.exr --passes 1 --layers
expect_rc 0 "the first complete output"
# 20 trials each; 8 in a sanitizer build (it cannot run under a memory limit), whose renders
# and writes are several times slower and would otherwise hold CI for minutes.
TRIALS=20
(ulimit -v 1500000 && "$DP" --version) >/dev/null 2>&1 || TRIALS=8
for trial in $(seq 1 "$TRIALS"); do
    "$DP" render big.json -o kill.exr --passes 1 --layers --seed "$trial" 2>/dev/null &
    pid=$!
    sleep "0.$((RANDOM % 10))$((RANDOM % 10))"
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    run compare big.exr kill.exr
    expect_rc 0 "the output after SIGKILL in trial $trial"
done
# Double Ctrl-C: the first, once a pass is done, asks the render to stop and write it; the
# second, a random moment later, ends the process at once, often in the middle of that write.
# The output is always a complete file (the previous one or the new one) and the second signal
# takes the half-written temporary file with it.
rm -f .kill.tmp-*  # what the SIGKILL trials above may leave
run make-test-image mid.exr --size 512 384 --value 0.5 0.5 0.5
write_project mid.json "$BALL" "$FLOOR" mid.exr
sed -i 's/"photons_per_pass": 20000/"photons_per_pass": 2000/' mid.json
run render mid.json -o kill.exr --passes 1 --layers
expect_rc 0 "the first complete output of the double SIGINT trials"
cut_short=0
for trial in $(seq 1 "$TRIALS"); do
    "$DP" render mid.json -o kill.exr --time 60 --layers --seed "$trial" >stdout.txt 2>stderr.txt &
    pid=$!
    for _ in $(seq 1 600); do grep -q "^pass 1 " stderr.txt && break; sleep 0.05; done
    kill -INT "$pid" 2>/dev/null || true
    sleep "0.$((RANDOM % 10))$((RANDOM % 10))"
    kill -INT "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null
    grep -q "^wrote" stdout.txt || cut_short=$((cut_short + 1))
    run compare mid.exr kill.exr
    expect_rc 0 "the output after a double SIGINT in trial $trial"
    ls -a | grep -q '\.tmp-' && fail "a temporary output file was left after a double SIGINT in trial $trial"
done
echo "double SIGINT: $cut_short of $TRIALS renders ended by the second signal before their output was written"
echo "PASS"

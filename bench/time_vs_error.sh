#!/usr/bin/env bash
# Time against error, one command: builds diffphoton, makes the benchmark scenes and their
# truths (once; tens of minutes), runs every method on every scene, plots and summarises.
# Blender Cycles (method cycles, Debian's Blender 3.4; DP_BLENDER=PATH for another; methods
# cycles5 and cycles5-artist, Blender 5 from .deps/bpy5 or DP_BPY5_PYTHON=PATH) runs under the
# standard methods' budget; without a Blender the bench prints one line per method and skips it.
# SET=paper (the default) races the paper's scenes; SET=materials the materials set (rough metal,
# frosted glass, a textured glTF object, an area lamp by a wall, a polished floor), whose
# summary, plots and rows go to their own places (OUT defaults to out/bench/materials-error).
#   BUILD=build OUT=out/bench/error DIFF_S=30 STD_S=120 bash bench/time_vs_error.sh [--update-docs]
#   SET=materials bash bench/time_vs_error.sh [--update-docs]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
SET=${SET:-paper}
case "$SET" in
  paper)
    ORDER=(shadow_hard shadow_soft caustic mirrors bleeding five_objects big_proxy noop)
    OUT=${OUT:-out/bench/error}
    TAG=time-vs-error      # the markers, images folder and rows file of docs/
    ;;
  materials)
    ORDER=(gold_ball frosted_glass textured_gltf lamp_wall polished_floor)
    OUT=${OUT:-out/bench/materials-error}
    TAG=materials-vs-error
    ;;
  *) echo "SET must be paper or materials (got '$SET')" >&2; exit 2 ;;
esac
SCENES=${SCENES:-out/bench/scenes}
DIFF_S=${DIFF_S:-30}
STD_S=${STD_S:-120}
METHODS=${METHODS:-differential,differential-photons,differential-random,standard-correlated,cycles,cycles5,cycles5-artist}

commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
git diff --quiet HEAD 2>/dev/null || commit="$commit with uncommitted changes"
bash scripts/install-deps.sh --bench
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build "$BUILD" --target diffphoton
only=(); for s in "${ORDER[@]}"; do only+=(--only "$s"); done  # the scenes this run measures
/usr/bin/python3 bench/scenes/make_scenes.py --diffphoton "$BUILD/app/diffphoton" --out "$SCENES" "${only[@]}"
mkdir -p "$OUT"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
"$BUILD/app/diffphoton" bench "${ORDER[@]/#/$SCENES/}" -o "$OUT/rows.json" --images "$OUT/images" \
  --methods "$METHODS" --max-seconds-differential "$DIFF_S" --max-seconds-standard "$STD_S"
pairs_arg=()
if [ "$SET" = paper ]; then  # the cost of a big real proxy: alternating runs of the two scenes
  pairs=()
  for i in 1 2 3 4 5; do pairs+=("$SCENES/shadow_hard" "$SCENES/big_proxy"); done
  "$BUILD/app/diffphoton" bench "${pairs[@]}" -o "$OUT/pairs.json" --methods differential --max-seconds-differential 3
  pairs_arg=(--pairs "$OUT/pairs.json")
fi
/usr/bin/python3 bench/plot_time_vs_error.py "$OUT/rows.json" --out "$OUT" --image-prefix "images/$TAG/" \
  "${pairs_arg[@]}" \
  --note "$(nproc) cores; load average (1, 5, 15 min) $load_before before the run, $(cut -d' ' -f1-3 /proc/loadavg) after; built from commit $commit."
if [ "${1:-}" = "--update-docs" ]; then
  # The summary replaces the set's marked region of docs/benchmarks.md (<!-- $TAG:begin -->
  # to <!-- $TAG:end -->); plots and last images go beside it, the rows to docs/$TAG-rows.json.
  mkdir -p "docs/images/$TAG"
  cp "$OUT"/*.png "docs/images/$TAG/"
  for f in "$OUT"/images/*.png; do cp "$f" "docs/images/$TAG/render-$(basename "$f")"; done
  cp "$OUT/rows.json" "docs/$TAG-rows.json"
  /usr/bin/python3 - "$OUT/summary.md" docs/benchmarks.md "$TAG" <<'PY'
import re, sys
summary, doc, tag = open(sys.argv[1]).read(), open(sys.argv[2]).read(), sys.argv[3]
begin, end = f"<!-- {tag}:begin -->", f"<!-- {tag}:end -->"
assert begin in doc and end in doc, f"docs/benchmarks.md lacks the {tag} markers"
head, rest = doc.split(begin, 1)
open(sys.argv[2], "w").write(head + begin + "\n" + summary + end + rest.split(end, 1)[1])
PY
  echo "updated docs/benchmarks.md and docs/images/$TAG/"
fi

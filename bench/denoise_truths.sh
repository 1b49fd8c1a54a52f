#!/usr/bin/env bash
# Raw against denoised error on the time-against-error benchmark's scenes and truths
# (bench/time_vs_error.sh makes them): our method for a few seconds a scene, measured at the
# usual pass counts, each image also denoised at final quality. Prints a table of the relative
# RMSE over the changed pixels (objects and real surfaces apart) at the first measurements from 4, 16 and 64 passes.
#   BUILD=build SCENES=out/bench/scenes SECONDS_EACH=20 bash bench/denoise_truths.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
SCENES=${SCENES:-out/bench/scenes}
OUT=${OUT:-out/bench/denoise}
SECONDS_EACH=${SECONDS_EACH:-20}
ORDER=(shadow_hard shadow_soft caustic mirrors bleeding five_objects big_proxy)
mkdir -p "$OUT"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg); built from $(git rev-parse --short HEAD)"
dirs=(); for s in "${ORDER[@]}"; do [ -s "$SCENES/$s/truth.json" ] && dirs+=("$SCENES/$s"); done
"$BUILD/app/diffphoton" bench "${dirs[@]}" -o "$OUT/rows.json" --methods differential \
  --max-seconds-differential "$SECONDS_EACH" --denoise > "$OUT/log.txt"
/usr/bin/python3 - "$OUT/rows.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
truth = {s["scene"]: s for s in doc["scenes"]}
print("| scene | truth noise | passes | raw, changed | denoised, changed | raw / denoised | objects raw / denoised | real raw / denoised | denoise s |")
print("|---|---|---|---|---|---|---|---|---|")
for scene in truth:
    rows = [r for r in doc["rows"] if r["scene"] == scene and "rel_rmse_changed_denoised" in r]
    for want in (4, 16, 64):
        near = [r for r in rows if r["passes"] >= want]  # measured at passes spaced by sqrt(2)
        if not near: continue
        r = min(near, key=lambda r: r["passes"])
        raw, den = r["rel_rmse_changed"], r["rel_rmse_changed_denoised"]
        print(f"| {scene} | {100 * truth[scene]['truth_rel_rmse_changed']:.2f}% | {r['passes']} | {100 * raw:.2f}% | {100 * den:.2f}% "
              f"| {raw / den:.2f}x | {100 * r['rel_rmse_objects']:.2f}% / {100 * r['rel_rmse_objects_denoised']:.2f}% "
              f"| {100 * r['rel_rmse_real_changed']:.2f}% / {100 * r['rel_rmse_real_changed_denoised']:.2f}% | {r['denoise_seconds']:.2f} |")
PY

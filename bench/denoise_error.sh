#!/usr/bin/env bash
# Error of raw and denoised renders of the sample against a long render of it (the truth), over
# the pixels the objects change (docs/method-notes.md, "Denoising").
# Usage: bash bench/denoise_error.sh [BUILD_DIR] [OUT_DIR]   (TRUTH_PASSES, PASSES to change)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
out="${2:-$root/out/denoise}"
dp="$build/app/diffphoton"
truth_passes="${TRUTH_PASSES:-128}"
passes="${PASSES:-2 8 32}"
project="$root/resources/sample/sample.json"
mkdir -p "$out"
[ -x "$dp" ] || { echo "build $dp first (cmake --build $build --target diffphoton)" >&2; exit 1; }

echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
if [ ! -s "$out/truth-$truth_passes.exr" ]; then
  "$dp" render "$project" -o "$out/truth-$truth_passes.exr" --layers --passes "$truth_passes" --seed 1000 \
    2>/dev/null | tail -1
fi
truth="$out/truth-$truth_passes.exr"
photo="$root/resources/sample/photo.exr"
echo "passes  render_s  denoise_s  pixels   raw_rmse  denoised_rmse  ratio   (over the truth's changed pixels)"
for p in $passes; do
  line=$("$dp" render "$project" -o "$out/p$p.exr" --layers --denoise --passes "$p" 2>/dev/null | tail -1)
  secs=$(echo "$line" | awk '{for (i = 1; i < NF; ++i) if ($i == "seconds") { print $(i + 1); exit }}')
  dsecs=$(echo "$line" | awk '{for (i = 1; i < NF; ++i) if ($i == "denoise") { print $(i + 2); exit }}')
  for only in "" real objects; do
    raw=$("$dp" compare "$out/p$p.exr" "$truth" --changed "$photo" ${only:+--only $only} | awk '{print $2}')
    den=$("$dp" compare "$out/p$p.exr" "$truth" --changed "$photo" ${only:+--only $only} --layer-a denoised |
      awk '{print $2}')
    px=$("$dp" compare "$truth" "$truth" --changed "$photo" ${only:+--only $only} | awk '{split($6, a, "/"); print a[2]}')
    awk -v p="$p" -v s="$secs" -v w="$dsecs" -v x="$px" -v r="$raw" -v d="$den" -v o="${only:-all}" \
      'BEGIN { printf "%6s  %8s  %9s  %6s %-7s  %8.5f  %13.5f  %5.2fx\n", p, s, w, x, o, r, d, r / d }'
  done

done

#!/usr/bin/env bash
# The cost of sharding a render (docs/farm.md, "Overhead of sharding"): PASSES passes of a
# project in one process against the same passes as shards of 8, 64 and 512 passes, each shard
# its own `diffphoton render --pass-range` process run one after the other on this machine,
# plus `diffphoton merge`. Every merge is checked to be the single render's file, byte for byte.
# Usage: bench/shard_overhead.sh DIFFPHOTON PROJECT [PASSES] [PHOTONS] [SHARD...]
set -euo pipefail
dp=$(realpath "$1")
project=$(realpath "$2")
passes=${3:-512}
photons=${4:-20000}
shift $(( $# < 4 ? $# : 4 ))
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(8 64 512)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }
calc() { awk "BEGIN { print $1 }"; }

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
t0=$(now)
"$dp" render "$project" --passes "$passes" --photons "$photons" --adaptive off -o "$work/single.exr" >/dev/null 2>&1
t1=$(now)
single=$(calc "$t1 - $t0")
printf "one process: %d passes in %.2f s\n" "$passes" "$single"
for size in "${sizes[@]}"; do
  rm -f "$work"/*.dpp
  t0=$(now)
  for ((b = 0; b < passes; b += size)); do
    e=$(( b + size < passes ? b + size : passes ))
    "$dp" render "$project" --pass-range "$b:$e" --photons "$photons" -o "$work/part-$b.dpp" >/dev/null 2>&1
  done
  t1=$(now)
  "$dp" merge "$work"/*.dpp -o "$work/merged.exr" >/dev/null
  t2=$(now)
  cmp -s "$work/single.exr" "$work/merged.exr" || { echo "shards of $size: merge differs from the single render"; exit 1; }
  shards=$(( (passes + size - 1) / size ))
  printf "shards of %d: %d shards %.2f s + merge %.2f s = %.2f s, overhead %+.1f%% (%.3f s a shard); identical\n" \
    "$size" "$shards" "$(calc "$t1 - $t0")" "$(calc "$t2 - $t1")" "$(calc "$t2 - $t0")" \
    "$(calc "100 * ($t2 - $t0 - $single) / $single")" "$(calc "($t2 - $t0 - $single) / $shards")"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

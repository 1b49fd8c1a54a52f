#!/usr/bin/env bash
# The cost of sharding a render (docs/farm.md, "Overhead of sharding"): PASSES passes of a
# project in one process against the same passes as shards of each SHARD size, each shard its
# own `diffphoton render --pass-range` process run one after the other on this machine, plus
# `diffphoton merge`. The methods alternate within each of ROUNDS rounds (one process, then each
# shard size, then again), so that a change in the machine's load falls on all of them; the
# ratio to the one-process time is taken within a round. Every merge is checked to be the single
# render's file, byte for byte.
# Usage: bench/shard_overhead.sh DIFFPHOTON PROJECT [PASSES] [PHOTONS] [ROUNDS] [SHARD...]
set -euo pipefail
dp=$(realpath "$1")
project=$(realpath "$2")
passes=${3:-512}
photons=${4:-20000}
rounds=${5:-3}
shift $(( $# < 5 ? $# : 5 ))
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(8 64 512)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }
calc() { awk "BEGIN { print $1 }"; }

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
declare -A ratios
for ((round = 1; round <= rounds; ++round)); do
  t0=$(now)
  "$dp" render "$project" --passes "$passes" --photons "$photons" --adaptive off -o "$work/single.exr" >/dev/null 2>&1
  single=$(calc "$(now) - $t0")
  printf "round %d: one process: %d passes in %.2f s (load %s)\n" "$round" "$passes" "$single" \
    "$(cut -d' ' -f1 /proc/loadavg)"
  for size in "${sizes[@]}"; do
    rm -f "$work"/*.dpp
    t0=$(now)
    for ((b = 0; b < passes; b += size)); do
      e=$(( b + size < passes ? b + size : passes ))
      "$dp" render "$project" --pass-range "$b:$e" --photons "$photons" -o "$work/part-$b.dpp" >/dev/null 2>&1
    done
    t1=$(now)
    "$dp" merge "$work"/*.dpp -o "$work/merged.exr" >/dev/null 2>"$work/merge.err" || { cat "$work/merge.err"; exit 1; }
    t2=$(now)
    cmp -s "$work/single.exr" "$work/merged.exr" || { echo "shards of $size: merge differs from the single render"; exit 1; }
    shards=$(( (passes + size - 1) / size ))
    ratio=$(calc "($t2 - $t0) / $single")
    ratios[$size]="${ratios[$size]:-} $ratio"
    printf "round %d: shards of %d: %d shards %.2f s + merge %.2f s = %.2f s, x%.3f of one process (%+.3f s a shard); identical\n" \
      "$round" "$size" "$shards" "$(calc "$t1 - $t0")" "$(calc "$t2 - $t1")" "$(calc "$t2 - $t0")" "$ratio" \
      "$(calc "($t2 - $t0 - $single) / $shards")"
  done
done
for size in "${sizes[@]}"; do
  echo "shards of $size: time against one process, per round:${ratios[$size]}; median $(tr ' ' '\n' <<<"${ratios[$size]}" | sed '/^$/d' | sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }')"
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

#!/usr/bin/env bash
# Builds dp_bench, runs every benchmark into out/bench/results.json and prints a summary.
# Usage: [BUILD=build-dir] bash bench/run_benchmarks.sh [extra Google Benchmark flags]
# e.g. bash bench/run_benchmarks.sh --benchmark_filter=1080p
set -euo pipefail

cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
OUT_DIR=out/bench
RESULTS=$OUT_DIR/results.json

if [[ ! -f $BUILD/build.ninja && ! -f $BUILD/Makefile ]]; then
    cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
fi
build_type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$BUILD/CMakeCache.txt")
if [[ $build_type != Release && $build_type != RelWithDebInfo ]]; then
    echo "error: $BUILD is a '$build_type' build; benchmarks need Release or RelWithDebInfo" >&2
    exit 1
fi
cmake --build "$BUILD" --target dp_bench -j "$(nproc)"

mkdir -p "$OUT_DIR"
echo "machine: $(nproc) cores, $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1)," \
     "load average $(cut -d' ' -f1-3 /proc/loadavg)"
# JSON on stdout too (kept next to the results); progress would interleave with it otherwise.
"$BUILD/bench/dp_bench" --benchmark_format=json --benchmark_out="$RESULTS" "$@" \
    > "$OUT_DIR/stdout.json"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - "$RESULTS" <<'PY'
import json
import sys

doc = json.load(open(sys.argv[1]))
runs = {}
for b in doc["benchmarks"]:
    # Repeated benchmarks: keep the median; single runs: the run itself.
    if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
        continue
    runs[b["run_name"]] = b

def find(prefix, threads=None):
    for name, b in runs.items():
        if name.split("/")[0] != prefix:
            continue
        if threads is None or f"/threads:{threads}/" in name + "/":
            return b
    return None

def seconds(b):
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
    return b["real_time"] * scale

def fmt(v, unit=""):
    if v is None:
        return "-"
    for div, suffix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if abs(v) >= div:
            return f"{v / div:.2f} {suffix}{unit}"
    return f"{v:.3g} {unit}".rstrip()

rows = []
for t, label in ((0, "all cores"), (1, "1 thread")):
    e, p = find("BM_EmbreeRaysSampleScene", t), find("BM_PhotonTracingSampleScene", t)
    er = e and e["rays_per_s"]
    pr = p and p["rays_per_s"]
    rows.append((f"raw Embree rays/s ({label})", fmt(er, "rays/s")))
    rows.append((f"photon tracer photons/s ({label})", fmt(p and p["photons_per_s"], "photons/s")))
    rows.append((f"photon tracer Embree queries/s ({label})", fmt(pr, "rays/s")))
    ratio = pr / er if er and pr else None
    rows.append((f"tracer / raw rays/s ({label}, target >= 50%)",
                 f"{ratio:.1%}" if ratio is not None else "-"))
for t, label in ((0, "all cores"), (1, "1 thread")):
    b = find("BM_PhotonMapBuild", t)
    if b:
        rows.append((f"photon map build ({label})",
                     f"{seconds(b) * 1e3:.1f} ms for {b['photons']:.0f} photons"))
for t, label in ((0, "all cores"), (1, "1 thread")):
    g = find("BM_Gather", t)
    rows.append((f"gathers/s ({label})", fmt(g and g["gathers_per_s"], "gathers/s")))
p = find("BM_OnePass1080p")
if p:
    s, mem = seconds(p), p["peak_rss_bytes"]
    rows.append(("1080p pass, 1M photons (median, target < 1 s)",
                 f"{s:.3f} s  [{'met' if s < 1 else 'NOT met'}]"))
    rows.append(("peak resident memory (target < 1 GiB)",
                 f"{mem / 2**20:.0f} MiB  [{'met' if mem < 2**30 else 'NOT met'}]"))
    rows.append(("skipped-pixel fraction", f"{p['skipped_fraction']:.3f}"))
ph = find("BM_OnePass1080pPhases")
if ph:
    for key, label in (("trace_s", "photon tracing"), ("build_s", "map builds"),
                       ("shade_virtual_s", "shading: pixels near virtual objects"),
                       ("shade_real_s", "shading: real pixels the map reaches"),
                       ("accumulate_s", "accumulation"),
                       ("skip_test_s", "  (of shading: the skip test alone)")):
        rows.append((f"  phase: {label}", f"{ph[key]:.3f} s"))

width = max(len(r[0]) for r in rows)
print(f"\n{'figure'.ljust(width)}  value")
print(f"{'-' * width}  {'-' * 32}")
for k, v in rows:
    print(f"{k.ljust(width)}  {v}")
print(f"\nfull results: {sys.argv[1]}")
PY

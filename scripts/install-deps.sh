#!/usr/bin/env bash
# Installs the Debian 12 packages diffphoton needs. Idempotent: does nothing when all are present.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libglm-dev libopenexr-dev libopencv-dev libassimp-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libexiv2-dev  # EXIF focal length for camera calibration
  libopenimageio-dev libopencolorio-dev  # image files (layers, windows, ICC, metadata) and view transforms
  liblcms2-dev  # Little CMS: the photos' embedded ICC profiles
  openimageio-tools  # OpenImageIO's CMake targets name its command-line tools (/usr/bin/iconvert...)
  opencv-doc    # OpenCV's chessboard photographs, used by the calibration tests
  blender-data  # the CC0 light probes the sample project and benchmarks use
  qt6-base-dev  # the studio (Widgets, Test; pulls libqt6gui6 with the offscreen and xcb platforms)
  xvfb xauth    # xvfb-run for the studio's screenshot test and documentation screenshots
  iproute2      # ip: the farm's test across network namespaces (farm/tests/test_namespaces.py)
  clang libclang-rt-14-dev  # the sanitizer build and the libFuzzer targets (tests/fuzz)
)
# `--bench`: also what the benchmark plots need, Blender 3.4 for the cycles method and the venv
# module for Blender 5 (below).
bench=0
[ "${1:-}" = "--bench" ] && bench=1 && packages+=(python3-matplotlib blender python3-venv)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "install-deps: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Intel Open Image Denoise for `render --denoise`: Debian 12 has no package, so the prebuilt CPU
# libraries come from the pinned pyoidn wheel into .deps/oidn/lib (loaded at run time by
# core/image/denoise.cpp; the wheel's own libtbb.so.12 is newer than Debian's and is kept).
oidn_version=2.3.0
oidn_dir="$(cd "$(dirname "$0")/.." && pwd)/.deps/oidn"
if [ -f "$oidn_dir/lib/libOpenImageDenoise.so.2" ] && [ "$(cat "$oidn_dir/VERSION" 2>/dev/null)" = "$oidn_version" ]; then
  echo "install-deps: Open Image Denoise $oidn_version present in .deps/oidn"
else
  echo "install-deps: fetching Open Image Denoise $oidn_version (pyoidn wheel) into .deps/oidn"
  if ! python3 -m pip --version >/dev/null 2>&1; then
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    ${sudo:-} apt-get update -qq
    DEBIAN_FRONTEND=noninteractive ${sudo:-} apt-get install -y -qq --no-install-recommends python3-pip
  fi
  tmp="$(mktemp -d)"
  trap 'rm -rf "$tmp"' EXIT
  python3 -m pip download --quiet --no-deps --only-binary=:all: --platform manylinux2014_x86_64 \
    -d "$tmp" "pyoidn==$oidn_version"
  python3 -m zipfile -e "$tmp"/pyoidn-*.whl "$tmp/wheel"
  src="$tmp/wheel/pyoidn/oidn/lib"
  rm -rf "$oidn_dir" && mkdir -p "$oidn_dir/lib"
  # The API library, its core (the trained weights), the CPU device and the TBB it was built with.
  for f in libOpenImageDenoise.so.2 "libOpenImageDenoise_core.so.$oidn_version" \
           "libOpenImageDenoise_device_cpu.so.$oidn_version" libtbb.so.12; do
    cp "$src/$f" "$oidn_dir/lib/"
  done
  cp "$tmp"/wheel/pyoidn-*.dist-info/LICENSE "$oidn_dir/LICENSE" 2>/dev/null || true
  echo "$oidn_version" > "$oidn_dir/VERSION"
fi
# Every library must resolve its dependencies (the CPU device needs the wheel's libtbb.so.12).
for f in "$oidn_dir"/lib/*.so*; do
  if LD_LIBRARY_PATH="$oidn_dir/lib" ldd "$f" | grep -q "not found"; then
    echo "install-deps: $f has unresolved libraries:" >&2
    LD_LIBRARY_PATH="$oidn_dir/lib" ldd "$f" | grep "not found" >&2
    exit 1
  fi
done

# `--bench`: Blender 5 as a Python module (PyPI bpy, which needs Python 3.11) in the venv
# .deps/bpy5, for the cycles5 and cycles5-artist methods of `diffphoton bench` (docs/cycles.md).
# Optional: when it cannot be installed (no network, no Python 3.11 with venv) one line says why
# and the rest goes on.
bpy_version=5.0.1
bpy_dir="$(cd "$(dirname "$0")/.." && pwd)/.deps/bpy5"
install_bpy5() {
  local py="" candidate log
  for candidate in /usr/bin/python3 python3.11 python3; do
    if "$candidate" -c 'import sys, venv, ensurepip; sys.exit(sys.version_info[:2] != (3, 11))' 2>/dev/null; then
      py="$candidate"
      break
    fi
  done
  if [ -z "$py" ]; then
    echo "install-deps: skipping Blender 5 (bpy $bpy_version): no Python 3.11 with venv and ensurepip found" >&2
    return 0
  fi
  echo "install-deps: installing Blender 5 (bpy $bpy_version: a 370 MB download, 1 GB installed) into .deps/bpy5 with $py"
  log="$(mktemp)"
  rm -rf "$bpy_dir"
  if "$py" -m venv "$bpy_dir" >"$log" 2>&1 &&
     "$bpy_dir/bin/python" -m pip install --quiet --disable-pip-version-check "bpy==$bpy_version" >>"$log" 2>&1 &&
     "$bpy_dir/bin/python" -c 'import sys, bpy; v = bpy.app.version_string; print(v); sys.exit(not v.startswith("5.0"))' >>"$log" 2>&1; then
    echo "$bpy_version" > "$bpy_dir/VERSION"
  else
    echo "install-deps: skipping Blender 5 (bpy $bpy_version): $(grep -v '^\s*$' "$log" | tail -n 1)" >&2
    rm -rf "$bpy_dir"
  fi
  rm -f "$log"
}
if [ "$bench" = 1 ]; then
  if [ -x "$bpy_dir/bin/python" ] && [ "$(cat "$bpy_dir/VERSION" 2>/dev/null)" = "$bpy_version" ]; then
    echo "install-deps: Blender 5 (bpy $bpy_version) present in .deps/bpy5"
  else
    install_bpy5
  fi
fi

# The Dask runner (farm/, docs/farm.md): dask.distributed from PyPI and the farm package itself,
# for whatever python3 is on PATH (its tests run with it). Debian's python3 refuses installs into
# the system's site-packages (PEP 668) unless told to.
root="$(cd "$(dirname "$0")/.." && pwd)"
# Present, and the same sources as farm/ (an older installed copy is replaced).
farm_installed_is_current() {
  python3 - "$root/farm/diffphoton_farm" <<'PY' 2>/dev/null
import filecmp, pathlib, sys
import distributed  # noqa: F401
import diffphoton_farm
installed, source = pathlib.Path(diffphoton_farm.__file__).parent, pathlib.Path(sys.argv[1])
names = sorted(p.name for p in source.glob("*.py"))
_, mismatch, errors = filecmp.cmpfiles(source, installed, names, shallow=False)
sys.exit(1 if mismatch or errors else 0)
PY
}
if farm_installed_is_current; then
  echo "install-deps: dask.distributed and diffphoton-farm present for $(command -v python3)"
else
  if ! python3 -m pip --version >/dev/null 2>&1; then
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    ${sudo:-} apt-get update -qq
    DEBIAN_FRONTEND=noninteractive ${sudo:-} apt-get install -y -qq --no-install-recommends python3-pip
  fi
  pip_flags=(--quiet)
  if [ -f "$(python3 -c 'import sysconfig; print(sysconfig.get_path("stdlib"))')/EXTERNALLY-MANAGED" ]; then
    pip_flags+=(--break-system-packages)
  fi
  echo "install-deps: installing dask[distributed] and farm/ (diffphoton-farm) for $(command -v python3)"
  python3 -m pip install "${pip_flags[@]}" "$root/farm"
  rm -rf "$root/farm/build" "$root"/farm/*.egg-info
fi

#!/usr/bin/env bash
# Every file the installed CMake package configs and pkg-config modules name must exist: a -dev
# package whose config names a file of a package it only recommends (libopenimageio-dev names
# openimageio-tools' /usr/bin/iconvert) breaks any project that finds it, ours only when it does.
# Run after scripts/install-deps.sh, on the machine it installed.
set -euo pipefail
missing=0
dirs=()
for d in /usr/lib/x86_64-linux-gnu/cmake /usr/lib/cmake /usr/share/cmake /usr/share/cmake-*; do
    [ -d "$d" ] && dirs+=("$d")
done
# The files CMake checks when a config imports its targets (_cmake_import_check_files_for_...),
# where a missing one stops the import (FATAL_ERROR; Debian's Imath only reports it). Qt's plugin
# targets are left out: a shared Qt's find_package never loads them (plugins such as its GTK
# theme and SQL drivers are optional packages).
checked=0
while read -r targets; do
    main="${targets%-*.cmake}.cmake"
    grep -q 'FATAL_ERROR "The imported target' "$main" 2>/dev/null || continue
    case "$(basename "$targets")" in Qt6*PluginTargets-*.cmake) continue ;; esac
    while read -r f; do
        checked=$((checked + 1))
        [ -e "$f" ] || { echo "check-package-files: $targets names $f, which is not installed" >&2; missing=1; }
    done < <(grep -hoiE '_(cmake_)?import_check_files_for_[^ ]+ [^)]*' "$targets" | grep -oE '"[^"]+"' |
             tr -d '"' | sed 's|\${_IMPORT_PREFIX}|/usr|' | grep -v '\${')
done < <(grep -rliE '_(cmake_)?import_check_files_for_' "${dirs[@]}" --include='*Targets-*.cmake' 2>/dev/null)
# Every pkg-config module resolves its requirements, and its -I and -L folders exist.
modules=0
for pc in /usr/lib/x86_64-linux-gnu/pkgconfig/*.pc /usr/share/pkgconfig/*.pc; do
    [ -f "$pc" ] || continue
    m="$(basename "$pc" .pc)"
    modules=$((modules + 1))
    if ! pkg-config --exists --print-errors "$m"; then
        echo "check-package-files: pkg-config module $m does not resolve" >&2
        missing=1
        continue
    fi
    for flag in $(pkg-config --libs-only-L --cflags-only-I "$m"); do
        d="${flag#-[LI]}"
        [ -e "$d" ] || { echo "check-package-files: $m names $d, which is not installed" >&2; missing=1; }
    done
done
echo "check-package-files: $checked files named by CMake configs, $modules pkg-config modules"
exit "$missing"

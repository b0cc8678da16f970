#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the dependencies (root, Debian 12) and builds origamic, its tests and tools in build/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
# Ninja for a new build directory; one configured already keeps its generator (CMake refuses another).
generator=()
[ -f build/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE="${ORIGAMIC_BUILD_TYPE:-Release}" >/dev/null
cmake --build build -j "$(nproc)"

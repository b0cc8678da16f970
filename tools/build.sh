#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the dependencies (root, Debian 12) and builds origamic, its tests and tools in build/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE="${ORIGAMIC_BUILD_TYPE:-Release}" >/dev/null
cmake --build build -j "$(nproc)"

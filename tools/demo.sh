#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Quick start: install, build, and design a pop-up for the project's own demo model.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
out=out/house
build/origamic design fixtures/house.obj --out "$out" --dump-maps "$out/maps" --fold-model --renders
echo "outputs are in $(pwd)/$out: house.dxf, house.svg, house.png, house.pdf (the plan; print the PDF at 100 %), house.json (report),"
echo "  maps/ (raster maps), house_popup.obj (the pop-up in 3D), house_popup.png, house_model.png, house_opening.gif (pictures)"

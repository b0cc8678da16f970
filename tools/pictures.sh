#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Regenerates the README's pictures of the demo house in docs/pictures/: its plan, the pop-up and the
# model from one viewpoint, and the card opening. Builds origamic first if needed.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/origamic ] || bash tools/build.sh
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build/origamic design fixtures/house.obj --renders --render-size 800x600 --out "$tmp"
mkdir -p docs/pictures
cp "$tmp/house.png" docs/pictures/house_plan.png
cp "$tmp/house_popup.png" "$tmp/house_model.png" "$tmp/house_opening.gif" docs/pictures/
ls -l docs/pictures

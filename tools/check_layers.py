#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks that every file of the library includes only its own stage and the stages before it.

The stages and what each links are read from the top-level CMakeLists.txt (origamic_stage(NAME ...
LINKS origamic_EARLIER ...)); a stage may use a header of any stage it reaches through them. Source
files and internal headers belong to the stage of their folder, src/STAGE; public headers
(include/origamic) to the stage in PUBLIC_HEADERS below, which must name every one of them.

  tools/check_layers.py [--root DIR]

Prints each include that reaches a later (or unrelated) stage and exits 1 if there is any; exits 0
with a one-line summary otherwise.
"""
import argparse
import re
import sys
from pathlib import Path

# The stage each public header belongs to: its types and calls are that stage's.
PUBLIC_HEADERS = {
    "oa.hpp": "core", "grid.hpp": "core", "unfilled_vector.hpp": "core", "error.hpp": "core", "output.hpp": "core",
    "mm_text.hpp": "core", "version.hpp": "core",
    "mesh_io.hpp": "load", "placement.hpp": "load",
    "raster.hpp": "raster",
    "segment.hpp": "segment",
    "slice.hpp": "slice",
    "validity.hpp": "validity",
    "plan.hpp": "plan", "plan_regions.hpp": "plan",
    "likeness.hpp": "likeness",
    "supports.hpp": "supports",
    "plan_analysis.hpp": "validate", "plan_dxf_reader.hpp": "validate",
    "plan_export.hpp": "export", "fold_style.hpp": "export", "raster_images.hpp": "export",
    "fold3d.hpp": "popup3d", "render.hpp": "popup3d",
    "design.hpp": "design", "report.hpp": "design", "popup_files.hpp": "design",
}


def stages_of(cmake_text):
    """Each stage and the stages it links directly, from the origamic_stage(...) calls."""
    stages = {}
    for call in re.finditer(r"origamic_stage\((\w+)(.*?)\)\s*$", cmake_text, re.S | re.M):
        name, body = call.group(1), call.group(2)
        links = body.split("LINKS", 1)[1] if "LINKS" in body else ""
        stages[name] = [m for m in re.findall(r"\borigamic_(\w+)", links)]
    return stages


def reachable(stages):
    """Per stage, itself and every stage it links, directly or not."""
    closure = {}

    def visit(name, seen):
        if name in closure:
            return closure[name]
        if name in seen:
            raise SystemExit(f"check_layers: stages link in a cycle through {name}")
        found = {name}
        for linked in stages.get(name, []):
            found |= visit(linked, seen | {name})
        closure[name] = found
        return found

    for name in stages:
        visit(name, set())
    return closure


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", type=Path, default=Path(__file__).resolve().parent.parent)
    root = parser.parse_args().root
    stages = stages_of((root / "CMakeLists.txt").read_text())
    if not stages:
        raise SystemExit("check_layers: no origamic_stage(...) in CMakeLists.txt")
    stages["cli"] = ["design"]
    allowed = reachable(stages)

    public = {p.name for p in (root / "include" / "origamic").glob("*.hpp*")}
    public = {name.removesuffix(".in") for name in public}
    unplaced = sorted(public - PUBLIC_HEADERS.keys())
    problems = [f"include/origamic/{name}: no stage (add it to PUBLIC_HEADERS)" for name in unplaced]

    internal = {}  # internal header name -> its stage
    files = []  # (path, stage)
    for folder in sorted((root / "src").iterdir()):
        if not folder.is_dir():
            continue
        if folder.name not in stages:
            problems.append(f"src/{folder.name}: a folder that is no stage of CMakeLists.txt")
            continue
        for path in sorted(folder.iterdir()):
            if path.suffix in (".cpp", ".hpp"):
                files.append((path, folder.name))
                if path.suffix == ".hpp":
                    internal[path.name] = folder.name
    files += [(root / "include" / "origamic" / name, PUBLIC_HEADERS[name])
              for name in sorted(public & PUBLIC_HEADERS.keys()) if (root / "include" / "origamic" / name).exists()]

    includes = 0
    for path, stage in files:
        for number, line in enumerate(path.read_text().splitlines(), 1):
            match = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not match:
                continue
            includes += 1
            target = match.group(1)
            name = target.removeprefix("origamic/")
            used = PUBLIC_HEADERS.get(name) if target.startswith("origamic/") else internal.get(name)
            if used is None:
                problems.append(f"{path.relative_to(root)}:{number}: includes {target}, which no stage holds")
            elif used not in allowed[stage]:
                problems.append(f"{path.relative_to(root)}:{number}: stage {stage} includes {target} of stage {used}, "
                                "which it does not link")
    for problem in problems:
        print(problem)
    if problems:
        return 1
    print(f"{len(files)} files, {includes} includes, {len(stages)} stages: every include within its stage's reach")
    return 0


if __name__ == "__main__":
    sys.exit(main())

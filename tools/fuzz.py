#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Mutation fuzzing of origamic's readers, through the program as a user runs it.

Seeds are mesh files (../shared/models, the fixtures) and plans (DXF the program writes of them);
each run mutates one seed (bit flips, chunks cut or repeated, numbers made extreme, long lines,
truncation) and runs `design` on a mesh, or `validate` and `fold` on a plan, within a time and an
address-space limit. A run fails if the program dies of a signal, runs past the time limit, exits
with a status other than the command's, says more than one line when it refuses the input, or
leaves a file behind that a failed run must not (a temporary *.part* file, or any output at all).
Failing inputs are kept in OUT/failures with what went wrong.

  tools/fuzz.py --minutes 60                 # an hour, as a developer runs it
  tools/fuzz.py --runs 40 --seed 1 --quick   # the ctest smoke run: small seeds only

With AddressSanitizer and UBSan (the Debug build; a sanitizer's report exits 1, a failure here):
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DORIGAMIC_BUILD_TESTS=OFF \
        -DORIGAMIC_BUILD_TOOLS=OFF && cmake --build build-asan
  ASAN_OPTIONS=detect_leaks=0 tools/fuzz.py --exe build-asan/origamic --memory-gib 0 --timeout 300 --minutes 60
(--memory-gib 0: no address-space limit, which AddressSanitizer's shadow memory exceeds; no leak
check: fontconfig and libstdc++ keep a few buffers to the end of every run.)
"""
import argparse
import gzip
import os
import random
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MESH_SUFFIXES = (".obj", ".stl", ".ply", ".off")
EXTREMES = [b"-1", b"0", b"2147483647", b"4294967296", b"-2147483648", b"1e20", b"1e308", b"-1e308",
            b"nan", b"inf", b"-inf", b"1e-320", b"99999999999999999999"]
STATUS = {"design": {0, 2}, "validate": {0, 2, 3}, "fold": {0, 2}}


def mutate(data: bytes, rng: random.Random) -> bytes:
    data = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        kind = rng.randrange(8)
        at = rng.randrange(len(data)) if data else 0
        if kind == 0 and data:  # flip bits
            data[at] ^= 1 << rng.randrange(8)
        elif kind == 1 and data:  # a random byte
            data[at] = rng.randrange(256)
        elif kind == 2:  # cut a chunk
            del data[at:at + rng.randint(1, 64)]
        elif kind == 3:  # repeat a chunk
            chunk = data[at:at + rng.randint(1, 256)]
            data[at:at] = chunk * rng.randint(1, 8)
        elif kind == 4:  # a number made extreme
            start = at
            while start < len(data) and not (48 <= data[start] <= 57 or data[start] == 45):
                start += 1
            end = start
            while end < len(data) and (48 <= data[end] <= 57 or data[end] in b"-+.eE"):
                end += 1
            data[start:end] = rng.choice(EXTREMES)
        elif kind == 5:  # a long line
            data[at:at] = b"9" * rng.choice([1023, 1024, 5000, 70000])
        elif kind == 6:  # truncate
            del data[at:]
        elif kind == 7:  # a line of header keywords, out of place
            data[at:at] = rng.choice([b"\nelement vertex 99999999\n", b"\nproperty float x\n", b"\nend_header\n",
                                      b"\nOFF\n", b"\nmtllib /dev/zero\n", b"\n90\n2147483647\n",
                                      b"\n0\nLWPOLYLINE\n8\nMOUNTAIN\n", b"\x00\x0b\x1b[2J"])
    return bytes(data)


def limit_memory(gib: float):
    def set_limit():
        if gib > 0:
            size = int(gib * (1 << 30))
            resource.setrlimit(resource.RLIMIT_AS, (size, size))
    return set_limit


def run_case(exe, command, file, work, timeout, gib):
    """Runs one command on one file; returns a failure message or None."""
    out_dir = work / "out"
    shutil.rmtree(out_dir, ignore_errors=True)
    out_dir.mkdir()
    args = [str(exe), command, str(file)]
    if command == "design":
        args += ["--out", str(out_dir), "--px-per-mm", "2"]
    elif command == "fold":
        args += ["--out", str(out_dir / "folded.obj")]
    try:
        done = subprocess.run(args, capture_output=True, timeout=timeout, preexec_fn=limit_memory(gib))
    except subprocess.TimeoutExpired:
        return f"hang: no end within {timeout} s"
    if done.returncode < 0:
        return f"signal {-done.returncode}"
    if done.returncode not in STATUS[command]:
        return f"exit status {done.returncode}"
    left = sorted(p.name for p in out_dir.iterdir())
    if any(".part" in name for name in left):
        return "temporary file left: " + ", ".join(left)
    if done.returncode == 2:
        lines = done.stderr.decode("utf-8", "replace").splitlines()
        if len(lines) != 1:
            return f"{len(lines)} lines of error: {done.stderr[:200]!r}"
        if left:
            return "a refused input left files: " + ", ".join(left)
    return None


def seeds(models: Path, quick: bool, exe: Path, work: Path):
    meshes = [ROOT / "fixtures" / "house.obj"]
    if not quick and models.is_dir():
        for path in sorted(models.rglob("*")):
            name = path.name.lower()
            if name.endswith(".gz"):
                name = name[:-3]
            if name.endswith(MESH_SUFFIXES) and path.stat().st_size < 3 << 20:
                meshes.append(path)
    plans = []
    for mesh in meshes[:1] if quick else meshes[:6]:
        out = work / "seed_plans" / mesh.name
        out.mkdir(parents=True, exist_ok=True)
        subprocess.run([str(exe), "design", str(mesh), "--out", str(out)], capture_output=True, timeout=120)
        plans += sorted(out.glob("*.dxf"))
    return meshes, plans


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--exe", type=Path, default=ROOT / "build" / "origamic")
    parser.add_argument("--models", type=Path, default=ROOT.parent / "shared" / "models")
    parser.add_argument("--minutes", type=float, default=0, help="run this long (default: --runs)")
    parser.add_argument("--runs", type=int, default=200)
    parser.add_argument("--seed", type=int, default=int(time.time()))
    parser.add_argument("--timeout", type=float, default=60, help="seconds a run may take")
    parser.add_argument("--memory-gib", type=float, default=4, help="address space a run may take (0: no limit)")
    parser.add_argument("--quick", action="store_true", help="small seeds only (the fixture and its plan)")
    parser.add_argument("--out", type=Path, default=None, help="where failing inputs are kept")
    args = parser.parse_args()
    if not args.exe.is_file():
        sys.exit(f"fuzz: {args.exe} not found: build first (tools/build.sh)")
    rng = random.Random(args.seed)
    work = Path(tempfile.mkdtemp(prefix="origamic-fuzz-"))
    failures_dir = args.out or (work / "failures")
    try:
        # A copy: a rebuild during a long run must not pull the program from under it.
        exe = work / "origamic"
        shutil.copy2(args.exe, exe)
        args.exe = exe
        meshes, plans = seeds(args.models, args.quick, args.exe, work)
        end = time.monotonic() + 60 * args.minutes
        runs = failures = 0
        while (time.monotonic() < end) if args.minutes else (runs < args.runs):
            use_plan = plans and rng.random() < 0.4
            seed = rng.choice(plans if use_plan else meshes)
            data = seed.read_bytes()
            if seed.suffix == ".gz":
                data = gzip.decompress(data)
            name = seed.name[:-3] if seed.suffix == ".gz" else seed.name
            mutated = mutate(data, rng)
            if not use_plan and rng.random() < 0.2:  # sometimes gzipped again
                mutated, name = gzip.compress(mutated), name + ".gz"
            case = work / f"case_{runs}_{name}"
            case.write_bytes(mutated)
            for command in (["validate", "fold"] if use_plan else ["design"]):
                failure = run_case(args.exe, command, case, work, args.timeout, args.memory_gib)
                if failure:
                    failures += 1
                    failures_dir.mkdir(parents=True, exist_ok=True)
                    kept = failures_dir / f"{command}_{runs}_{name}"
                    shutil.copy(case, kept)
                    print(f"FAIL {command} {kept}: {failure}", flush=True)
            case.unlink()
            runs += 1
        print(f"fuzz: {runs} inputs (seed {args.seed}), {failures} failures"
              + (f", kept in {failures_dir}" if failures else ""))
        return 1 if failures else 0
    finally:
        if args.out is None and not any(work.glob("failures/*")):
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Mutation check: shows that the unit tests catch a broken rule of the flight code.

Each mutation of mutations.toml (a file, an exact piece of its text, the replacement, and the
test binaries with the GoogleTest filters expected to catch it) is applied on its own to a
temporary copy of the source tree, never to the tree itself. The copy is configured once in its
own build directory; for each mutation only the targeted test binaries are rebuilt (ccache is
used when present) and only their filtered tests are run. A mutation is caught when a test
fails (or crashes, or times out); it survives when they all pass.

Exit status: 0 when every mutation is caught; 1 when one survives, when a pattern no longer
matches its file exactly once (a stale list: the code moved on and the mutation must follow
it), when a mutation does not build, or when the unmutated tests fail.

Usage: tools/mutation_check/mutation_check.py [--only NAME ...] [--list] [--keep] [--jobs N] [--no-ccache]
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
DEFAULT_SOURCE = HERE.parent.parent
# Never copied: build trees, version control, caches.
IGNORED = shutil.ignore_patterns("build", "build-*", ".git", "__pycache__", "*.pyc")


def load_mutations(path):
    with open(path, "rb") as f:
        data = tomllib.load(f)
    mutations = data.get("mutation", [])
    names = set()
    for m in mutations:
        for key in ("name", "file", "original", "replacement", "tests"):
            if key not in m:
                sys.exit(f"{path}: mutation {m.get('name', '?')}: missing key '{key}'")
        if m["name"] in names:
            sys.exit(f"{path}: mutation name '{m['name']}' given twice")
        if m["original"] == m["replacement"]:
            sys.exit(f"{path}: mutation {m['name']}: the replacement is the original")
        if not isinstance(m["tests"], dict) or not m["tests"]:
            sys.exit(f"{path}: mutation {m['name']}: 'tests' must map test binaries to GoogleTest filters")
        names.add(m["name"])
    return mutations


def stale_reason(source, m):
    """None when the original text occurs exactly once in the file, else why not."""
    path = source / m["file"]
    if not path.is_file():
        return f"{m['file']} does not exist"
    count = path.read_text().count(m["original"])
    return None if count == 1 else f"the original text occurs {count} times in {m['file']} (must be once)"


def run(cmd, log, timeout=None, env=None):
    """Runs cmd, appending its output to log; returns (exit status, seconds); -1 on timeout."""
    start = time.monotonic()
    with open(log, "a") as out:
        out.write(f"\n$ {' '.join(str(c) for c in cmd)}\n")
        out.flush()
        try:
            status = subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT, timeout=timeout, env=env).returncode
        except subprocess.TimeoutExpired:
            status = -1
    return status, time.monotonic() - start


def configure(copy, build, source, log, use_ccache):
    cmd = ["cmake", "-S", str(copy), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
           "-DREENTRY_BUILD_BENCHMARKS=OFF", "-DREENTRY_BUILD_TESTS=ON",
           f"-DREENTRY_SHARED_DIR={(source.parent / 'shared').resolve()}"]
    if use_ccache and shutil.which("ccache"):
        cmd.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    return run(cmd, log)[0] == 0


def build_targets(build, targets, log, jobs):
    return run(["cmake", "--build", str(build), "-j", str(jobs), "--target", *sorted(targets)], log)[0] == 0


def find_binary(build, name):
    hits = [p for p in build.rglob(name) if p.is_file() and os.access(p, os.X_OK)]
    return hits[0] if hits else None


def run_tests(build, tests, log, timeout):
    """Runs each binary with its filter, stopping at the first failure. Returns (all passed,
    what failed)."""
    for binary, gtest_filter in sorted(tests.items()):
        exe = find_binary(build, binary)
        if exe is None:
            return False, f"{binary}: not built"
        # From the binary's own directory, as CTest runs it.
        cmd = [str(exe), f"--gtest_filter={gtest_filter}", "--gtest_fail_fast=1", "--gtest_brief=1"]
        with open(log, "a") as out:
            out.write(f"\n$ (cd {exe.parent} && {' '.join(cmd)})\n")
        start = time.monotonic()
        try:
            proc = subprocess.run(cmd, cwd=exe.parent, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return False, f"{binary}: timed out after {timeout} s"
        with open(log, "a") as out:
            out.write(proc.stdout + proc.stderr + f"(exit {proc.returncode}, {time.monotonic() - start:.1f} s)\n")
        if proc.returncode != 0:
            failed = [line.split("]", 1)[1].split("(")[0].strip() for line in proc.stdout.splitlines()
                      if line.startswith("[  FAILED  ]") and "." in line]
            what = failed[0] if failed else f"exit {proc.returncode}"
            return False, f"{binary}: {what}"
    return True, ""


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--source", type=Path, default=DEFAULT_SOURCE, help="source tree (read only)")
    parser.add_argument("--mutations", type=Path, default=HERE / "mutations.toml")
    parser.add_argument("--only", nargs="*", default=[], help="run only these mutations (by name)")
    parser.add_argument("--list", action="store_true", help="list the mutations and check their patterns")
    parser.add_argument("--keep", action="store_true", help="keep the temporary copy and its build")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--no-ccache", action="store_true", help="compile without ccache even when present")
    parser.add_argument("--test-timeout", type=float, default=300.0, help="seconds per test binary run")
    args = parser.parse_args()
    source = args.source.resolve()
    mutations = load_mutations(args.mutations)
    if args.only:
        unknown = set(args.only) - {m["name"] for m in mutations}
        if unknown:
            sys.exit(f"unknown mutation(s): {', '.join(sorted(unknown))}")
        mutations = [m for m in mutations if m["name"] in args.only]

    stale = {m["name"]: r for m in mutations if (r := stale_reason(source, m))}
    if args.list:
        for m in mutations:
            tests = ", ".join(f"{b} {f}" for b, f in m["tests"].items())
            print(f"{m['name']:40s} {m['file']:45s} {'STALE: ' + stale[m['name']] if m['name'] in stale else tests}")
        return 1 if stale else 0

    start = time.monotonic()
    work = Path(tempfile.mkdtemp(prefix="reentry_mutation_"))
    copy, build, log = work / "src", work / "build", work / "mutation_check.log"
    results = []
    try:
        shutil.copytree(source, copy, ignore=IGNORED, symlinks=True)
        print(f"mutation_check: {len(mutations)} mutations; copy and build in {work}", flush=True)
        live = [m for m in mutations if m["name"] not in stale]
        targets = {b for m in live for b in m["tests"]}
        if not configure(copy, build, source, log, not args.no_ccache) or not build_targets(build, targets, log, args.jobs):
            print(f"mutation_check: the unmutated copy does not configure or build (log: {log})")
            return 1
        # The targeted tests must pass unmutated, or 'caught' would mean nothing.
        baseline = {}
        for m in live:
            for b, f in m["tests"].items():
                baseline.setdefault(b, set()).update(f.split(":"))
        ok, what = run_tests(build, {b: ":".join(sorted(f)) for b, f in baseline.items()}, log, args.test_timeout)
        if not ok:
            print(f"mutation_check: the unmutated tests fail ({what}; log: {log})")
            return 1
        print(f"mutation_check: unmutated build and tests ok ({time.monotonic() - start:.0f} s)", flush=True)
        # Grouped by file: a file is restored once, after its last mutation.
        for m in sorted(mutations, key=lambda m: m["file"]):
            if m["name"] in stale:
                results.append((m, "STALE", stale[m["name"]], 0.0))
                print(f"  {m['name']:40s} STALE     {stale[m['name']]}", flush=True)
                continue
            t0 = time.monotonic()
            path = copy / m["file"]
            original = path.read_text()
            path.write_text(original.replace(m["original"], m["replacement"], 1))
            if not build_targets(build, m["tests"].keys(), log, args.jobs):
                status, detail = "NO-BUILD", "the mutated code does not build"
            else:
                passed, what = run_tests(build, m["tests"], log, args.test_timeout)
                status, detail = ("SURVIVED", "every targeted test passes") if passed else ("caught", what)
            path.write_text(original)
            results.append((m, status, detail, time.monotonic() - t0))
            print(f"  {m['name']:40s} {status:9s} {detail} ({time.monotonic() - t0:.0f} s)", flush=True)
    finally:
        if args.keep:
            print(f"mutation_check: kept {work}")
        else:
            shutil.rmtree(work, ignore_errors=True)

    caught = sum(1 for _, s, _, _ in results if s == "caught")
    print(f"mutation_check: {caught} of {len(results)} caught, "
          f"{sum(1 for _, s, _, _ in results if s == 'SURVIVED')} survived, {len(stale)} stale, "
          f"{sum(1 for _, s, _, _ in results if s == 'NO-BUILD')} not building; {time.monotonic() - start:.0f} s")
    return 0 if caught == len(results) else 1


if __name__ == "__main__":
    sys.exit(main())

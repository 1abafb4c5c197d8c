#!/usr/bin/python3
"""Compare two campaigns record by record (DEVELOPERS.md: before/after a change that must not
alter behaviour). Usage: compare_runs.py DIR_A DIR_B [--ignore FIELD ...]

Reads DIR/runs*.jsonl of both, matches records by run index and compares every field exactly
(numbers bit for bit, as written by the JSON writer), except the wall-clock measurements
(wall_s, planner_ms_max and any field named in --ignore, also inside nested objects). Prints
`identical (N runs)` and exits 0, or lists the first differences and exits 1."""
import argparse
import glob
import json
import os
import sys

WALL_CLOCK = {"wall_s", "planner_ms_max", "solve_s", "wall_time_s"}


def load(d):
    runs = {}
    for path in sorted(glob.glob(os.path.join(d, "runs*.jsonl"))):
        with open(path) as f:
            for line in f:
                if line.strip():
                    r = json.loads(line)
                    runs[r["run"]] = r
    return runs


def diff(a, b, ignore, path=""):
    out = []
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k in ignore:
                continue
            if k not in a or k not in b:
                out.append(f"{path}{k}: only in {'B' if k not in a else 'A'}")
            else:
                out += diff(a[k], b[k], ignore, f"{path}{k}.")
    elif a != b:
        out.append(f"{path.rstrip('.')}: {a!r} != {b!r}")
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--ignore", nargs="*", default=[])
    args = ap.parse_args()
    ignore = WALL_CLOCK | set(args.ignore)
    ra, rb = load(args.a), load(args.b)
    if not ra or not rb:
        print("no run records in one of the directories", file=sys.stderr)
        return 2
    problems = []
    if set(ra) != set(rb):
        problems.append(f"run indices differ: {sorted(set(ra) ^ set(rb))}")
    for run in sorted(set(ra) & set(rb)):
        for d in diff(ra[run], rb[run], ignore):
            problems.append(f"run {run}: {d}")
    if problems:
        for p in problems[:20]:
            print(p)
        print(f"{len(problems)} differences")
        return 1
    print(f"identical ({len(ra)} runs, ignoring {', '.join(sorted(ignore))})")
    return 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""The house rule on function length: no function under fsw/, sim_truth/, common/ or tools/
longer than a limit (80 lines, from its first to its last line). Functions are located by
universal-ctags (Debian package universal-ctags), which reports each definition's first and last
line for C++, Python and shell. Usage: function_length.py [--limit N] [--root DIR] [DIRS ...].
Prints every function over the limit (lines, file:line, name) and exits 1 if there is one,
0 otherwise, 2 when ctags is missing or fails."""
import argparse
import os
import shutil
import subprocess
import sys

DEFAULT_DIRS = ["fsw", "sim_truth", "common", "tools"]
LANG_KINDS = ["--languages=C++,Python,Sh", "--kinds-C++=f", "--kinds-Python=fm", "--kinds-Sh=f"]


def functions(root, dirs):
    ctags = shutil.which("ctags")
    if ctags is None:
        sys.exit("function_length: ctags not found (install Debian's universal-ctags)")
    cmd = [ctags, "-R", "--fields=+ne", "-x", "--_xformat=%{line} %{end} %F %N", *LANG_KINDS, *dirs]
    out = subprocess.run(cmd, cwd=root, capture_output=True, text=True)
    if out.returncode != 0:
        print(f"function_length: ctags failed: {out.stderr.strip()}", file=sys.stderr)
        sys.exit(2)
    for line in out.stdout.splitlines():
        parts = line.split(" ", 3)
        if len(parts) == 4 and parts[0].isdigit() and parts[1].isdigit():
            yield int(parts[0]), int(parts[1]), parts[2], parts[3]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dirs", nargs="*", default=DEFAULT_DIRS)
    ap.add_argument("--limit", type=int, default=80)
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    args = ap.parse_args()
    long = sorted(((end - first + 1, path, first, name) for first, end, path, name in functions(args.root, args.dirs)
                   if end - first + 1 > args.limit), reverse=True)
    for n, path, first, name in long:
        print(f"{n:5d} lines  {path}:{first}  {name}")
    if long:
        print(f"function_length: {len(long)} function(s) over {args.limit} lines", file=sys.stderr)
        return 1
    print(f"function_length: no function over {args.limit} lines in {' '.join(args.dirs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

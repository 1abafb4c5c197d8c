#!/usr/bin/env python3
"""Print L/D max and alpha(L/D max) of config/vehicles/*.toml at given Mach numbers, using
bilinear interpolation of the tables (as the models do), alpha scanned every 0.1 deg."""
import bisect, os, sys, tomllib
HERE = os.path.dirname(os.path.abspath(__file__))
def interp(xs, ys, x):
    x = min(max(x, xs[0]), xs[-1]); j = min(max(bisect.bisect_right(xs, x) - 1, 0), len(xs) - 2)
    t = (x - xs[j]) / (xs[j + 1] - xs[j]); return ys[j] * (1 - t) + ys[j + 1] * t
def coef(a, m, tab, ad, md):
    col = [interp(md, row, m) for row in tab]
    return interp(ad, col, a)
for v in ("horus", "x33", "orbiter", "x38"):
    d = tomllib.load(open(os.path.join(HERE, "..", "vehicles", v + ".toml"), "rb"))["aero"]
    ad, md = d["alpha_deg"], d["mach"]
    out = []
    for m in (2.0, 5.0, 10.0, 20.0):
        best = max(((coef(i / 10, m, d["cl"], ad, md) / coef(i / 10, m, d["cd"], ad, md), i / 10) for i in range(int(ad[0] * 10) + 1, int(ad[-1] * 10) + 1)))
        out.append("M%-2g L/D %.2f @ %.1f deg" % (m, best[0], best[1]))
    print("%-8s" % v, " | ".join(out))

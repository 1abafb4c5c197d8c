#!/usr/bin/env python3
"""Plots the reachable TAEM footprint written by reentry_optimal --footprint.

DIR/footprint.json (the extremal solves) and DIR/footprint_tracks.csv (their ground tracks) ->
DIR/footprint.png: left, the ground tracks and the footprint's boundary on a latitude/longitude
map with the entry point and the aim point; right, the boundary in the arrival-line frame of the
aim point (along > 0 long, across > 0 right) with the TAEM range tolerance."""
import csv
import json
import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def converged(p):
    return p["status"] in ("optimal", "acceptable")


def boundary(points):
    """The reached extremal points (flown open loop within every path limit) in order around the
    footprint: max crossrange from the far end inwards, min downrange, min crossrange from the
    near end outwards, max downrange."""
    ok = [p for p in points if p.get("replay", {}).get("reached")]
    for p in ok:  # the point the open-loop flight reached
        p["along_km"], p["cross_km"] = p["replay"]["along_km"], p["replay"]["cross_km"]
        p["final_lat_deg"], p["final_lon_deg"] = p["replay"]["final_lat_deg"], p["replay"]["final_lon_deg"]
    top = sorted([p for p in ok if p["mode"] == "max_crossrange"], key=lambda p: -p["downrange_target_km"])
    bottom = sorted([p for p in ok if p["mode"] == "min_crossrange"], key=lambda p: p["downrange_target_km"])
    near = [p for p in ok if p["mode"] == "min_downrange"]
    far = [p for p in ok if p["mode"] == "max_downrange"]
    ring = top + near + bottom + far
    return ring + ring[:1] if ring else ring


def inside(ring, x, y):
    """Point in the closed polygon `ring` (even-odd rule) in the arrival-line frame."""
    pts = [(p["along_km"], p["cross_km"]) for p in ring[:-1]]
    hit = False
    for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]):
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            hit = not hit
    return hit


def unwrap(lon, ref):
    """Longitude within 180 deg of ref (tracks crossing 0 or 180 deg stay continuous)."""
    return ref + (lon - ref + 180.0) % 360.0 - 180.0


def main(out_dir):
    out = Path(out_dir)
    doc = json.loads((out / "footprint.json").read_text())
    # Group rows into tracks: a new track starts when t_s goes back to its start.
    tracks = []
    with open(out / "footprint_tracks.csv") as f:
        prev_t = None
        for row in csv.DictReader(f):
            t = float(row["t_s"])
            if prev_t is None or t < prev_t:
                tracks.append({"label": row["label"], "lat": [], "lon": []})
            tracks[-1]["lat"].append(float(row["lat_deg"]))
            tracks[-1]["lon"].append(float(row["lon_deg"]))
            prev_t = t
    entry, aim = doc["entry_lon_deg"], doc["aim_lon_deg"]
    ref = entry + 0.5 * (unwrap(aim, entry) - entry)  # midway between entry and aim
    for tr in tracks:
        tr["lon"] = [unwrap(x, ref) for x in tr["lon"]]
    ring = boundary(doc["points"])
    for p in ring:
        p["final_lon_deg"] = unwrap(p["final_lon_deg"], ref)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5.5))
    for tr in tracks:
        guid = tr["label"] == "guidance_nominal"
        ax.plot(tr["lon"], tr["lat"], color="tab:red" if guid else "0.6", lw=1.6 if guid else 0.7,
                label="guidance (nominal flight)" if guid else None, zorder=3 if guid else 1)
    if ring:
        ax.plot([p["final_lon_deg"] for p in ring], [p["final_lat_deg"] for p in ring], "b.-", lw=1.2,
                label="reachable TAEM footprint")
    ax.plot(unwrap(entry, ref), doc["entry_lat_deg"], "k^", ms=8, label="entry")
    ax.plot(unwrap(aim, ref), doc["aim_lat_deg"], "r*", ms=14, label="aim point")
    ax.set_xlabel("longitude [deg]")
    ax.set_ylabel("latitude (geocentric) [deg]")
    ax.set_title(f"{doc['mission']}: extremal trajectories")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    if ring:
        bx.fill([p["along_km"] for p in ring], [p["cross_km"] for p in ring], color="tab:blue", alpha=0.15)
        bx.plot([p["along_km"] for p in ring], [p["cross_km"] for p in ring], "b.-", lw=1.2, label="reached footprint")
    tol = doc["range_tol_km"]
    a = [2 * math.pi * k / 100 for k in range(101)]
    bx.plot([tol * math.cos(x) for x in a], [tol * math.sin(x) for x in a], "r-", lw=1, label=f"range tolerance {tol:g} km")
    bx.plot(0, 0, "r*", ms=14, label="aim point")
    failed = [p for p in doc["points"] if not converged(p) and p.get("replay", {}).get("reached")]
    if failed:
        bx.plot([p["replay"]["along_km"] for p in failed], [p["replay"]["cross_km"] for p in failed], "rx", ms=9, mew=2,
                label="solve not converged (reached, inner bound)")
    bx.set_xlabel("along the arrival line [km] (> 0 long)")
    bx.set_ylabel("across [km] (> 0 right)")
    n = len(doc["points"])
    n_conv = sum(converged(p) for p in doc["points"])
    aim_in = bool(ring) and inside(ring, 0.0, 0.0)
    bx.set_title(f"TAEM points reached open loop: {n_conv} of {n} solves converged; aim point "
                 f"{'inside' if aim_in else 'OUTSIDE'}; {doc['footprint_wall_s']:.0f} s", fontsize=10)
    print(f"{doc['mission']}: {n_conv} of {n} solves converged, aim point {'inside' if aim_in else 'outside'}, "
          f"footprint wall time {doc['footprint_wall_s']:.0f} s")
    bx.grid(True, alpha=0.3)
    bx.axis("equal")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "footprint.png", dpi=110)
    print(f"footprint plot: {out / 'footprint.png'}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: footprint_plot.py DIR")
    main(sys.argv[1])

#!/usr/bin/python3
"""Plots of a Monte Carlo campaign: miss histogram, TAEM footprint, error histograms.

Reads DIR/runs*.jsonl (one JSON record per run, written by reentry_mc) and DIR/report.json;
writes DIR/miss_histogram.png, DIR/footprint.png, DIR/errors.png and, when runs failed,
DIR/failure_modes.png (the report's failure modes as bars; matplotlib, Agg).
"""
import glob
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: mc_plots.py DIR")
    out = sys.argv[1]
    runs = []
    for path in sorted(glob.glob(os.path.join(out, "runs*.jsonl"))):
        with open(path) as f:
            runs += [json.loads(line) for line in f if line.strip()]
    if not runs:
        sys.exit(f"mc_plots: no runs*.jsonl in {out}")
    ok = [r for r in runs if r["success"]]
    bad = [r for r in runs if not r["success"]]
    title = f"{runs[0].get('mission', '')}: {len(ok)}/{len(runs)} runs successful"

    fig, ax = plt.subplots(figsize=(9, 5.5))
    miss = [r["miss_km"] for r in runs]
    bins = [0, 1, 2, 3, 5, 8, 11, 20, 50, 100, 1000, max(1001.0, max(miss) * 1.01)]
    ax.hist(miss, bins=bins, color="tab:blue", edgecolor="k")
    ax.set_xscale("symlog", linthresh=10)
    ax.set_xlabel("distance to the TAEM aim point at the TAEM energy [km]")
    ax.set_ylabel("runs [-]")
    ax.set_title(title)
    ax.grid(alpha=0.4)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "miss_histogram.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 7))
    if all("miss_along_km" in r for r in runs):
        # Footprint in the arrival-line frame: across the line (> 0 right) against along it
        # (> 0 past the aim point), the aim point at the origin.
        for group, colour, label in ((ok, "tab:green", "success"), (bad, "tab:red", "failure")):
            xs = [r["miss_cross_km"] for r in group if r["miss_km"] < 60.0]
            ys = [r["miss_along_km"] for r in group if r["miss_km"] < 60.0]
            ax.scatter(xs, ys, s=14, c=colour, label=f"{label} ({len(group)})")
        ax.plot([0.0], [0.0], "k+", ms=14, mew=2, label="aim point")
        ax.set_xlabel("across the arrival line at TAEM energy [km] (> 0 right)")
        ax.set_ylabel("along the arrival line at TAEM energy [km] (> 0 past the aim point)")
        ax.set_aspect("equal", adjustable="datalim")
    else:  # run files written before the miss split
        near = [r for r in runs if r["miss_km"] < 60.0]
        lat0 = sum(r["final_lat_deg"] for r in near) / len(near) if near else runs[0]["final_lat_deg"]
        for group, colour, label in ((ok, "tab:green", "success"), (bad, "tab:red", "failure")):
            xs = [r["final_lon_deg"] for r in group if r["miss_km"] < 60.0]
            ys = [r["final_lat_deg"] for r in group if r["miss_km"] < 60.0]
            ax.scatter(xs, ys, s=14, c=colour, label=f"{label} ({len(group)})")
        ax.set_xlabel("longitude at TAEM energy [deg]")
        ax.set_ylabel("latitude at TAEM energy [deg]")
        ax.set_aspect(1.0 / max(math.cos(math.radians(lat0)), 0.1), adjustable="datalim")
    ax.set_title(title + " (runs within 60 km shown)")
    ax.legend()
    ax.grid(alpha=0.4)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "footprint.png"), dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.5))
    for ax, key, label in ((axes[0], "alt_err_km", "altitude error at TAEM [km]"),
                           (axes[1], "mach", "Mach at TAEM [-]"),
                           (axes[2], "heading_err_deg", "heading error at TAEM [deg]")):
        ax.hist([r[key] for r in runs if abs(r["miss_km"]) < 60.0], bins=25, color="tab:blue", edgecolor="k")
        ax.set_xlabel(label)
        ax.set_ylabel("runs [-]")
        ax.grid(alpha=0.4)
    fig.suptitle(title + " (runs within 60 km)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "errors.png"), dpi=110)
    plt.close(fig)
    written = "miss_histogram.png, footprint.png, errors.png"
    report_path = os.path.join(out, "report.json")
    modes = []
    if os.path.exists(report_path):
        with open(report_path) as f:
            modes = json.load(f).get("failure_modes", [])
    if modes:
        # Failure modes (each failed run's set of violations), most frequent at the top.
        shown = modes[:12]
        fig, ax = plt.subplots(figsize=(10, 0.45 * len(shown) + 1.6))
        labels = [m["mode"].replace("taem_", "") for m in shown][::-1]
        counts = [m["runs"] for m in shown][::-1]
        ax.barh(range(len(shown)), counts, color="tab:red", edgecolor="k")
        ax.set_yticks(range(len(shown)))
        ax.set_yticklabels(labels)
        for i, c in enumerate(counts):
            ax.text(c, i, f" {c}", va="center")
        ax.set_xlabel("failed runs [-]")
        rest = sum(m["runs"] for m in modes[12:])
        ax.set_title(title + (f" ({rest} more in other modes)" if rest else ""))
        ax.grid(axis="x", alpha=0.4)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "failure_modes.png"), dpi=110)
        plt.close(fig)
        written += ", failure_modes.png"
    print(f"mc_plots: wrote {written} in {out}")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Plots of a Monte Carlo campaign: miss histogram, TAEM footprint, error histograms.

Reads the campaign's records (the file DIR/report.json names, else DIR/runs*.jsonl; one JSON
record per run, written by reentry_mc) and DIR/report.json; writes DIR/miss_histogram.png,
DIR/footprint.png, DIR/errors.png and, when runs failed, DIR/failure_modes.png (the report's
failure modes as bars; matplotlib, Agg); a failure_modes.png of an earlier campaign is removed.
Exit: 0, 2 no records, 8 a PNG file could not be written (file and reason named).
"""
import glob
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


EXIT_USAGE, EXIT_WRITE_FAILED = 2, 8


class WriteFailed(Exception):
    """A PNG file could not be written."""


def save(fig, path):
    try:
        fig.savefig(path, dpi=110)
    except OSError as exc:
        raise WriteFailed(f"{path}: {exc.strerror or exc}") from exc
    finally:
        plt.close(fig)


def load_runs(out):
    """The campaign's own records: the file its report names (else every runs*.jsonl)."""
    report = {}
    try:
        with open(os.path.join(out, "report.json")) as f:
            report = json.load(f)
    except (OSError, ValueError):
        pass
    paths = [os.path.join(out, report["records"])] if "records" in report else \
        sorted(glob.glob(os.path.join(out, "runs*.jsonl")))
    runs = []
    for path in paths:
        with open(path) as f:
            runs += [json.loads(line) for line in f if line.strip()]
    # A run that could not be flown carries no result to plot.
    return [r for r in runs if not r.get("error") and isinstance(r.get("miss_km"), (int, float))], report


def main():
    if len(sys.argv) != 2:
        print("usage: mc_plots.py DIR", file=sys.stderr)
        return EXIT_USAGE
    out = sys.argv[1]
    runs, report = load_runs(out)
    if not runs:
        print(f"mc_plots: no flown run records in {out}", file=sys.stderr)
        return EXIT_USAGE
    try:
        plot_all(out, runs, report)
    except WriteFailed as exc:
        print(f"mc_plots: write failed: {exc}", file=sys.stderr)
        return EXIT_WRITE_FAILED
    except OSError as exc:
        print(f"mc_plots: write failed: {exc.filename}: {exc.strerror}", file=sys.stderr)
        return EXIT_WRITE_FAILED
    return 0


def plot_all(out, runs, report):
    ok = [r for r in runs if r["success"]]
    bad = [r for r in runs if not r["success"]]
    title = f"{runs[0].get('mission', '')}: {len(ok)}/{len(runs)} runs successful"
    plot_histogram(out, runs, title)
    plot_footprint(out, runs, ok, bad, title)
    plot_errors(out, runs, title)
    written = "miss_histogram.png, footprint.png, errors.png"
    if plot_modes(out, report.get("failure_modes", []), title):
        written += ", failure_modes.png"
    print(f"mc_plots: wrote {written} in {out}")


def plot_histogram(out, runs, title):
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
    save(fig, os.path.join(out, "miss_histogram.png"))


def plot_footprint(out, runs, ok, bad, title):
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
    save(fig, os.path.join(out, "footprint.png"))


def plot_errors(out, runs, title):
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
    save(fig, os.path.join(out, "errors.png"))


def plot_modes(out, modes, title):
    """Failure modes (each failed run's set of violations), most frequent at the top; False
    when no run failed (an earlier campaign's plot is removed)."""
    stale = os.path.join(out, "failure_modes.png")
    if not modes:
        if os.path.exists(stale):
            os.remove(stale)
        return False
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
    save(fig, os.path.join(out, "failure_modes.png"))
    return True


if __name__ == "__main__":
    sys.exit(main())

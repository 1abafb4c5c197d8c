#!/usr/bin/python3
"""Plots of one reentry run from its CSV export (tools/log2csv) and summary.json.

usage: plot_run.py RUN_DIR [--log FILE] [--csv DIR] [--out DIR]

Reads RUN_DIR/run_csv/*.csv (running tools/log2csv on RUN_DIR/run.lcm first when the folder is
missing or older than the log: the CSV files are always those of the log) and RUN_DIR/summary.json
when present, and writes PNG files to RUN_DIR/plots/ (its earlier plots removed first: no plot of
another run stays). A plot whose channels are missing is skipped with a warning. Exit status (the
table in tools/README.md): 0 at least one plot written, 2 nothing to plot (no log, no TRUTH), 8 a
CSV or PNG file could not be written (file and reason named), 11 a column this script asks for is
not in the message definitions.

Optional summary.json keys used:
  entry_energy_Jpkg                       normalisation energy (else the first TRUTH energy)
  taem_lat_deg, taem_lon_deg, hac_radius_km, taem_heading_deg (else final flown heading)
  limit_heat_flux_kW_m2, limit_g, limit_q_kPa
  corridor_hv: {velocity_mps: [...], altitude_low_m: [...], altitude_high_m: [...]}
  corridor_drag: {e_norm: [...], drag_low_mps2: [...], drag_high_mps2: [...]}
"""
import argparse
import csv
import glob
import json
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.patches  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "tools", "logtools"))
# The columns come from the message definitions, as tools/log2csv's do.
from lcm_schema import SchemaError, csv_columns, csv_point_columns, parse_all  # noqa: E402

SCHEMA = {st.name: st for st in parse_all(glob.glob(os.path.join(REPO, "interfaces", "*.lcm")))}
# The CSV tables plotted: channel (file name) -> its message type and table.
CHANNELS = {"TRUTH": ("truth_telemetry_t", csv_columns),
            "GUIDANCE_CMD": ("guidance_cmd_t", csv_columns),
            "TRACKER_STATUS": ("tracker_status_t", csv_columns),
            "PLAN_points": ("plan_t", csv_point_columns)}
EARTH_RADIUS_M = 6378137.0
MU_M3PS2 = 3.986004418e14
RHO0_KGPM3 = 1.225
SCALE_HEIGHT_M = 7050.0
DPI = 120
PLOTS = ("ground_track.png", "altitude_velocity.png", "drag_energy.png", "bank_alpha.png", "gamma_energy.png",
         "constraints_time.png", "tracker_status.png")
EXIT_USAGE, EXIT_WRITE_FAILED, EXIT_RUN_ERROR = 2, 8, 11


class WriteFailed(Exception):
    """An output file could not be written whole."""


def warn(msg):
    print(f"plot_run: warning: {msg}", file=sys.stderr)


class Columns(dict):
    """A table's columns by name. A name that is no column of its message (interfaces/*.lcm) is
    an error in this script (SchemaError); one the log lacks is a KeyError (the plot is skipped)."""

    def __init__(self, cols, channel):
        super().__init__(cols)
        self.channel = channel

    def __missing__(self, name):
        type_name, table = CHANNELS[self.channel]
        if name not in table(SCHEMA[type_name]):
            raise SchemaError(f"{self.channel}: '{name}' is no column of {type_name} "
                              f"(interfaces/{type_name}.lcm)")
        raise KeyError(name)

    def where(self, mask):
        return Columns({k: v[mask] for k, v in self.items()}, self.channel)


def read_channel(csv_dir, channel):
    """The columns of one channel's CSV table (None if absent or empty)."""
    cols = read_csv(os.path.join(csv_dir, channel + ".csv"))
    return None if cols is None else Columns(cols, channel)


def read_csv(path):
    """Columns of a CSV file as float arrays (None if the file is absent or empty)."""
    if not os.path.isfile(path):
        return None
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        return None
    header, body = rows[0], rows[1:]
    cols = {}
    for j, name in enumerate(header):
        vals = []
        for r in body:
            try:
                vals.append(float(r[j]))
            except (IndexError, ValueError):
                vals.append(math.nan)
        cols[name] = np.array(vals)
    return cols


def style(ax, xlabel, ylabel, title=None, legend=True):
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    ax.grid(True, alpha=0.4)
    if legend and ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", fontsize=9)


def save(fig, out_dir, name, made):
    path = os.path.join(out_dir, name)
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=DPI)
    except OSError as exc:
        plt.close(fig)
        raise WriteFailed(f"{path}: {exc.strerror or exc}") from exc
    plt.close(fig)
    made.append(path)
    print(f"plot_run: wrote {path}")


def destination(lat_rad, lon_rad, bearing_rad, dist_m):
    """Great-circle destination point on a sphere."""
    d = dist_m / EARTH_RADIUS_M
    lat2 = np.arcsin(np.sin(lat_rad) * np.cos(d) + np.cos(lat_rad) * np.sin(d) * np.cos(bearing_rad))
    lon2 = lon_rad + np.arctan2(np.sin(bearing_rad) * np.sin(d) * np.cos(lat_rad),
                                np.cos(d) - np.sin(lat_rad) * np.sin(lat2))
    return lat2, lon2


def energy_norm(truth, summary):
    e_entry = summary.get("entry_energy_Jpkg")
    if not e_entry:
        e_entry = truth["energy_Jpkg"][0]
    return truth["energy_Jpkg"] / e_entry


def plot_ground_track(truth, summary, out_dir, made):
    """Whole track (left) and the terminal area around the aim point (right, with the HAC)."""
    fig, (ax, az) = plt.subplots(1, 2, figsize=(14, 6.5), gridspec_kw={"width_ratios": [1.6, 1.0]})
    lat = np.degrees(truth["latitude_rad"])
    lon = np.degrees(np.unwrap(np.asarray(truth["longitude_rad"], dtype=float)))
    lon0 = lon[0]

    def near_track(lon_deg):  # same branch as the track (mission files may use 0..360 deg)
        return (lon_deg - lon0 + 180.0) % 360.0 - 180.0 + lon0

    for a in (ax, az):
        a.plot(lon, lat, "b-", lw=1.8, label="flown ground track (TRUTH)")
        a.plot(lon[-1], lat[-1], "ks", ms=7, label="end of run")
    ax.plot(lon[0], lat[0], "go", ms=9, label="entry interface")
    have_aim = "taem_lat_deg" in summary and "taem_lon_deg" in summary
    if have_aim:
        alat, alon = float(summary["taem_lat_deg"]), near_track(float(summary["taem_lon_deg"]))
        for a in (ax, az):
            a.plot(alon, alat, "r*", ms=14, label="TAEM aim point")
        if "hac_radius_km" in summary:
            r_m = float(summary["hac_radius_km"]) * 1e3
            if "taem_heading_deg" in summary:
                chi = math.radians(float(summary["taem_heading_deg"]))
            else:
                chi = float(truth["heading_rad"][-1])
            clat, clon = destination(math.radians(alat), math.radians(alon), chi, r_m)
            b = np.linspace(0.0, 2.0 * math.pi, 361)
            hlat, hlon = destination(clat, clon, b, r_m)
            az.plot(np.degrees(hlon), np.degrees(hlat), "m--", lw=1.4,
                    label=f"heading-alignment circle (r = {r_m / 1e3:.1f} km)")
            az.plot(math.degrees(clon), math.degrees(clat), "m+", ms=10, label="HAC centre")
        # Terminal-area window: 1.5 deg around the aim point (about 170 km).
        az.set_xlim(alon - 1.5, alon + 1.5)
        az.set_ylim(alat - 1.0, alat + 1.0)
    style(ax, "longitude [deg]", "latitude [deg]", "Ground track")
    style(az, "longitude [deg]", "latitude [deg]", "Terminal area")
    ax.set_aspect(1.0 / max(math.cos(math.radians(float(np.nanmean(lat)))), 0.1), adjustable="datalim")
    if have_aim:
        az.set_aspect(1.0 / max(math.cos(math.radians(alat)), 0.1), adjustable="box")
    fig.tight_layout()
    save(fig, out_dir, "ground_track.png", made)


def plot_altitude_velocity(truth, summary, out_dir, made):
    fig, ax = plt.subplots(figsize=(10, 7))
    v = truth["velocity_mps"]
    h = truth["altitude_m"]
    ax.plot(v / 1e3, h / 1e3, "b-", lw=1.8, label="flown (TRUTH)")
    corr = summary.get("corridor_hv")
    if isinstance(corr, dict) and all(k in corr for k in ("velocity_mps", "altitude_low_m", "altitude_high_m")):
        cv = np.asarray(corr["velocity_mps"], float) / 1e3
        ax.fill_between(cv, np.asarray(corr["altitude_low_m"], float) / 1e3,
                        np.asarray(corr["altitude_high_m"], float) / 1e3, color="orange", alpha=0.25,
                        label="entry corridor")
    else:
        # Equilibrium glide (gamma' = 0, sigma = 0): k q = g - V^2/r with k = L/q estimated from the
        # flown lift, exponential atmosphere for the altitude of the required density.
        q = truth["q_Pa"]
        ok = q > 50.0
        if np.any(ok):
            k = float(np.median(truth["lift_mps2"][ok] / q[ok]))
            vg = np.linspace(max(300.0, float(np.nanmin(v))), float(np.nanmax(v)), 300)
            r = EARTH_RADIUS_M + 60e3
            need = MU_M3PS2 / r**2 - vg**2 / r
            good = need > 0
            rho = 2.0 * need[good] / (k * vg[good] ** 2)
            h_eq = -SCALE_HEIGHT_M * np.log(rho / RHO0_KGPM3)
            ax.plot(vg[good] / 1e3, h_eq / 1e3, "r--", lw=1.4,
                    label=f"equilibrium glide, bank 0 (L/q = {k:.2e} m²/kg, exp. atmosphere)")
        else:
            warn("no dynamic pressure above 50 Pa: equilibrium-glide curve omitted")
    style(ax, "Earth-relative velocity V [km/s]", "altitude h [km]", "Altitude - velocity")
    save(fig, out_dir, "altitude_velocity.png", made)


def plan_groups(points):
    """Plan points split per plan sequence number, in order."""
    out = []
    for s in sorted(set(points["seq"].astype(int))):
        m = points["seq"].astype(int) == s
        out.append((s, points.where(m)))
    return out


def plot_drag_energy(truth, points, summary, out_dir, made):
    fig, ax = plt.subplots(figsize=(10, 7))
    if points is not None:
        groups = plan_groups(points)
        cmap = plt.get_cmap("viridis", max(len(groups), 2))
        for i, (s, p) in enumerate(groups):
            # Up to 8 plans get a legend entry each; beyond that only the first and the last.
            named = len(groups) <= 8 or i in (0, len(groups) - 1)
            ax.plot(p["e_norm"], p["drag_mps2"], "-", lw=0.9, color=cmap(i),
                    label=(f"plan {s}" if named else None))
        if len(groups) > 8:
            ax.plot([], [], "-", lw=0.9, color="grey", label=f"({len(groups)} plans, colour = sequence)")
    else:
        warn("no PLAN points: drag_energy.png shows the flown drag only")
    corr = summary.get("corridor_drag")
    if isinstance(corr, dict) and all(k in corr for k in ("e_norm", "drag_low_mps2", "drag_high_mps2")):
        ce = np.asarray(corr["e_norm"], float)
        ax.plot(ce, np.asarray(corr["drag_low_mps2"], float), "k--", lw=1.2, label="corridor lower bound")
        ax.plot(ce, np.asarray(corr["drag_high_mps2"], float), "k-.", lw=1.2, label="corridor upper bound")
    ax.plot(energy_norm(truth, summary), truth["drag_mps2"], "r-", lw=2.0, label="flown (TRUTH)")
    ax.invert_xaxis()
    style(ax, "normalised energy E / E_entry [-]", "drag acceleration D [m/s²]", "Drag - energy profile")
    save(fig, out_dir, "drag_energy.png", made)


def on_truth_energy(truth, summary, msg):
    """Normalised energy at each message's tick, interpolated in time from TRUTH."""
    e = energy_norm(truth, summary)
    return np.interp(msg["utime"], truth["utime"], e)


def plot_bank_alpha(truth, cmd, summary, out_dir, made):
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(10, 8), sharex=True)
    e = energy_norm(truth, summary)
    if cmd is not None:
        ec = on_truth_energy(truth, summary, cmd)
        a1.plot(ec, np.degrees(cmd["sigma_rad"]), "k-", lw=1.0, label="commanded σ (GUIDANCE_CMD)")
        a2.plot(ec, np.degrees(cmd["alpha_rad"]), "k-", lw=1.0, label="commanded α (GUIDANCE_CMD)")
    else:
        warn("no GUIDANCE_CMD: bank_alpha.png shows the flown angles only")
    a1.plot(e, np.degrees(truth["sigma_rad"]), "r--", lw=1.6, label="flown σ (TRUTH)")
    a2.plot(e, np.degrees(truth["alpha_rad"]), "r--", lw=1.6, label="flown α (TRUTH)")
    a1.invert_xaxis()
    style(a1, "", "bank angle σ [deg]", "Bank angle and angle of attack")
    style(a2, "normalised energy E / E_entry [-]", "angle of attack α [deg]")
    save(fig, out_dir, "bank_alpha.png", made)


def plot_gamma_energy(truth, points, summary, out_dir, made):
    fig, ax = plt.subplots(figsize=(10, 7))
    if points is not None:
        s, p = plan_groups(points)[-1]
        ax.plot(p["e_norm"], np.degrees(p["gamma_rad"]), "b-", lw=1.4, label=f"planned γ (latest plan, seq {s})")
    else:
        warn("no PLAN points: gamma_energy.png shows the flown flight-path angle only")
    ax.plot(energy_norm(truth, summary), np.degrees(truth["gamma_rad"]), "r--", lw=1.6, label="flown γ (TRUTH)")
    ax.invert_xaxis()
    style(ax, "normalised energy E / E_entry [-]", "flight-path angle γ [deg]", "Flight-path angle - energy")
    save(fig, out_dir, "gamma_energy.png", made)


def plot_constraints(truth, summary, out_dir, made):
    fig, axes = plt.subplots(3, 1, figsize=(10, 9), sharex=True)
    t = truth["t_s"]
    spec = [("heat_flux_Wpm2", 1e-3, "heat flux [kW/m²]", "limit_heat_flux_kW_m2"),
            ("load_factor_g", 1.0, "load factor [g]", "limit_g"),
            ("q_Pa", 1e-3, "dynamic pressure [kPa]", "limit_q_kPa")]
    for ax, (col, scale, label, key) in zip(axes, spec):
        ax.plot(t, truth[col] * scale, "b-", lw=1.5, label="flown (TRUTH)")
        if key in summary:
            ax.axhline(float(summary[key]), color="r", ls="--", lw=1.3, label=f"limit {float(summary[key]):g}")
        style(ax, "time t [s]" if ax is axes[-1] else "", label)
    axes[0].set_title("Path constraints")
    save(fig, out_dir, "constraints_time.png", made)


def phase_names():
    """Tracker phase names by value, from tracker_status_t's PHASE_* constants."""
    consts = sorted(SCHEMA["tracker_status_t"].consts_of("phase"), key=lambda c: int(c.value))
    return [c.comment or c.name[len("PHASE_"):].lower().replace("_", " ") for c in consts]


PHASE_NAMES = phase_names()
PHASE_COLORS = ["#eeeeee", "#dde8f5", "#e3f2dd", "#f8ecd6", "#f6dada"]


def phase_color(k):
    return PHASE_COLORS[k % len(PHASE_COLORS)]


def shade_phases(ax, t, phase):
    """Background spans coloured by the tracker phase (TRACKER_STATUS.phase)."""
    p = np.nan_to_num(phase, nan=0).astype(int)
    start = 0
    for i in range(1, len(p) + 1):
        if i == len(p) or p[i] != p[start]:
            ax.axvspan(t[start], t[i - 1], color=phase_color(max(p[start], 0)), lw=0)
            start = i


def plot_tracker_status(tracker, summary, out_dir, made):
    """The tracker's internals over time, on its phases: drag loop, ratio estimates, heading
    corridor, terminal range control."""
    t = tracker["utime"] * 1e-6
    fig, axes = plt.subplots(4, 1, figsize=(10, 12), sharex=True)
    for ax in axes:
        shade_phases(ax, t, tracker["phase"])
    ax = axes[0]
    ax.plot(t, tracker["drag_ref_mps2"], "k--", lw=1.2, label="reference D_ref")
    ax.plot(t, tracker["drag_ref_mps2"] + tracker["drag_err_mps2"], "b-", lw=1.2, label="sensed at the reference alpha")
    style(ax, "", "drag [m/s²]", "Tracker state (background: phase)")
    ax = axes[1]
    ax.plot(t, tracker["drag_ratio"], "b-", lw=1.2, label="K = D sensed / D model")
    ax.plot(t, tracker["lift_over_drag_ratio"], "g-", lw=1.2, label="L/D sensed / L/D model")
    style(ax, "", "ratio [-]")
    ax = axes[2]
    hw = np.degrees(tracker["corridor_half_width_rad"])
    ax.plot(t, np.degrees(tracker["heading_err_rad"]), "b-", lw=1.2, label="heading error")
    ax.plot(t, hw, "r--", lw=1.0, label="corridor half-width")
    ax.plot(t, -hw, "r--", lw=1.0)
    style(ax, "", "heading [deg]")
    ax = axes[3]
    ax.plot(t, tracker["drag_integral_mps"], "c-", lw=1.2, label="drag integral ∫(D - D_ref) dt")
    style(ax, "time t [s]", "drag integral [m/s]", legend=False)
    tw = ax.twinx()
    tw.plot(t, tracker["terminal_increment_mps2"], "m-", lw=1.2, label="terminal increment c")
    tw.set_ylabel("terminal increment c [m/s²]")
    lines = ax.get_lines() + tw.get_lines()
    ax.legend(lines, [ln.get_label() for ln in lines], fontsize=8, loc="lower left")
    handles = [matplotlib.patches.Patch(color=phase_color(k), label=n) for k, n in enumerate(PHASE_NAMES)]
    axes[0].legend(handles=axes[0].get_legend_handles_labels()[0] + handles, fontsize=8, loc="upper left")
    save(fig, out_dir, "tracker_status.png", made)


def csv_of_log(run_dir, log_arg, csv_dir):
    """The CSV files of the log: converted when missing or older than the log. None or the exit status."""
    log = log_arg or os.path.join(run_dir, "run.lcm")
    have_log = os.path.isfile(log)
    if os.path.isdir(csv_dir):
        csvs = [os.path.join(csv_dir, n) for n in os.listdir(csv_dir) if n.endswith(".csv")]
        if not have_log or not csvs or min(os.path.getmtime(c) for c in csvs) >= os.path.getmtime(log):
            return None
        for c in csvs:  # the CSV files of another log
            os.remove(c)
    elif not have_log:
        print(f"plot_run: nothing to plot: neither {csv_dir} nor {log} exists", file=sys.stderr)
        return EXIT_USAGE
    log2csv = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "log2csv")
    rc = subprocess.call([log2csv, log, "--out", csv_dir])
    if rc == EXIT_WRITE_FAILED:
        print(f"plot_run: write failed: the CSV files of {log} in {csv_dir}", file=sys.stderr)
        return EXIT_WRITE_FAILED
    if rc != 0:
        print(f"plot_run: warning: log2csv exited with status {rc}", file=sys.stderr)
        if not os.path.isdir(csv_dir):
            return EXIT_USAGE
    return None


def read_summary(run_dir):
    summary = {}
    spath = os.path.join(run_dir, "summary.json")
    if os.path.isfile(spath):
        try:
            with open(spath, encoding="utf-8") as f:
                summary = json.load(f)
        except (OSError, ValueError) as exc:
            warn(f"cannot read {spath}: {exc}")
        if not isinstance(summary, dict):
            summary = {}
    return summary


def make_plots(csv_dir, summary, out_dir):
    """Every plot the channels allow; the paths written."""
    truth, cmd, points, tracker = (read_channel(csv_dir, ch)
                                   for ch in ("TRUTH", "GUIDANCE_CMD", "PLAN_points", "TRACKER_STATUS"))
    made = []
    jobs = [("ground_track", lambda: plot_ground_track(truth, summary, out_dir, made)),
            ("altitude_velocity", lambda: plot_altitude_velocity(truth, summary, out_dir, made)),
            ("drag_energy", lambda: plot_drag_energy(truth, points, summary, out_dir, made)),
            ("bank_alpha", lambda: plot_bank_alpha(truth, cmd, summary, out_dir, made)),
            ("gamma_energy", lambda: plot_gamma_energy(truth, points, summary, out_dir, made)),
            ("constraints_time", lambda: plot_constraints(truth, summary, out_dir, made))]
    if tracker is not None:
        try:
            plot_tracker_status(tracker, summary, out_dir, made)
        except KeyError as exc:
            warn(f"tracker_status.png skipped: column {exc} missing")
            plt.close("all")
    else:
        warn(f"no TRACKER_STATUS channel in {csv_dir}: tracker_status.png skipped")
    for name, job in jobs:
        if truth is None:
            warn(f"no TRUTH channel in {csv_dir}: {name}.png skipped")
            continue
        try:
            job()
        except KeyError as exc:
            warn(f"{name}.png skipped: column {exc} missing")
            plt.close("all")
    return made


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--log", help="log file (default RUN_DIR/run.lcm)")
    ap.add_argument("--csv", help="CSV folder (default RUN_DIR/run_csv)")
    ap.add_argument("--out", help="plot folder (default RUN_DIR/plots)")
    args = ap.parse_args()
    run_dir = args.run_dir
    csv_dir = args.csv or os.path.join(run_dir, "run_csv")
    out_dir = args.out or os.path.join(run_dir, "plots")
    try:
        rc = csv_of_log(run_dir, args.log, csv_dir)
        if rc is not None:
            return rc
        os.makedirs(out_dir, exist_ok=True)
        for name in PLOTS:  # the plots of an earlier run
            if os.path.exists(os.path.join(out_dir, name)):
                os.remove(os.path.join(out_dir, name))
        made = make_plots(csv_dir, read_summary(run_dir), out_dir)
    except WriteFailed as exc:
        print(f"plot_run: write failed: {exc}", file=sys.stderr)
        return EXIT_WRITE_FAILED
    except OSError as exc:
        print(f"plot_run: write failed: {exc.filename}: {exc.strerror}", file=sys.stderr)
        return EXIT_WRITE_FAILED
    if not made:
        print("plot_run: nothing to plot: no plot could be made", file=sys.stderr)
        return EXIT_USAGE
    print(f"plot_run: {len(made)} plot(s) in {out_dir}")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except SchemaError as exc:  # a column this script asks for is not in the message definitions
        print(f"plot_run: plotting failed: {exc}", file=sys.stderr)
        sys.exit(EXIT_RUN_ERROR)

#!/usr/bin/python3
"""CTest checks for the log tools (tools/log2csv, tools/loginfo, tools/plot).

usage: check_logtools.py CHECK --bin-dir DIR --repo DIR --work DIR
CHECK is one of: rows, plots, plot_partial, malformed.
Every check builds its own synthetic log with reentry_synth_log in a fresh work folder.
"""
import argparse
import csv
import json
import os
import re
import shutil
import struct
import subprocess
import sys

MU_M3PS2 = 3.986004418e14
EARTH_RADIUS_M = 6378137.0
FAILURES = []


def expect(cond, msg):
    if not cond:
        FAILURES.append(msg)
        print(f"FAIL: {msg}")


def run(cmd, env=None):
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    return p.returncode, p.stdout, p.stderr


def csv_rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def lcm_fields(lcm_path):
    """Field names in declaration order, read independently of the build-time generator."""
    text = re.sub(r"//[^\n]*", "", open(lcm_path, encoding="utf-8").read())
    body = text[text.index("{") + 1:text.rindex("}")]
    out = []
    for stmt in body.split(";"):
        m = re.match(r"\s*(\w+)\s+(\w+)\s*(?:\[\s*(\d+)\s*\])?\s*$", stmt)
        if m and m.group(1) != "const":
            n = int(m.group(3)) if m.group(3) else 0
            out += [m.group(2)] if n == 0 else [f"{m.group(2)}_{i}" for i in range(n)]
    return out


def synth(a, name, *extra):
    log = os.path.join(a.work, name)
    rc, out, err = run([os.path.join(a.bin_dir, "reentry_synth_log"), log, *extra])
    if rc != 0:
        sys.exit(f"reentry_synth_log failed: {err}")
    return log


def check_rows(a):
    log = synth(a, "run.lcm", "--foreign", "--dt", "2.0")
    out_dir = os.path.join(a.work, "csv")
    rc, out, err = run([os.path.join(a.repo, "tools", "log2csv"), log, "--out", out_dir])
    expect(rc == 0, f"log2csv exit status {rc}: {err}")
    rc, out, err = run([os.path.join(a.repo, "tools", "loginfo"), "--json", log])
    expect(rc == 0, f"loginfo exit status {rc}: {err}")
    if rc != 0:
        return
    info = json.loads(out)
    chans = info["channels"]
    for ch in ("NAV_STATE", "TRUTH", "GUIDANCE_CMD", "GUIDANCE_STATUS", "TRACKER_STATUS", "PLAN", "RUN_CONTROL"):
        expect(ch in chans, f"loginfo lacks channel {ch}")
        path = os.path.join(out_dir, ch + ".csv")
        expect(os.path.isfile(path), f"missing {path}")
        if ch in chans and os.path.isfile(path):
            _, rows = csv_rows(path)
            expect(len(rows) == chans[ch]["messages"],
                   f"{ch}: {len(rows)} CSV rows but loginfo counts {chans[ch]['messages']}")
    # The synthetic log holds 3 foreign events and 2 truncated TRUTH events: counted, not written.
    expect(chans.get("FOREIGN", {}).get("unknown_type") == 3, "FOREIGN events not counted as unknown type")
    expect(not os.path.exists(os.path.join(out_dir, "FOREIGN.csv")), "CSV written for an unknown type")
    expect(chans["TRUTH"]["undecodable"] == 2, "truncated TRUTH events not counted as undecodable")
    expect(chans["TRUTH"]["events"] == chans["TRUTH"]["messages"] + 2, "TRUTH event accounting")
    # Rates from the utime fields: one message per 2 s tick.
    expect(chans["TRUTH"]["time_source"] == "utime", "TRUTH rate not taken from utime")
    expect(abs(chans["TRUTH"]["rate_hz"] - 0.5) < 1e-9, f"TRUTH rate {chans['TRUTH']['rate_hz']} != 0.5 Hz")
    # Column order follows the .lcm declaration (small arrays expanded to name_i).
    truth_header, truth = csv_rows(os.path.join(out_dir, "TRUTH.csv"))
    expect(truth_header == lcm_fields(os.path.join(a.repo, "interfaces", "truth_telemetry_t.lcm")),
           "TRUTH columns differ from the .lcm field list")
    nav_header, nav = csv_rows(os.path.join(out_dir, "NAV_STATE.csv"))
    expected = lcm_fields(os.path.join(a.repo, "interfaces", "nav_state_t.lcm"))
    expect(nav_header == expected and "position_I_m_2" in nav_header, f"NAV_STATE columns {nav_header}")
    # Values land in the right columns: specific energy obeys E = V^2/2 - mu/r + mu/R (7.8).
    col = {n: i for i, n in enumerate(truth_header)}
    worst = 0.0
    for r in truth:
        v, h, e = float(r[col["velocity_mps"]]), float(r[col["altitude_m"]]), float(r[col["energy_Jpkg"]])
        rr = EARTH_RADIUS_M + h
        worst = max(worst, abs(0.5 * v * v - MU_M3PS2 / rr + MU_M3PS2 / EARTH_RADIUS_M - e) / abs(e))
    expect(worst < 1e-9, f"TRUTH energy column inconsistent with V and h (rel. err {worst:g})")
    # |r_I| of NAV_STATE equals R + altitude of TRUTH at the same tick.
    ncol = {n: i for i, n in enumerate(nav_header)}
    tr_by_tick = {int(r[col["tick"]]): float(r[col["altitude_m"]]) for r in truth}
    for r in nav[:50]:
        pos = [float(r[ncol[f"position_I_m_{i}"]]) for i in range(3)]
        radius = sum(p * p for p in pos) ** 0.5
        h = tr_by_tick[int(r[ncol["tick"]])]
        expect(abs(radius - EARTH_RADIUS_M - h) < 1e-3, f"NAV radius {radius} vs TRUTH altitude {h}")
    # Long-format plan points: one row per valid point of every plan.
    plan_header, plans = csv_rows(os.path.join(out_dir, "PLAN.csv"))
    pts_header, pts = csv_rows(os.path.join(out_dir, "PLAN_points.csv"))
    n_total = sum(int(p[plan_header.index("n_points")]) for p in plans)
    expect(len(pts) == n_total, f"PLAN_points rows {len(pts)} != sum of n_points {n_total}")
    expect(pts_header[:4] == ["utime", "tick", "seq", "i"], f"PLAN_points key columns {pts_header[:4]}")
    e = [float(p[pts_header.index("e_norm")]) for p in pts if p[2] == "1"]
    expect(abs(e[0] - 1.0) < 1e-12 and all(x > y for x, y in zip(e, e[1:])), "plan 1 e_norm not 1 -> decreasing")
    # --channel selects one channel only.
    sel = os.path.join(a.work, "csv_sel")
    rc, out, err = run([os.path.join(a.repo, "tools", "log2csv"), log, "--channel", "PLAN", "--out", sel])
    expect(rc == 0 and sorted(os.listdir(sel)) == ["PLAN.csv", "PLAN_points.csv"], f"--channel PLAN gave {os.listdir(sel) if os.path.isdir(sel) else rc}")


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def check_plots(a):
    run_dir = os.path.join(a.work, "run")
    os.makedirs(run_dir)
    synth(a, os.path.join("run", "run.lcm"))
    with open(os.path.join(run_dir, "summary.json"), "w") as f:
        json.dump({"taem_lat_deg": 42.0, "taem_lon_deg": -95.0, "hac_radius_km": 30.0,
                   "limit_heat_flux_kW_m2": 1000.0, "limit_g": 2.5, "limit_q_kPa": 15.0}, f)
    rc, out, err = run([os.path.join(a.repo, "tools", "plot"), run_dir])
    expect(rc == 0, f"plot exit status {rc}: {err}")
    expect(os.path.isdir(os.path.join(run_dir, "run_csv")), "plot did not run log2csv first")
    plots = os.path.join(run_dir, "plots")
    names = sorted(n for n in os.listdir(plots) if n.endswith(".png")) if os.path.isdir(plots) else []
    expect(len(names) >= 7, f"only {len(names)} PNG files: {names}")
    for want in ("ground_track", "altitude_velocity", "drag_energy", "bank_alpha", "gamma_energy",
                 "constraints_time", "tracker_status"):
        expect(want + ".png" in names, f"{want}.png missing")
    for n in names:
        p = os.path.join(plots, n)
        wh = png_size(p)
        expect(wh is not None, f"{n} is not a PNG")
        if wh:
            expect(wh[0] > 300 and wh[1] > 300, f"{n} is {wh[0]}x{wh[1]}")
        expect(os.path.getsize(p) > 20000, f"{n} is only {os.path.getsize(p)} bytes")


def check_plot_partial(a):
    run_dir = os.path.join(a.work, "run")
    os.makedirs(run_dir)
    log = synth(a, os.path.join("run", "run.lcm"))
    rc, _, err = run([os.path.join(a.repo, "tools", "log2csv"), log, "--channel", "TRUTH",
                      "--out", os.path.join(run_dir, "run_csv")])
    expect(rc == 0, f"log2csv --channel TRUTH failed: {err}")
    rc, out, err = run([os.path.join(a.repo, "tools", "plot"), run_dir])
    expect(rc == 0, f"plot with TRUTH only: exit status {rc}: {err}")
    expect("warning" in err, "no warning about the missing PLAN / GUIDANCE_CMD channels")
    # Without TRUTH no plot can be made: non-zero exit, no traceback.
    os.remove(os.path.join(run_dir, "run_csv", "TRUTH.csv"))
    shutil.rmtree(os.path.join(run_dir, "plots"))
    rc, out, err = run([os.path.join(a.repo, "tools", "plot"), run_dir])
    expect(rc != 0 and "Traceback" not in err, f"plot without TRUTH: status {rc}, stderr {err!r}")


def first_event_bytes(data):
    """Length of the first event of an LCM log (sync, eventnum, utime, lengths, channel, data)."""
    channel_len, data_len = struct.unpack(">ii", data[20:28])
    return 28 + channel_len + data_len


def check_malformed(a):
    good = synth(a, "good.lcm")
    data = open(good, "rb").read()
    cases = {
        "garbage.lcm": bytes((i * 73 + 11) % 256 for i in range(5000)),
        "empty.lcm": b"",
        "truncated.lcm": data[:len(data) // 2 + 7],
        "corrupt_middle.lcm": data[:40000] + b"\x00" * 333 + data[40000:],
        "huge_lengths.lcm": b"\xed\xa1\xda\x01" + b"\x00" * 16 + b"\x7f\xff\xff\xff" * 2,
        # A good event, then a header claiming 2 GB of data (LCM 1.3.1 alone crashes on this).
        "huge_data_length.lcm": data[:first_event_bytes(data)] + b"\xed\xa1\xda\x01" + b"\x00" * 16
        + b"\x00\x00\x00\x05\x7f\xff\xff\xffTRUTHabc",
    }
    for name, blob in cases.items():
        path = os.path.join(a.work, name)
        with open(path, "wb") as f:
            f.write(blob)
        for tool in ("log2csv", "loginfo"):
            cmd = [os.path.join(a.repo, "tools", tool), path]
            if tool == "log2csv":
                cmd += ["--out", os.path.join(a.work, name + "_csv")]
            rc, out, err = run(cmd)
            # The exit table (tools/README.md): 2 not an LCM log, 6 a damaged one.
            expect(rc in (2, 6), f"{tool} {name}: exit status {rc} (want 2 or 6)")
            expect(rc != 6 or name not in ("garbage.lcm", "empty.lcm"), f"{tool} {name}: status {rc}")
            expect(("not an LCM log" in err or "damaged log" in err) and name in err,
                   f"{tool} {name}: unclear message {err!r}")
    rc, _, err = run([os.path.join(a.repo, "tools", "loginfo"), os.path.join(a.work, "does_not_exist.lcm")])
    expect(rc == 2 and "cannot open" in err, f"missing file: status {rc}, {err!r}")
    # A truncated tail still yields the events before it; --lenient accepts it.
    rc, out, err = run([os.path.join(a.repo, "tools", "loginfo"), "--json", "--lenient",
                        os.path.join(a.work, "truncated.lcm")])
    expect(rc == 0, f"--lenient on a truncated log: status {rc}")
    if rc == 0:
        info = json.loads(out)
        expect(info["malformed"] and info["events"] > 100, "truncated log: events before the damage lost")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("check", choices=["rows", "plots", "plot_partial", "malformed"])
    ap.add_argument("--bin-dir", required=True)
    ap.add_argument("--repo", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    # The wrappers find the binaries through REENTRY_BUILD_DIR (bin dir = <build>/tools/logtools).
    os.environ.setdefault("REENTRY_BUILD_DIR", os.path.dirname(os.path.dirname(os.path.abspath(a.bin_dir))))
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    {"rows": check_rows, "plots": check_plots, "plot_partial": check_plot_partial,
     "malformed": check_malformed}[a.check](a)
    if FAILURES:
        print(f"{len(FAILURES)} failure(s)")
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())

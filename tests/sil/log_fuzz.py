#!/usr/bin/python3
"""Damaged run logs into replay, loginfo and log2csv (CTest fuzz.logs, seeded, bounded).

Builds a consistent, sealed lockstep run log with the SIL guidance double (its replay of a
synthetic log, --replay-log), checks that it replays identical, then feeds 330 damaged copies
(truncated, bit-flipped, garbage inserted, events removed, duplicated or swapped, END_OF_RUN
removed, length fields blown up, re-framed without the damaged event) to the three tools.
Every tool must exit with a status of its own (no signal, no sanitizer report), and the replay
must never call a damaged copy identical: the seal's CRC covers every byte, so this holds for
a flipped time stamp or status field too.
"""
import argparse
import os
import random
import struct
import subprocess
import sys

SYNC = b"\xed\xa1\xda\x01"


def events(data):
    """Strict parse: list of (offset, length, eventnum, channel, payload) or None if damaged."""
    out, pos, last = [], 0, None
    while pos < len(data):
        if pos + 28 > len(data) or data[pos:pos + 4] != SYNC:
            return None
        num, _, cl, dl = struct.unpack(">qqii", data[pos + 4:pos + 28])
        if cl < 1 or cl > 999 or dl < 0 or pos + 28 + cl + dl > len(data):
            return None
        if last is not None and num != last + 1:
            return None
        last = num
        out.append((pos, 28 + cl + dl, num, data[pos + 28:pos + 28 + cl], data[pos + 28 + cl:pos + 28 + cl + dl]))
        pos += 28 + cl + dl
    return out


def content(evs):
    return [(c, p) for (_, _, _, c, p) in evs if c in (b"NAV_STATE", b"GUIDANCE_CMD", b"RUN_CONTROL")]


def renumber(evs_bytes):
    """Re-emit a list of (channel, payload, timestamp) as a framing-valid log."""
    out = b""
    for i, (c, p, t) in enumerate(evs_bytes):
        out += SYNC + struct.pack(">qqii", i, t, len(c), len(p)) + c + p
    return out


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=120)
    return p.returncode, p.stdout, p.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    ap.add_argument("--repo", required=True)
    a = ap.parse_args()
    build = os.environ["REENTRY_BUILD_DIR"]
    double = os.environ["REENTRY_DOUBLE_BIN"]
    synth = os.path.join(build, "tools", "logtools", "reentry_synth_log")
    loginfo = os.path.join(build, "tools", "logtools", "reentry_loginfo")
    log2csv = os.path.join(build, "tools", "logtools", "reentry_log2csv")
    d = a.dir
    src, good = os.path.join(d, "synth.lcm"), os.path.join(d, "run.lcm")
    rc, out, err = run([synth, src, "--ticks", "300", "--dt", "0.1"])
    assert rc == 0, err
    rc, out, err = run([double, "--replay", src, "--unsealed", "--replay-log", good])
    assert rc == 0, (rc, out, err)
    rc, out, err = run([double, "--replay", good, "--compare"])
    print("clean log:", out.strip())
    if rc != 0 or not out.startswith("identical"):
        print("FAIL: the clean log does not replay identical")
        return 1
    data = open(good, "rb").read()
    evs = events(data)
    assert evs, "the clean log does not parse"
    end_index = [i for i, e in enumerate(evs) if e[3] == b"RUN_CONTROL"]
    rng = random.Random(20261203)

    cases = []
    for _ in range(60):
        cases.append(("truncated", data[:rng.randrange(1, len(data))]))
    for _ in range(120):
        b = bytearray(data)
        for _ in range(rng.randint(1, 3)):
            b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
        cases.append(("bit_flips", bytes(b)))
    for _ in range(40):
        pos = rng.randrange(len(data))
        cases.append(("garbage", data[:pos] + bytes(rng.getrandbits(8) for _ in range(rng.randint(1, 300))) + data[pos:]))
    for _ in range(30):
        o, n, *_ = evs[rng.randrange(len(evs))]
        cases.append(("event_removed", data[:o] + data[o + n:]))
    for _ in range(20):
        o, n, *_ = evs[rng.randrange(len(evs))]
        cases.append(("event_duplicated", data[:o + n] + data[o:o + n] + data[o + n:]))
    for _ in range(20):
        i = rng.randrange(len(evs) - 1)
        (o1, n1, *_), (o2, n2, *_) = evs[i], evs[i + 1]
        cases.append(("events_swapped", data[:o1] + data[o2:o2 + n2] + data[o1:o1 + n1] + data[o2 + n2:]))
    for _ in range(20):
        o, n, *_ = evs[rng.randrange(len(evs))]
        b = bytearray(data)
        b[o + 24:o + 28] = struct.pack(">i", rng.choice([0x7FFFFFFF, -1, 0x10000000, len(data)]))
        cases.append(("huge_length", bytes(b)))
    # A framing-valid log without its END_OF_RUN, and one cut at an event boundary (renumbered).
    kept = [(c, p, 0) for i, (_, _, _, c, p) in enumerate(evs) if i not in end_index]
    for _ in range(10):
        cases.append(("no_end_of_run", renumber(kept)))
        cut = rng.randrange(1, len(evs) - 1)
        cases.append(("cut_at_event", renumber([(c, p, 0) for (_, _, _, c, p) in evs[:cut]])))
        drop = rng.randrange(len(evs) - 4)
        cases.append(("event_dropped_renumbered",
                      renumber([(c, p, 0) for i, (_, _, _, c, p) in enumerate(evs) if i != drop])))

    failures, stats = [], {}
    path = os.path.join(d, "damaged.lcm")
    cases = [(kind, blob) for kind, blob in cases if blob != data]  # (two flips of one bit cancel)
    for i, (kind, blob) in enumerate(cases):
        with open(path, "wb") as f:
            f.write(blob)
        results = {}
        for tool, cmd in (("replay", [double, "--replay", path, "--compare"]),
                          ("loginfo", [loginfo, "--json", path]),
                          ("log2csv", [log2csv, path, "--out", os.path.join(d, "csv")])):
            rc, out, err = run(cmd)
            results[tool] = (rc, out)
            if rc < 0 or rc >= 128 or "Sanitizer" in err or "runtime error" in err:
                failures.append("%s case %d (%s): exit %d %s" % (tool, i, kind, rc, err.strip()[-300:]))
            elif tool != "replay" and rc not in (0, 2, 6):  # ok, not a log, damaged (tools/README.md)
                failures.append("%s case %d (%s): exit %d" % (tool, i, kind, rc))
        rc, out = results["replay"]
        verdict = out.split(":")[0].split(" (")[0].strip() or "exit %d" % rc
        stats.setdefault(kind, {}).setdefault(verdict, 0)
        stats[kind][verdict] += 1
        if out.startswith("identical"):
            failures.append("replay case %d (%s): a damaged log was called identical: %s" % (i, kind, out.strip()))
        elif rc == 0:
            failures.append("replay case %d (%s): exit 0 without 'identical': %s" % (i, kind, out.strip()))
    print("%d damaged logs x 3 tools; replay verdicts by damage:" % len(cases))
    for kind, v in stats.items():
        print("  %-26s %s" % (kind, ", ".join("%s %d" % kv for kv in sorted(v.items()))))
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""Monte Carlo campaigns on a Slurm cluster (tools/mc --slurm; tools/README.md, "On a cluster").

  tools/mc --slurm --mission M --runs N --seed S --out DIR [reentry_mc options]
           [--array-tasks K] [--cpus-per-task C] [--partition P] [--time T] [--sbatch OPT ...]
           [--wait] [--poll S]
  tools/mc --slurm --resume DIR [--cpus-per-task C] [--partition P] [--time T] [--wait]

Writes two job scripts into DIR/slurm/ and submits them with sbatch: an array job whose task i
flies the existing shard `reentry_mc ... --shard i/K --out DIR/shards/i` (all reentry_mc options,
e.g. --oracle or --dispersions stress, pass through), and a merge job that depends on it
(afterok) and runs `tools/mc --merge DIR/shards/0 ... --out DIR` (runs.jsonl, report.json, plots).
The scripts name the build and the repository by absolute path: both, and DIR, must be on a
filesystem the compute nodes share. DIR/slurm/campaign.json keeps the campaign (its reentry_mc
arguments, K, the submissions); --resume DIR resubmits only the shards whose results are missing
or incomplete, then the merge. --wait follows the jobs (scontrol, sacct once a job has left the
controller) with a progress line until the merge ends; a shard that ends other than COMPLETED
is named with its Slurm state, the merge (which can then never run) is cancelled.
Exit: 0 submitted (or, with --wait, merged); 1 the campaign failed on the cluster; 2 usage;
3 a Slurm command failed."""
import argparse
import datetime
import json
import os
import re
import shlex
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
TERMINAL_OK = {"COMPLETED"}
TERMINAL_BAD = {"FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY", "PREEMPTED", "BOOT_FAIL",
                "DEADLINE", "REVOKED", "SPECIAL_EXIT"}
# Set by reentry_mc per task, or meaningless for a campaign split by this script.
REFUSED = {"--shard": "the array tasks are the shards", "--merge": "the merge job merges"}


class SlurmError(Exception):
    pass


def fail(msg, code=2):
    print(f"tools/mc --slurm: {msg}", file=sys.stderr)
    sys.exit(code)


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="tools/mc --slurm", add_help=True, allow_abbrev=False,
                                 description="Monte Carlo campaign as a Slurm array job + merge job")
    ap.add_argument("--slurm", action="store_true", required=True)
    ap.add_argument("--out", help="campaign directory (on the shared filesystem)")
    ap.add_argument("--resume", metavar="DIR", help="resubmit the shards of DIR whose results are missing")
    ap.add_argument("--array-tasks", type=int, default=None, help="K shards = array tasks (default 10, <= runs)")
    ap.add_argument("--cpus-per-task", type=int, default=None, help="CPUs of one shard task (its --jobs; default 1)")
    ap.add_argument("--jobs", type=int, default=None, help="parallel runs in one task (default: --cpus-per-task)")
    ap.add_argument("--partition", default=None)
    ap.add_argument("--time", default=None, help="time limit of one task (Slurm format, e.g. 2:00:00)")
    ap.add_argument("--sbatch", action="append", default=[], metavar="OPT",
                    help="extra sbatch option for both jobs, e.g. --sbatch=--account=gnc (repeatable)")
    ap.add_argument("--wait", action="store_true", help="follow the jobs until the merge ends")
    ap.add_argument("--poll", type=float, default=5.0, help="seconds between queue polls with --wait")
    args, mc_args = ap.parse_known_args(argv)
    for a in mc_args:
        if a.split("=")[0] in REFUSED:
            fail(f"{a.split('=')[0]} is not for a Slurm campaign ({REFUSED[a.split('=')[0]]})")
    if args.resume and (args.out or mc_args or args.array_tasks):
        fail("--resume DIR takes the campaign from DIR/slurm/campaign.json: only --cpus-per-task, --jobs, "
             "--partition, --time, --sbatch, --wait, --poll go with it")
    if not args.resume and not args.out:
        fail("--out DIR is required (the campaign directory, on the shared filesystem)")
    if args.poll <= 0 or (args.cpus_per_task is not None and args.cpus_per_task < 1) or \
            (args.jobs is not None and args.jobs < 1):
        fail("--poll, --cpus-per-task and --jobs must be positive")
    return args, mc_args


def option_value(mc_args, name):
    """The value of `name V` or `name=V` in the reentry_mc arguments (the last one wins)."""
    value = None
    for i, a in enumerate(mc_args):
        if a == name and i + 1 < len(mc_args):
            value = mc_args[i + 1]
        elif a.startswith(name + "="):
            value = a.split("=", 1)[1]
    return value


def absolute_mission(mc_args):
    """A mission given as a file relative to the submitting directory becomes an absolute path."""
    out = list(mc_args)
    for i, a in enumerate(out):
        if a == "--mission" and i + 1 < len(out) and os.path.isfile(out[i + 1]):
            out[i + 1] = os.path.abspath(out[i + 1])
        elif a.startswith("--mission=") and os.path.isfile(a.split("=", 1)[1]):
            out[i] = "--mission=" + os.path.abspath(a.split("=", 1)[1])
    return out


def new_campaign(args, mc_args):
    out = os.path.abspath(args.out)
    runs_arg = option_value(mc_args, "--runs")
    if option_value(mc_args, "--mission") is None or runs_arg is None:
        fail("--mission and --runs N are required")
    try:
        runs = int(runs_arg)
    except ValueError:
        fail(f"--runs must be an integer, got '{runs_arg}'")
    k = args.array_tasks if args.array_tasks is not None else min(10, runs)
    if runs < 1 or k < 1 or k > runs:
        fail(f"need 1 <= --array-tasks ({k}) <= --runs ({runs})")
    if os.path.exists(os.path.join(out, "slurm", "campaign.json")):
        fail(f"{out} already holds a Slurm campaign: --resume {out}, or another --out")
    if os.path.isdir(out) and any(n.startswith("runs") and n.endswith(".jsonl") for n in os.listdir(out)):
        fail(f"{out} already holds campaign records: choose another --out")
    build = os.path.abspath(os.environ.get("REENTRY_BUILD_DIR", os.path.join(REPO, "build")))
    return {"out": out, "runs": runs, "array_tasks": k, "mc_args": absolute_mission(mc_args), "build": build,
            "repo": REPO, "submissions": []}


def shard_dir(c, i):
    return os.path.join(c["out"], "shards", str(i))


def shard_file(c, i):
    return os.path.join(shard_dir(c, i), f"runs_shard_{i}_of_{c['array_tasks']}.jsonl")


def shard_complete(c, i):
    """True when shard i's run file holds exactly its runs (r % K == i), each a parsed record."""
    want = set(range(i, c["runs"], c["array_tasks"]))
    got = set()
    try:
        with open(shard_file(c, i)) as f:
            for line in f:
                if line.strip():
                    got.add(json.loads(line)["run"])
    except (OSError, ValueError, KeyError, TypeError):
        return False
    return got == want


def sbatch_header(c, args, name, log):
    lines = ["#!/bin/bash", f"#SBATCH --job-name={name}", f"#SBATCH --output={log}", f"#SBATCH --chdir={c['out']}"]
    if args.partition:
        lines.append(f"#SBATCH --partition={args.partition}")
    if args.time:
        lines.append(f"#SBATCH --time={args.time}")
    return lines


def write_scripts(c, args):
    """DIR/slurm/shard.sbatch (array task i = shard i/K) and DIR/slurm/merge.sbatch."""
    mc = os.path.join(c["build"], "tools", "montecarlo", "reentry_mc")
    if not os.access(mc, os.X_OK):
        fail(f"missing binary {mc} (build on the shared filesystem first, or set REENTRY_BUILD_DIR)")
    sdir = os.path.join(c["out"], "slurm")
    os.makedirs(os.path.join(sdir, "logs"), exist_ok=True)
    cpus = args.cpus_per_task or 1
    jobs = args.jobs or cpus
    mission = os.path.basename(option_value(c["mc_args"], "--mission") or "mc").replace(".toml", "")
    k = c["array_tasks"]
    shard = sbatch_header(c, args, f"mc-{mission}", os.path.join(sdir, "logs", "shard_%a_job_%A.out"))
    shard += [f"#SBATCH --cpus-per-task={cpus}", "# Array task i flies shard i/K of the campaign.", "set -u",
              "i=${SLURM_ARRAY_TASK_ID:?not an array task}",
              f"export REENTRY_BUILD_DIR={shlex.quote(c['build'])}",
              f"exec {shlex.quote(mc)} {' '.join(shlex.quote(a) for a in c['mc_args'])} --jobs {jobs} "
              f"--shard \"$i/{k}\" --out {shlex.quote(os.path.join(c['out'], 'shards'))}/\"$i\""]
    merge = sbatch_header(c, args, f"mc-{mission}-merge", os.path.join(sdir, "logs", "merge_job_%j.out"))
    shard_dirs = " ".join(shlex.quote(shard_dir(c, i)) for i in range(k))
    merge += ["#SBATCH --cpus-per-task=1", "# Runs after every shard task succeeded (afterok).", "set -u",
              f"export REENTRY_BUILD_DIR={shlex.quote(c['build'])}",
              f"exec {shlex.quote(os.path.join(c['repo'], 'tools', 'mc'))} --merge {shard_dirs} "
              f"--out {shlex.quote(c['out'])}"]
    for name, lines in (("shard.sbatch", shard), ("merge.sbatch", merge)):
        with open(os.path.join(sdir, name), "w") as f:
            f.write("\n".join(lines) + "\n")


def run(cmd, check=True):
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    except FileNotFoundError:
        raise SlurmError(f"{cmd[0]} not found (install slurm-client, or run on the cluster's login node)")
    except subprocess.TimeoutExpired:
        raise SlurmError(f"{' '.join(cmd)} did not answer within 120 s")
    if check and p.returncode != 0:
        raise SlurmError(f"{' '.join(cmd)}: {p.stderr.strip() or p.stdout.strip()}")
    return p


def sbatch(args, extra):
    p = run(["sbatch", "--parsable"] + args.sbatch + extra)
    return p.stdout.strip().split(";")[0]


def array_spec(shards):
    """Slurm's array index list: consecutive indices as ranges (0-3,5,7-8)."""
    parts, start = [], None
    for j, i in enumerate(shards):
        if start is None:
            start = i
        if j + 1 == len(shards) or shards[j + 1] != i + 1:
            parts.append(str(start) if start == i else f"{start}-{i}")
            start = None
    return ",".join(parts)


def submit(c, args, shards):
    sdir = os.path.join(c["out"], "slurm")
    sub = {"time": datetime.datetime.now().isoformat(timespec="seconds"), "shards": shards}
    if shards:
        sub["array_job"] = sbatch(args, [f"--array={array_spec(shards)}", os.path.join(sdir, "shard.sbatch")])
        dep = [f"--dependency=afterok:{sub['array_job']}"]
    else:
        dep = []
    try:
        sub["merge_job"] = sbatch(args, dep + [os.path.join(sdir, "merge.sbatch")])
    except SlurmError:
        if shards:
            run(["scancel", sub["array_job"]], check=False)
        raise
    c["submissions"].append(sub)
    save(c)
    k, n = c["array_tasks"], c["runs"]
    if shards:
        print(f"slurm: shards: array job {sub['array_job']} (tasks {array_spec(shards)} of {k}, {n} runs in all, "
              f"up to {-(-n // k)} per task)")
    print(f"slurm: merge: job {sub['merge_job']}" + (f" (after array job {sub['array_job']} succeeds)" if shards else ""))
    print(f"slurm: results in {c['out']} (shards in {c['out']}/shards, job logs in {sdir}/logs)")
    return sub


def save(c):
    path = os.path.join(c["out"], "slurm", "campaign.json")
    with open(path + ".tmp", "w") as f:
        json.dump(c, f, indent=1)
    os.replace(path + ".tmp", path)


def load(out):
    path = os.path.join(os.path.abspath(out), "slurm", "campaign.json")
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail(f"--resume: cannot read {path}: {e}")


def expand_tasks(spec):
    """Array task ids of a scontrol/sacct field: '3', '1-3', '1,3', '1-7%2' (throttle dropped)."""
    out = []
    for part in spec.split("%")[0].strip("[]").split(","):
        if "-" in part:
            a, b = part.split("-")
            out += list(range(int(a), int(b) + 1))
        elif part.isdigit():
            out.append(int(part))
    return out


def parse_scontrol(text):
    states = {}
    for line in text.splitlines():
        f = dict(kv.split("=", 1) for kv in line.split() if "=" in kv)
        if "JobState" not in f:
            continue
        for t in (expand_tasks(f["ArrayTaskId"]) if "ArrayTaskId" in f else [None]):
            states[t] = (f["JobState"], f.get("ExitCode", ""))
    return states


def sacct_states(job):
    """{task or None: (state, exit code)} from the accounting database, {} when it has none."""
    try:
        p = run(["sacct", "-n", "-P", "-X", "-j", job, "-o", "JobID,State,ExitCode"], check=False)
    except SlurmError:
        return {}
    states = {}
    for line in p.stdout.splitlines() if p.returncode == 0 else []:
        jobid, state, code = (line.split("|") + ["", ""])[:3]
        tail_ = jobid.split("_", 1)[1] if "_" in jobid else None
        for t in (expand_tasks(tail_) if tail_ else [None]):
            states[t] = (state.split()[0] if state else "UNKNOWN", code)
    return states


def job_states(job):
    """{array task or None: (Slurm state, exit code)} of a job: from the controller while it
    knows the job, then (after MinJobAge) from accounting, {} when neither has it; None when
    the controller did not answer (try again)."""
    p = run(["scontrol", "-o", "show", "job", job], check=False)
    if p.returncode == 0:
        return parse_scontrol(p.stdout)
    if "invalid job id" in (p.stderr + p.stdout).lower():
        return sacct_states(job)
    return None


def shard_states(c, sub):
    """{shard: (state, exit code)}; a shard whose job neither the controller nor accounting
    knows any more is judged by its results (COMPLETED when its run file is complete, else GONE)."""
    st = job_states(sub["array_job"]) if sub.get("array_job") else {}
    if st is None:
        return None
    return {i: st.get(i) or (("COMPLETED", "results present") if shard_complete(c, i) else ("GONE", ""))
            for i in sub["shards"]}


def merged_complete(c):
    try:
        with open(os.path.join(c["out"], "runs.jsonl")) as f:
            n = sum(1 for line in f if line.strip())
    except OSError:
        return False
    return n == c["runs"] and os.path.isfile(os.path.join(c["out"], "report.json"))


def merge_state(c, sub):
    st = job_states(sub["merge_job"])
    if st is None:
        return None
    return st.get(None) or (("COMPLETED", "results present") if merged_complete(c) else ("GONE", ""))


class Progress:
    """One updating line on a terminal; in a log (not a terminal) a plain line when the counts
    change, or every minute."""

    def __init__(self):
        self.tty = sys.stderr.isatty()
        self.last_text, self.last_time, self.t0 = None, 0.0, time.time()

    def show(self, text):
        now = time.time()
        line = f"slurm: {now - self.t0:5.0f} s  {text}"
        if self.tty:
            sys.stderr.write("\r" + line.ljust(100)[:120])
        elif text != self.last_text or now - self.last_time >= 60:
            sys.stderr.write(line + "\n")
        else:
            return
        sys.stderr.flush()
        self.last_text, self.last_time = text, now

    def note(self, msg):
        """A line of its own (on a terminal above the progress line, which is redrawn)."""
        if self.tty and self.last_text is not None:
            sys.stderr.write("\r" + " " * 120 + "\r")
            sys.stderr.flush()
            self.last_text = None
        print(msg, flush=True)

    def end(self):
        if self.tty and self.last_text is not None:
            sys.stderr.write("\n")
            self.last_text = None


def shard_log(c, sub, i):
    return os.path.join(c["out"], "slurm", "logs", f"shard_{i}_job_{sub['array_job']}.out")


def summary_text(c, shards, merge):
    """Counts over the whole campaign: shards not in this submission were complete before it."""
    k = c["array_tasks"]
    count = lambda pred: sum(1 for s, _ in shards.values() if pred(s))
    done = [i for i in range(k) if i not in shards or shards[i][0] in TERMINAL_OK]
    runs_done = sum(len(range(i, c["runs"], k)) for i in done)
    return (f"shards {len(done)}/{k} completed ({runs_done}/{c['runs']} runs), {count(lambda s: s == 'RUNNING')} running, "
            f"{count(lambda s: s == 'PENDING')} pending, {count(lambda s: s in TERMINAL_BAD or s == 'GONE')} failed; "
            f"merge {merge[0].lower()}")


def report_failed_shards(c, sub, shards, reported, progress):
    for i, (s, code) in sorted(shards.items()):
        if (s in TERMINAL_BAD or s == "GONE") and i not in reported:
            reported.add(i)
            why = f", exit code {code}" if code and code != "0:0" else ""
            progress.note(f"slurm: shard {i} (job {sub['array_job']}_{i}): {s}{why}; log {shard_log(c, sub, i)}")


def tail(path, n=20):
    try:
        with open(path) as f:
            return f.read().splitlines()[-n:]
    except OSError:
        return [f"(no log {path})"]


def finish(c, sub, merge, ok):
    log = os.path.join(c["out"], "slurm", "logs", f"merge_job_{sub['merge_job']}.out")
    if ok and merged_complete(c):
        print("\n".join(tail(log, 25)))
        print(f"slurm: campaign merged into {c['out']} (runs.jsonl, report.json)")
        return 0
    if ok:
        print(f"slurm: the merge job ended but {c['out']}/runs.jsonl does not hold the {c['runs']} runs")
    print(f"slurm: merge job {sub['merge_job']}: {merge[0]} (exit code {merge[1]}); log {log}:")
    print("\n".join("  " + line for line in tail(log, 10)))
    return 1


def follow(c, sub, args):
    """Polls until the merge ends (0) or cannot run because a shard failed (1)."""
    progress, reported, silent = Progress(), set(), 0
    while True:
        shards = shard_states(c, sub)
        merge = merge_state(c, sub)
        if shards is None or merge is None:
            silent += 1
            if silent * args.poll > 600:
                raise SlurmError("the Slurm controller has not answered for 10 minutes")
            time.sleep(args.poll)
            continue
        silent = 0
        progress.show(summary_text(c, shards, merge))
        bad = [i for i, (s, _) in shards.items() if s in TERMINAL_BAD or s == "GONE"]
        settled = all(s in TERMINAL_OK or s in TERMINAL_BAD or s == "GONE" for s, _ in shards.values())
        report_failed_shards(c, sub, shards, reported, progress)
        if settled and bad:
            progress.end()
            if merge[0] not in TERMINAL_OK | TERMINAL_BAD:
                run(["scancel", sub["merge_job"]], check=False)
                print(f"slurm: merge job {sub['merge_job']} cancelled (its shards did not all succeed)")
            print(f"slurm: {len(bad)} of {len(shards)} shards failed; resubmit them with: "
                  f"tools/mc --slurm --resume {c['out']} --wait")
            return 1
        if merge[0] in TERMINAL_OK or (merge[0] in TERMINAL_BAD | {"GONE"} and settled):
            progress.end()
            return finish(c, sub, merge, merge[0] in TERMINAL_OK)
        time.sleep(args.poll)


def slurm_options(c, args):
    """The sbatch options of this submission: those given now, else those of the campaign."""
    saved = c.get("slurm_options", {})
    for key in ("partition", "time", "cpus_per_task", "jobs"):
        if getattr(args, key) is None:
            setattr(args, key, saved.get(key))
    args.sbatch = args.sbatch or saved.get("sbatch", [])
    c["slurm_options"] = {key: getattr(args, key) for key in ("partition", "time", "cpus_per_task", "jobs", "sbatch")}


def resume(args):
    c = load(args.resume)
    slurm_options(c, args)
    last = c["submissions"][-1] if c["submissions"] else {}
    if last.get("array_job"):
        st = job_states(last["array_job"]) or {}
        active = sorted(t for t, (s, _) in st.items() if s not in TERMINAL_OK | TERMINAL_BAD)
        if active:
            fail(f"shards {array_spec(active)} of array job {last['array_job']} are still queued or running: "
                 f"wait for them (or scancel {last['array_job']}) before --resume")
    if last.get("merge_job"):
        m = (job_states(last["merge_job"]) or {}).get(None)
        if m and m[0] not in TERMINAL_OK | TERMINAL_BAD:
            run(["scancel", last["merge_job"]], check=False)
            print(f"slurm: cancelled the waiting merge job {last['merge_job']} of the last submission")
    missing = [i for i in range(c["array_tasks"]) if not shard_complete(c, i)]
    if not missing and merged_complete(c):
        print(f"slurm: {c['out']}: every shard and the merge are complete; nothing to resubmit")
        return 0
    print(f"slurm: resubmitting {len(missing)} of {c['array_tasks']} shards"
          + (f" ({array_spec(missing)}: results missing or incomplete)" if missing else "") + " and the merge")
    write_scripts(c, args)
    sub = submit(c, args, missing)
    return follow(c, sub, args) if args.wait else 0


def main(argv):
    args, mc_args = parse_args(argv)
    try:
        if args.resume:
            return resume(args)
        c = new_campaign(args, mc_args)
        slurm_options(c, args)
        write_scripts(c, args)
        sub = submit(c, args, list(range(c["array_tasks"])))
        return follow(c, sub, args) if args.wait else 0
    except SlurmError as e:
        print(f"tools/mc --slurm: {e}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("\ntools/mc --slurm: stopped following; the jobs go on (squeue; tools/mc --slurm --resume DIR "
              "resubmits what fails)", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/bin/bash
# Reproductions of issue 38 through the user-facing tools (CTest): reliability_tests.sh <case> <dir>
# Environment: REENTRY_BUILD_DIR; REENTRY_FSW_BIN (the guidance process tools/sil flies: the SIL
# test double, whose trivial law is fast); REAL_FSW (reentry_fsw, where the guidance matters);
# SYNTH_LOG (reentry_synth_log). Full filesystems are small tmpfs mounts inside `unshare -m`,
# interrupts are signals, every wait is bounded. Cases:
#   sil_args         bad arguments refused at once (2): --out "", --out without a value, --seed abc,
#                    -1, 2^64, --link-timeout-ticks 0, --mode x; no process started.
#   sil_full_disk    --out on a 2 MB tmpfs, a read-only one, a file: 8 and the file named, no traceback,
#                    no stale pids, no process left.
#   sil_rerun        x33 then x38 into one folder: the CSV files and plots are x38's; a foreign file
#                    in the folder is refused (2); a second run into a folder in use is refused (10).
#   sil_interrupt    SIGTERM and SIGINT to tools/sil mid-flight (realtime, lockstep) and in the first
#                    0.3 s, SIGKILL: 128 + signal, both children gone, logs sealed, no stale pids.
#   sil_setup        a mission the simulator cannot fly (entry latitude 90, a wind file with nan):
#                    refused at once (2) naming file, key and value, never "process died".
#   sil_seed         --seed 0 flies the dispersed draw 0, the record of tools/mc --seed 0; no --seed
#                    flies the nominal run, the record of tools/mc --nominal.
#   sil_deadlines    realtime with the simulator stopped for 0.6 s: its own missed deadlines counted;
#                    progress into a file as plain lines.
#   replay_mission   a run flown from a mission file replays identical against that file; the file
#                    changed, --mission of another mission, a realtime log: not replayable (12);
#                    --replay-log on a full tmpfs: 8, never "identical".
#   logtools_write   log2csv into a read-only or full folder, loginfo into /dev/full, logmerge onto
#                    a full tmpfs: 8 with the file named.
#   mc_write         --out on an 8 kB tmpfs, --trace on a small one, an uncreatable --out: 8, the
#                    folder checked before the campaign flies, no "successful" over empty records.
#   mc_merge         shards of other missions, seeds, shard counts, a missing shard, run -1, run
#                    1e12, a string miss_km: refused (2) with the reason; nothing written.
#   mc_args          --seed -1, --runs 2e9, --shard 1/3x, --out without a value, a mission the
#                    simulator cannot fly: 2 at once; progress into a file (a campaign, an oracle
#                    campaign): plain lines, no frames.
set -u
case_name="$1"; dir="$2"
repo="$(cd "$(dirname "$0")/../.." && pwd)"
build="${REENTRY_BUILD_DIR:?}"
sil="$repo/tools/sil" mc="$repo/tools/mc" replay="$repo/tools/replay"
fails=0
fail() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }
die() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$dir"; mkdir -p "$dir/tmp"
export TMPDIR="$dir/tmp"  # what the tools leave in the temporary directory is checked, and stays here
export REENTRY_SIL_PLOTS="${REENTRY_SIL_PLOTS:-0}"

# expect RC WANT TEXT FILE WHAT: the exit status and a message in FILE.
expect() {
  local rc=$1 want=$2 text=$3 file=$4 what=$5
  if [[ $rc -ne $want ]]; then fail "$what: exit $rc, want $want: $(tail -3 "$file" | tr '\n' ' ')"; return; fi
  if [[ -n "$text" ]] && ! grep -q -- "$text" "$file"; then fail "$what: no '$text' in: $(tail -3 "$file" | tr '\n' ' ')"; return; fi
  if grep -q Traceback "$file"; then fail "$what: a Python traceback"; return; fi
  echo "ok: $what: exit $rc: $(grep -m1 -- "${text:-.}" "$file" | cut -c1-160)"
}
# on_tmpfs SIZE[,ro] MOUNTPOINT CMD...: CMD with a fresh tmpfs at MOUNTPOINT in a private mount namespace.
on_tmpfs() {
  local opts=$1 mnt=$2; shift 2
  mkdir -p "$mnt"
  unshare -m -- sh -c 'mount -t tmpfs -o "size=$1" tmpfs "$2" && shift 2 && exec "$@"' sh "$opts" "$mnt" "$@"
}
# no_process_of BIN...: none of our builds' processes runs (the tests run serially).
no_process_left() {
  local b
  for b in "$build/sim_truth/app/reentry_sim_lcm" "${REENTRY_FSW_BIN:-}" "${REAL_FSW:-}"; do
    [[ -n "$b" ]] && pgrep -f -- "^$b " >/dev/null && { fail "$1: a process of $b outlived tools/sil"; return 1; }
  done
  return 0
}
alive() { ps -o stat= -p "$1" 2>/dev/null | grep -qv Z; }  # running (an exited zombie is not)
x33_copy() {  # a copy of config/ (missions, vehicles, environment) to edit
  rm -rf "$dir/cfg"; cp -r "$repo/config" "$dir/cfg"
}

case "$case_name" in
  sil_args)
    for args in '--out|' '--out' '--seed|abc' '--seed|-1' '--seed|18446744073709551616' '--link-timeout-ticks|0' \
                '--mode|fast'; do
      IFS='|' read -r -a a <<< "$args"
      [[ "$args" == *'|' ]] && a+=("")
      t0=$(date +%s%N)
      "$sil" --mission x33 "${a[@]}" > "$dir/out.txt" 2>&1; rc=$?
      ms=$(( ($(date +%s%N) - t0) / 1000000 ))
      expect $rc 2 "tools/sil: " "$dir/out.txt" "tools/sil --mission x33 ${a[*]}"
      (( ms < 1500 )) || fail "tools/sil ${a[*]}: refused after $ms ms (want at once)"
    done
    [[ ! -e "$dir/sil_out" && ! -e "$repo/sil_out/pids" ]] || fail "a refused run left an output folder"
    ;;
  sil_full_disk)
    on_tmpfs 2m "$dir/full" "$sil" --mission x33 --out "$dir/full/run" > "$dir/full.txt" 2>&1; rc=$?
    expect $rc 8 "write failed" "$dir/full.txt" "tools/sil --out on a 2 MB tmpfs"
    grep -q "No space left on device" "$dir/full.txt" || fail "full disk: the reason is not named"
    on_tmpfs 2m,ro "$dir/ro" "$sil" --mission x33 --out "$dir/ro/run" > "$dir/ro.txt" 2>&1; rc=$?
    expect $rc 8 "write failed" "$dir/ro.txt" "tools/sil --out in a read-only folder"
    : > "$dir/a_file"
    "$sil" --mission x33 --out "$dir/a_file" > "$dir/file.txt" 2>&1; rc=$?
    expect $rc 8 "not a directory" "$dir/file.txt" "tools/sil --out a file"
    no_process_left "full disk"
    ;;
  sil_rerun)
    "$sil" --mission x33 --out "$dir/run" > "$dir/x33.txt" 2>&1; rc=$?
    [[ $rc -le 1 ]] || die "x33: exit $rc"
    REENTRY_SIL_PLOTS=1 "$sil" --mission x38 --out "$dir/run" > "$dir/x38.txt" 2>&1; rc=$?
    [[ $rc -le 1 ]] || die "x38 into the same folder: exit $rc: $(tail -2 "$dir/x38.txt")"
    /usr/bin/python3 - "$dir/run" <<'PY' || fail "the second run's folder holds the first run's data"
import csv, json, os, sys
d = sys.argv[1]
s = json.load(open(os.path.join(d, "summary.json")))
info = json.load(open(os.path.join(d, "run_info.json")))
rows = list(csv.DictReader(open(os.path.join(d, "run_csv", "TRUTH.csv"))))
want = info["channels"]["TRUTH"]["messages"]
assert s["mission"] == "x38", s["mission"]
assert len(rows) == want, "TRUTH.csv has %d rows, the x38 log %d" % (len(rows), want)
log_t = os.path.getmtime(os.path.join(d, "run.lcm"))
pngs = [f for f in os.listdir(os.path.join(d, "plots")) if f.endswith(".png")]
assert pngs and all(os.path.getmtime(os.path.join(d, "plots", f)) >= log_t for f in pngs), "stale plots"
print("ok: x33 then x38 into one folder: summary, %d TRUTH rows and %d plots are x38's" % (len(rows), len(pngs)))
PY
    ! grep -q $'\r' "$dir/x38.txt" || fail "carriage-return frames in a log file"
    touch "$dir/run/my_notes.txt"
    "$sil" --mission x33 --out "$dir/run" > "$dir/foreign.txt" 2>&1; rc=$?
    expect $rc 2 "my_notes.txt" "$dir/foreign.txt" "tools/sil into a folder with a foreign file"
    rm -f "$dir/run/my_notes.txt"
    "$sil" --mission x33 --mode realtime --out "$dir/run" > "$dir/first.txt" 2>&1 &
    first=$!
    for _ in $(seq 1 100); do [[ -s "$dir/run/pids" ]] && break; sleep 0.05; done
    "$sil" --mission x33 --out "$dir/run" > "$dir/second.txt" 2>&1; rc=$?
    expect $rc 10 "in use" "$dir/second.txt" "a second tools/sil into a folder in use"
    kill -TERM $first; wait $first
    no_process_left "rerun"
    ;;
  sil_interrupt)
    # signal, delay [s], mode: mid-flight realtime, mid-flight lockstep, before the simulator starts.
    for spec in TERM:2.0:realtime INT:2.0:realtime INT:0.1:lockstep TERM:0.05:lockstep; do
      IFS=: read -r sig delay mode <<< "$spec"
      out="$dir/int_${sig}_${mode}_$delay"
      # A background job of a script ignores SIGINT; a terminal's foreground job (Ctrl-C) does not.
      env --default-signal=INT "$sil" --mission x33 --mode "$mode" --out "$out" > "$out.txt" 2>&1 &
      pid=$!
      sleep "$delay"
      pids=$(awk '{print $2}' "$out/pids" 2>/dev/null)
      kill -"$sig" $pid
      t0=$(date +%s%N)
      wait $pid; rc=$?
      ms=$(( ($(date +%s%N) - t0) / 1000000 ))
      want=$(( 128 + $(kill -l "$sig") ))
      # Before its first line runs (the shell starting) a signal ends tools/sil silently: nothing started.
      msg="interrupted"; [[ "$delay" == 2.0 ]] || msg=""
      expect $rc $want "$msg" "$out.txt" "SIG$sig to tools/sil after $delay s ($mode), ended in $ms ms"
      for p in $pids; do alive "$p" && fail "SIG$sig: process $p outlived tools/sil"; done
      [[ ! -e "$out/pids" ]] || fail "SIG$sig: stale $out/pids"
      (( ms < 6000 )) || fail "SIG$sig: tools/sil took $ms ms to end"
      if [[ "$delay" == 2.0 ]]; then
        for l in sim fsw; do
          "$build/tools/logtools/reentry_loginfo" --json --lenient "$out/$l.lcm" > "$out/$l.info" 2>/dev/null
          grep -q '"sealed": true' "$out/$l.info" || fail "SIG$sig: $l.lcm not sealed"
        done
        grep -q '"interrupted": "SIG'"$sig"'"' "$out/summary.json" || fail "SIG$sig: the summary does not say interrupted"
      fi
      no_process_left "SIG$sig" || true
    done
    # SIGKILL cannot be trapped: the children end with tools/sil (parent-death signal).
    "$sil" --mission x33 --mode realtime --out "$dir/killed" > "$dir/killed.txt" 2>&1 &
    pid=$!
    for _ in $(seq 1 100); do [[ -s "$dir/killed/pids" ]] && break; sleep 0.05; done
    pids=$(awk '{print $2}' "$dir/killed/pids")
    # The parent-death signal is set by setpriv before it executes the binary: wait for both.
    for p in $pids; do
      for _ in $(seq 1 100); do [[ "$(ps -o comm= -p "$p")" == reentry_* || "$(ps -o comm= -p "$p")" == sil_* ]] && break; sleep 0.02; done
    done
    kill -KILL $pid; wait $pid 2>/dev/null
    sleep 1.5
    left=0; for p in $pids; do alive "$p" && { left=1; kill -KILL "$p"; }; done
    [[ $left -eq 0 ]] && echo "ok: SIGKILL to tools/sil: both children ended with it" || fail "SIGKILL: orphans left"
    # Its folder of the processes' messages (outside --out) is removed by the next run.
    ls -d "$TMPDIR/reentry_sil.$pid."* > /dev/null 2>&1 || fail "SIGKILL: no message folder of pid $pid to sweep"
    "$sil" --mission x33 --out "$dir/after_kill" > "$dir/after_kill.txt" 2>&1
    ls -d "$TMPDIR/reentry_sil.$pid."* > /dev/null 2>&1 && fail "SIGKILL: the killed run's message folder was left" ||
      echo "ok: the next tools/sil removed the killed run's message folder"
    [[ -z "$(ls -A "$TMPDIR")" ]] || fail "tools/sil left files in TMPDIR: $(ls "$TMPDIR" | head -3 | tr '\n' ' ')"
    ;;
  sil_setup)
    x33_copy
    sed -i 's/^latitude_deg = -23.75/latitude_deg = 90.0/' "$dir/cfg/missions/x33.toml"
    t0=$(date +%s%N)
    "$sil" --mission "$dir/cfg/missions/x33.toml" --out "$dir/lat90" > "$dir/lat90.txt" 2>&1; rc=$?
    ms=$(( ($(date +%s%N) - t0) / 1000000 ))
    expect $rc 2 "entry.latitude_deg" "$dir/lat90.txt" "tools/sil with entry latitude 90 ($ms ms)"
    (( ms < 3000 )) || fail "entry latitude 90: refused after $ms ms"
    grep -q "process died\|lost the link" "$dir/lat90.txt" && fail "a set-up error reported as a dead process"
    x33_copy
    awk 'NR == 4 {$8 = "nan"} {print}' "$repo/config/environment/earthgram_nominal_wind.txt" > "$dir/cfg/environment/earthgram_nominal_wind.txt"
    "$sil" --mission "$dir/cfg/missions/x33.toml" --out "$dir/nan" > "$dir/nan.txt" 2>&1; rc=$?
    expect $rc 2 "earthgram_nominal_wind.txt:4" "$dir/nan.txt" "tools/sil with nan in the wind file"
    ;;
  sil_seed)
    REENTRY_FSW_BIN="$REAL_FSW" "$sil" --mission x33 --seed 0 --out "$dir/s0" > "$dir/s0.txt" 2>&1 || true
    REENTRY_FSW_BIN="$REAL_FSW" "$sil" --mission x33 --out "$dir/nominal" > "$dir/nominal.txt" 2>&1 || true
    "$build/tools/montecarlo/reentry_mc" --mission x33 --runs 1 --seed 0 --out "$dir/mc0" > /dev/null 2>&1 || fail "mc --seed 0"
    "$build/tools/montecarlo/reentry_mc" --mission x33 --runs 1 --seed 0 --nominal --out "$dir/mcn" > /dev/null 2>&1 || fail "mc --nominal"
    /usr/bin/python3 - "$dir" <<'PY' || fail "tools/sil and tools/mc fly different runs for one seed"
import json, os, sys
d = sys.argv[1]
for sil, mc, what in (("s0", "mc0", "--seed 0"), ("nominal", "mcn", "nominal")):
    s = json.load(open(os.path.join(d, sil, "summary.json")))
    r = json.loads(open(os.path.join(d, mc, "runs.jsonl")).readline())
    assert s["taem_miss_km"] == r["miss_km"] and s["max_g"] == r["max_g"], (what, s["taem_miss_km"], r["miss_km"])
    print("ok: %s: tools/sil and tools/mc miss %.6f km, max %.4f g" % (what, r["miss_km"], r["max_g"]))
a = json.load(open(os.path.join(d, "s0", "summary.json")))["taem_miss_km"]
b = json.load(open(os.path.join(d, "nominal", "summary.json")))["taem_miss_km"]
assert a != b, "seed 0 flew the nominal run"
PY
    ;;
  sil_deadlines)
    REENTRY_SIM_ARGS="--stop-after 8" "$sil" --mission x33 --mode realtime --link-timeout-ticks 50 --out "$dir/rt" \
      > "$dir/rt.txt" 2>&1 &
    pid=$!
    for _ in $(seq 1 100); do [[ -s "$dir/rt/pids" ]] && break; sleep 0.05; done
    sim_pid=$(awk '$1 == "sim" {print $2}' "$dir/rt/pids")
    sleep 2; kill -STOP "$sim_pid"; sleep 0.6; kill -CONT "$sim_pid"
    wait $pid; rc=$?
    [[ $rc -le 1 ]] || fail "realtime run: exit $rc: $(tail -2 "$dir/rt.txt")"
    misses=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get("sim_deadline_misses"))' "$dir/rt/summary.json")
    [[ "$misses" =~ ^[0-9]+$ ]] && (( misses >= 3 )) && echo "ok: the simulator counted $misses missed deadlines of its own" ||
      fail "sim_deadline_misses = $misses after a 0.6 s stall (want >= 3)"
    ! grep -q $'\r' "$dir/rt.txt" || fail "carriage-return frames in a log file"
    ;;
  replay_mission)
    export REENTRY_FSW_BIN="$REAL_FSW"
    x33_copy
    sed -i 's/^replan_period_s = .*/replan_period_s = 37.0/' "$dir/cfg/missions/x33.toml"
    "$sil" --mission "$dir/cfg/missions/x33.toml" --out "$dir/run" > "$dir/run.txt" 2>&1; rc=$?
    [[ $rc -le 1 ]] || die "the run from a mission file: exit $rc"
    "$replay" "$dir/run/run.lcm" > "$dir/r1.txt" 2>&1; rc=$?
    expect $rc 0 "identical" "$dir/r1.txt" "replay of a run flown from a mission file"
    "$replay" "$dir/run/run.lcm" --mission x38 > "$dir/r2.txt" 2>&1; rc=$?
    expect $rc 12 "another mission" "$dir/r2.txt" "replay of an x33 log as x38"
    echo "# edited after the run" >> "$dir/cfg/missions/x33.toml"
    "$replay" "$dir/run/run.lcm" > "$dir/r3.txt" 2>&1; rc=$?
    expect $rc 12 "changed" "$dir/r3.txt" "replay after the mission file changed"
    on_tmpfs 200k "$dir/full" "$replay" "$dir/run/run.lcm" --mission "$dir/cfg/missions/x33.toml" \
      --replay-log "$dir/full/replay.lcm" > "$dir/r4.txt" 2>&1; rc=$?
    expect $rc 8 "write failed" "$dir/r4.txt" "replay --replay-log on a 200 kB tmpfs"
    grep -q identical "$dir/r4.txt" && fail "a truncated --replay-log was called identical"
    REENTRY_SIM_ARGS="--stop-after 3" "$sil" --mission x33 --mode realtime --out "$dir/rt" > "$dir/rt.txt" 2>&1
    "$replay" "$dir/rt/run.lcm" > "$dir/r5.txt" 2>&1; rc=$?
    expect $rc 12 "realtime" "$dir/r5.txt" "replay of a realtime log"
    ;;
  logtools_write)
    "$SYNTH_LOG" "$dir/run.lcm" --ticks 600 > /dev/null || die "synth log"
    on_tmpfs 1m,ro "$dir/ro" "$repo/tools/log2csv" "$dir/run.lcm" --out "$dir/ro/csv" > "$dir/ro.txt" 2>&1; rc=$?
    expect $rc 8 "write failed" "$dir/ro.txt" "log2csv into a read-only folder"
    grep -q "wrote" "$dir/ro.txt" && fail "log2csv said 'wrote' over files it could not write"
    on_tmpfs 16k "$dir/full" "$repo/tools/log2csv" "$dir/run.lcm" --out "$dir/full/csv" > "$dir/full.txt" 2>&1; rc=$?
    expect $rc 8 "No space left on device" "$dir/full.txt" "log2csv into a 16 kB tmpfs"
    "$repo/tools/loginfo" --json "$dir/run.lcm" > /dev/full 2> "$dir/info.txt"; rc=$?
    expect $rc 8 "write failed" "$dir/info.txt" "loginfo --json into /dev/full"
    on_tmpfs 16k "$dir/mfull" "$build/tools/logtools/reentry_logmerge" "$dir/mfull/m.lcm" "$dir/run.lcm" > "$dir/merge.txt" 2>&1; rc=$?
    expect $rc 8 "write failed" "$dir/merge.txt" "logmerge onto a 16 kB tmpfs"
    ;;
  mc_write)
    t0=$(date +%s%N)
    on_tmpfs 8k "$dir/tiny" "$mc" --mission x33 --runs 4 --seed 7 --out "$dir/tiny/mc" > "$dir/tiny.txt" 2>&1; rc=$?
    ms=$(( ($(date +%s%N) - t0) / 1000000 ))
    expect $rc 8 "write failed" "$dir/tiny.txt" "tools/mc --out on an 8 kB tmpfs ($ms ms)"
    grep -q "successful" "$dir/tiny.txt" && fail "'successful' printed over records that were not written"
    on_tmpfs 60k "$dir/trace" "$mc" --mission x33 --runs 2 --seed 7 --trace --out "$dir/trace/mc" > "$dir/trace.txt" 2>&1; rc=$?
    expect $rc 8 "write failed" "$dir/trace.txt" "tools/mc --trace on a 60 kB tmpfs"
    grep -q "0/0 successful\|nan km" "$dir/trace.txt" && fail "an empty campaign reported"
    t0=$(date +%s%N)
    on_tmpfs 1m,ro "$dir/ro" "$mc" --mission x33 --runs 50 --seed 7 --out "$dir/ro/a/b" > "$dir/ro.txt" 2>&1; rc=$?
    ms=$(( ($(date +%s%N) - t0) / 1000000 ))
    expect $rc 8 "write failed" "$dir/ro.txt" "tools/mc with an uncreatable --out ($ms ms)"
    (( ms < 5000 )) || fail "the uncreatable --out was found after $ms ms (the campaign flew first)"
    ;;
  mc_merge)
    m="$build/tools/montecarlo/reentry_mc"
    run_mc() { "$m" "$@" > /dev/null 2>&1 || fail "reentry_mc $*"; }
    run_mc --mission x33 --runs 4 --seed 11 --shard 0/2 --out "$dir/s0"
    run_mc --mission x33 --runs 4 --seed 11 --shard 1/2 --out "$dir/s1"
    run_mc --mission x38 --runs 4 --seed 11 --shard 1/2 --out "$dir/x38_s1"
    run_mc --mission x33 --runs 4 --seed 12 --shard 1/2 --out "$dir/seed12_s1"
    run_mc --mission x33 --runs 4 --seed 11 --shard 1/3 --out "$dir/k3_s1"
    "$m" --merge "$dir/s0" "$dir/s1" --out "$dir/good" > "$dir/good.txt" 2>&1 || fail "a whole campaign refused"
    refuse() {  # refuse TEXT DIRS...: the merge is refused naming TEXT, writes nothing
      local text=$1 out="$dir/bad_$RANDOM"; shift
      "$m" --merge "$@" --out "$out" > "$out.txt" 2>&1; local rc=$?
      expect $rc 2 "$text" "$out.txt" "merge of ${*##*/}"
      [[ ! -e "$out/runs.jsonl" ]] || fail "a refused merge wrote $out/runs.jsonl"
    }
    refuse "mission" "$dir/s0" "$dir/x38_s1"
    refuse "seed" "$dir/s0" "$dir/seed12_s1"
    refuse "shard count" "$dir/s0" "$dir/k3_s1"
    refuse "shard 1/2 missing" "$dir/s0"
    refuse "appears twice" "$dir/s0" "$dir/s0"
    tamper() {  # tamper NAME PYTHON-EXPRESSION-ON-r: a copy of s1 with its first record changed
      rm -rf "$dir/$1"; cp -r "$dir/s1" "$dir/$1"
      /usr/bin/python3 - "$dir/$1/runs_shard_1_of_2.jsonl" "$2" <<'PY'
import json, sys
lines = open(sys.argv[1]).read().splitlines()
r = json.loads(lines[0]); exec(sys.argv[2]); lines[0] = json.dumps(r)
open(sys.argv[1], "w").write("\n".join(lines) + "\n")
PY
    }
    tamper neg 'r["run"] = -1'; refuse "field run" "$dir/s0" "$dir/neg"
    tamper huge 'r["run"] = 10**12'; refuse "not a run of shard" "$dir/s0" "$dir/huge"
    tamper str 'r["miss_km"] = "far"'; refuse "field miss_km" "$dir/s0" "$dir/str"
    ;;
  mc_args)
    m="$build/tools/montecarlo/reentry_mc"
    for args in "--runs|2|--seed|-1|--out|$dir/a" "--runs|2000000000|--out|$dir/a" "--runs|2|--shard|1/3x|--out|$dir/a" \
                "--runs|2|--seed|99999999999999999999|--out|$dir/a" "--runs|2|--out" "--runs|2|--out|"; do
      IFS='|' read -r -a a <<< "$args"
      [[ "$args" == *'|' ]] && a+=("")
      t0=$(date +%s%N)
      "$m" --mission x33 "${a[@]}" > "$dir/args.txt" 2>&1; rc=$?
      ms=$(( ($(date +%s%N) - t0) / 1000000 ))
      expect $rc 2 "bad argument" "$dir/args.txt" "reentry_mc ${a[*]} ($ms ms)"
      (( ms < 2000 )) || fail "reentry_mc ${a[*]}: refused after $ms ms"
    done
    x33_copy
    sed -i 's/^latitude_deg = -23.75/latitude_deg = 90.0/' "$dir/cfg/missions/x33.toml"
    "$mc" --mission "$dir/cfg/missions/x33.toml" --runs 3 --out "$dir/lat90" > "$dir/lat90.txt" 2>&1; rc=$?
    expect $rc 2 "entry.latitude_deg" "$dir/lat90.txt" "tools/mc with entry latitude 90"
    grep -q "successful" "$dir/lat90.txt" && fail "a mission that cannot be flown reported as a campaign"
    "$mc" --mission x33 --runs 6 --seed 7 --jobs 2 --out "$dir/progress" > "$dir/progress.txt" 2>&1 || fail "6-run campaign"
    ! grep -q $'\r' "$dir/progress.txt" || fail "carriage-return frames in a log file"
    n=$(grep -c "runs, .* elapsed" "$dir/progress.txt")
    (( n >= 1 && n <= 11 )) && echo "ok: tools/mc into a file: $n plain progress lines" || fail "$n progress lines"
    # The oracle's worker processes report through the same progress (runs its flights decide).
    "$m" --mission x33 --runs 4 --seed 7 --jobs 2 --oracle --out "$dir/oracle" > "$dir/oracle.txt" 2>&1 || fail "oracle campaign"
    ! grep -q $'\r' "$dir/oracle.txt" || fail "carriage-return frames in the oracle's log file"
    n=$(grep -c "runs, .* elapsed" "$dir/oracle.txt")
    (( n >= 1 && n <= 11 )) && echo "ok: the oracle into a file: $n plain progress lines" || fail "oracle: $n progress lines"
    ;;
  *) die "unknown case $case_name" ;;
esac
[[ $fails -eq 0 ]] || { echo "$fails failure(s)" >&2; exit 1; }
echo PASS

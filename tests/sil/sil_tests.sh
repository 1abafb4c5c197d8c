#!/bin/bash
# SIL machinery tests (CTest): sil_tests.sh <case> <work dir> <alter_nav_log binary>
#   lockstep_replay: lockstep X-33 SIL via tools/sil, complete run log + summary keys, replay
#                    identical; one altered nav value -> replay names that tick; a truncated
#                    copy and one without END_OF_RUN are named, never "identical".
#   kill_sim_lockstep|kill_sim_realtime|kill_fsw_lockstep|kill_fsw_realtime:
#                    one process killed (SIGKILL) mid-flight: the other detects the link loss
#                    within link_timeout_ticks (3) GNC periods, exits 3 with a named status
#                    (the guidance holds its safe command, the simulator ends the run), and
#                    tools/sil says which side died and exits 3.
#   realtime:        60 s realtime run (simulated 60 s): jitter reported, zero cycle overruns.
#   cpu_hog:         10 lockstep SILs while two CPU hogs load both cores: every run log complete
#                    and every replay identical (the hogs are started and stopped here).
set -u
case_name="$1"; dir="$2"; alter="$3"
repo="$(cd "$(dirname "$0")/../.." && pwd)"
fail() { echo "FAIL: $*" >&2; exit 1; }
unshare -n true 2>/dev/null || fail "'unshare -n' is not permitted: the SIL tests need a private network namespace (run as root)"
rm -rf "$dir"; mkdir -p "$dir"
run="$dir/run"  # tools/sil's --out: only its own outputs (the test's files stay in $dir)

check_keys() {
  /usr/bin/python3 - "$1" <<'PY' || exit 1
import json, sys
s = json.load(open(sys.argv[1]))
keys = ["mission", "success", "event", "taem_miss_km", "final_alt_km", "final_mach", "final_gamma_deg",
        "heading_err_deg", "max_heat_flux_kW_m2", "heat_load_MJ_m2", "max_g", "max_q_kPa", "max_q_alpha_kPa_deg",
        "violations", "planner_runs", "planner_ms_max", "plan_overruns", "plan_waits", "plan_wait_ms_max",
        "cycle_us_max", "cycle_overruns", "jitter_us_max", "wall_s", "log_complete", "link"]
missing = [k for k in keys if k not in s or (s[k] is None)]
if missing: print("FAIL: summary.json lacks", missing); sys.exit(1)
print("summary keys present; wall_s =", s["wall_s"], "event =", s["event"], "plan_waits =", s["plan_waits"],
      "plan_overruns =", s["plan_overruns"], "cycle_us_max =", s["cycle_us_max"], "log_complete =", s["log_complete"])
PY
}

# kill_one <sim|fsw> <lockstep|realtime>: start tools/sil, kill one side mid-flight, check the other.
kill_one() {
  local victim="$1" mode="$2"
  REENTRY_SIL_PLOTS=0 "$repo/tools/sil" --mission x33 --mode "$mode" --out "$run" > "$dir/sil_stdout.txt" 2>"$dir/sil_stderr.txt" &
  local sil=$!
  for _ in $(seq 1 200); do [[ -s "$run/pids" ]] && break; sleep 0.01; done
  [[ -s "$run/pids" ]] || fail "tools/sil did not start the processes"
  local sim_pid fsw_pid
  sim_pid=$(awk '$1 == "sim" {print $2}' "$run/pids"); fsw_pid=$(awk '$1 == "fsw" {print $2}' "$run/pids")
  # Mid-flight: lockstep flies 20000 ticks in about 1.5 s here, realtime 10 ticks per second.
  if [[ "$mode" == lockstep ]]; then sleep 0.3; else sleep 2.0; fi
  kill -0 "$sim_pid" 2>/dev/null && kill -0 "$fsw_pid" 2>/dev/null || fail "a process ended before the kill"
  local victim_pid=$sim_pid survivor_pid=$fsw_pid survivor=guidance
  [[ "$victim" == fsw ]] && { victim_pid=$fsw_pid; survivor_pid=$sim_pid; survivor=simulator; }
  local t0 t1
  t0=$(date +%s%N)
  kill -KILL "$victim_pid"
  for _ in $(seq 1 300); do kill -0 "$survivor_pid" 2>/dev/null || break; sleep 0.005; done
  t1=$(date +%s%N)
  wait "$sil"; local rc=$?
  local ms=$(( (t1 - t0) / 1000000 ))
  echo "killed the $victim ($mode); the $survivor exited $ms ms later; tools/sil exit $rc"
  cat "$dir/sil_stderr.txt"
  [[ $rc -eq 3 ]] || fail "tools/sil exited $rc, want 3 (a process died)"
  /usr/bin/python3 - "$dir" "$victim" "$ms" <<'PY' || exit 1
import json, sys, os
d, victim, ms = sys.argv[1], sys.argv[2], int(sys.argv[3])
test_dir, d = d, os.path.join(d, "run")
s = json.load(open(os.path.join(d, "summary.json")))
link = s["link"]
print("summary link:", link, "| log:", s["log_problem"])
err = open(os.path.join(test_dir, "sil_stderr.txt")).read()
fails = []
want_died, want_detector = ("simulator", "guidance") if victim == "sim" else ("guidance", "simulator")
if link["died"] != want_died: fails.append("died = %r, want %r" % (link["died"], want_died))
if link["detected_by"] != want_detector: fails.append("detected_by = %r, want %r" % (link["detected_by"], want_detector))
if ("the %s died" % ("simulator" if victim == "sim" else "guidance process")) not in err: fails.append("tools/sil did not say who died")
# Three GNC periods (0.3 s) of silence, then a clean exit. Lockstep detects at 0.3 s; realtime
# checks at its deadlines, so within one more period: reported silence 0.3-0.45 s, exit < 0.8 s.
det = link["detection_ms"]
if det is None or not (300.0 <= det <= 450.0): fails.append("reported silence %r ms, want 300-450" % det)
if ms > 800: fails.append("survivor exited %d ms after the kill, want < 800" % ms)
if victim == "sim":
    g = json.load(open(os.path.join(d, "guidance.json")))
    if g.get("exit") != "link_loss" or g.get("exit_code") != 3: fails.append("guidance exit %r" % g.get("exit"))
    fsw_err = open(os.path.join(d, "fsw.txt")).read()
    if "safe command held" not in fsw_err or "link_loss" not in fsw_err: fails.append("guidance message: %r" % fsw_err)
else:
    sim = json.load(open(os.path.join(d, "sim_summary.json")))
    if sim.get("event") != "link_loss" or sim.get("success"): fails.append("simulator summary event %r" % sim.get("event"))
    if "link loss" not in open(os.path.join(d, "sim_err.txt")).read(): fails.append("simulator message missing")
if s["log_complete"]: fails.append("a run cut by a dead process reported a complete log")
for f in fails: print("FAIL:", f)
sys.exit(1 if fails else 0)
PY
}

case "$case_name" in
  lockstep_replay)
    "$repo/tools/sil" --mission x33 --mode lockstep --out "$run" > "$dir/sil_stdout.txt"
    rc=$?
    [[ $rc -le 1 ]] || fail "tools/sil exited $rc: $(tail -3 "$dir/sil_stdout.txt")"
    [[ -s "$run/run.lcm" ]] || fail "no log written"
    check_keys "$run/summary.json"
    grep -q '"sim_exit": 0' "$run/summary.json" || fail "simulator did not end normally"
    grep -q '"fsw_exit": 0' "$run/summary.json" || fail "guidance did not end normally"
    grep -q '"log_complete": true' "$run/summary.json" || fail "run log incomplete: $(grep log_problem "$run/summary.json")"
    # No retry: a log with a hole is a failure of the product, not bad luck.
    out=$("$repo/tools/replay" "$run/run.lcm")
    echo "$out"
    [[ "$out" == identical* ]] || fail "replay did not print identical: $out"
    # tools/sil draws the plots at the end of the run: at least six valid, non-trivial PNGs.
    /usr/bin/python3 - "$run/plots" <<'PY' || fail "plots missing or invalid"
import os, struct, sys
d = sys.argv[1]
pngs = sorted(f for f in os.listdir(d) if f.endswith(".png")) if os.path.isdir(d) else []
ok = 0
for f in pngs:
    b = open(os.path.join(d, f), "rb").read()
    if b[:8] != b"\x89PNG\r\n\x1a\n" or b[12:16] != b"IHDR": print("not a PNG:", f); continue
    w, h = struct.unpack(">II", b[16:24])
    if w < 300 or h < 300 or len(b) < 20000: print("too small:", f, w, h, len(b)); continue
    ok += 1
print("plots:", ok, "valid PNGs:", ", ".join(pngs))
sys.exit(0 if ok >= 6 else 1)
PY
    tick=5000
    "$alter" "$run/run.lcm" "$run/altered.lcm" $tick 25.0 || fail "could not alter the log"
    out=$("$repo/tools/replay" "$run/altered.lcm"); rc=$?
    echo "$out"
    [[ $rc -ne 0 ]] || fail "altered log replayed without a difference"
    [[ "$out" == "differs at tick $tick "* ]] || fail "wrong tick reported: $out"
    # A log cut in the middle of an event, and one cut at an event boundary before END_OF_RUN.
    /usr/bin/python3 - "$run/run.lcm" "$run/cut.lcm" "$run/no_end.lcm" <<'PY' || fail "could not cut the log"
import struct, sys
data = open(sys.argv[1], "rb").read()
pos, ends, end_of_run = 0, [], None
while pos + 28 <= len(data):
    cl, dl = struct.unpack(">ii", data[pos + 20:pos + 28])
    if end_of_run is None and data[pos + 28:pos + 28 + cl] == b"RUN_CONTROL": end_of_run = pos
    pos += 28 + cl + dl
    ends.append(pos)
mid = ends[len(ends) * 2 // 3] + 17  # 17 bytes into an event: inside its header
open(sys.argv[2], "wb").write(data[:mid])
open(sys.argv[3], "wb").write(data[:end_of_run])
PY
    out=$("$repo/tools/replay" "$run/cut.lcm"); rc=$?
    echo "$out"
    [[ $rc -eq 6 && "$out" == "damaged log"* ]] || fail "truncated log: exit $rc, $out"
    out=$("$repo/tools/replay" "$run/no_end.lcm"); rc=$?
    echo "$out"
    [[ $rc -eq 5 && "$out" == "incomplete log"*END_OF_RUN* ]] || fail "log without END_OF_RUN: exit $rc, $out"
    ;;
  kill_sim_lockstep) kill_one sim lockstep ;;
  kill_sim_realtime) kill_one sim realtime ;;
  kill_fsw_lockstep) kill_one fsw lockstep ;;
  kill_fsw_realtime) kill_one fsw realtime ;;
  realtime)
    REENTRY_SIM_ARGS="--stop-after 60" "$repo/tools/sil" --mission x33 --mode realtime --out "$run" > "$dir/sil_stdout.txt"
    rc=$?
    [[ $rc -le 1 ]] || fail "tools/sil exited $rc"
    check_keys "$run/summary.json"
    # Into a file the progress is plain lines (every 10 % or minute), never carriage-return frames.
    ! grep -q $'\r' "$dir/sil_stdout.txt" || fail "carriage-return frames in a log file"
    /usr/bin/python3 - "$run/summary.json" <<'PY' || exit 1
import json, sys
s = json.load(open(sys.argv[1]))
print("realtime: jitter_us_max =", s.get("jitter_us_max"), "cycle_overruns =", s.get("cycle_overruns"),
      "sim_deadline_misses =", s.get("sim_deadline_misses"),
      "plan_waits =", s.get("plan_waits"), "cycle_us_max =", s.get("cycle_us_max"), "wall_s =", s.get("wall_s"),
      "log:", s.get("log_problem") or "complete")
if s.get("jitter_us_max") is None or s.get("cycle_overruns") != 0: sys.exit(1)
if s.get("plan_waits") != 0: sys.exit(1)  # realtime adopts when ready: it never waits
if s.get("sim_deadline_misses") is None: sys.exit(1)  # the simulator counts its own misses
if not s.get("log_complete"): sys.exit(1)
PY
    ;;
  cpu_hog)
    # Two busy loops, one per core, for the whole test; always stopped on exit.
    hogs=()
    cleanup() { for h in "${hogs[@]}"; do kill "$h" 2>/dev/null; done; wait 2>/dev/null; }
    trap cleanup EXIT
    for _ in 1 2; do /bin/sh -c 'while :; do :; done' & hogs+=($!); done
    sleep 0.5
    runs=10 complete=0 identical=0
    for i in $(seq 1 $runs); do
      d="$dir/run$i"
      t0=$(date +%s%N)
      REENTRY_SIL_PLOTS=0 "$repo/tools/sil" --mission x33 --mode lockstep --out "$d" > "$d.stdout" 2>&1
      rc=$?
      out=$("$repo/tools/replay" "$d/run.lcm")
      t1=$(date +%s%N)
      info=$(/usr/bin/python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); r=json.load(open(sys.argv[2]))["run"]
print("log_complete=%s nav_ticks=%s missing=%s unanswered=%s end=%s kernel_drops(sim)=%s log_dropped=%s wall_s=%s"
      % (s["log_complete"], r["nav_ticks"], r["missing_ticks"], r["unanswered_ticks"], r["end_event"],
         s.get("rx_kernel_drops"), s.get("log_dropped"), s["wall_s"]))' "$d/summary.json" "$d/run_info.json" 2>&1)
      echo "run $i: tools/sil exit $rc, $info, $(( (t1 - t0) / 1000000 )) ms with replay: $out"
      [[ $rc -le 1 ]] && grep -q '"log_complete": true' "$d/summary.json" && complete=$((complete + 1))
      [[ "$out" == identical* ]] && identical=$((identical + 1))
    done
    echo "under two CPU hogs: $complete of $runs run logs complete, $identical of $runs replays identical"
    [[ $complete -eq $runs && $identical -eq $runs ]] || fail "logs lost or replays differ under load"
    ;;
  *) fail "unknown case $case_name" ;;
esac
echo PASS

#!/bin/bash
# Hostile-input tests (CTest label fuzz; run in the Release and the sanitizer stage):
#   fuzz_tests.sh <case> <work dir>     (binaries from $WIRE_FUZZ, $REENTRY_FSW_BIN, ...)
#   guidance_wire:      the running reentry_fsw flies 2000 ticks twice against wire_fuzz acting
#                       as the simulator, clean and with 55 malformed datagrams per tick (1.1e5);
#                       the commands must be bit-identical, every datagram counted by kind in
#                       the guidance's counters, every implausible sample answered by the held
#                       command, the process alive to END_OF_RUN.
#   simulator_commands: the running reentry_sim_lcm against wire_fuzz acting as the guidance:
#                       NaN/inf/out-of-range/future/negative-tick and undecodable commands are
#                       counted and never flown; later valid commands are (no latch-up).
#   hostile_repro:      the ../shared/repro cases against fresh guidance processes: one LC03
#                       fragment with a wrapping offset, one sample with a tick 1e6 ahead, a time
#                       1e9 s, tick INT64_MAX, INT64_MIN+1 then INT64_MAX, a negative first tick;
#                       and issue 38's samples: a tick-0 sample at 999 km, 14.9 km/s, 489 m/s^2
#                       (refused: not the mission's entry), a plausible tick 0 5 km too high
#                       (replaced by the real stream after 3 samples), a 7.6 km/s radial velocity
#                       at tick 150 (refused by the flight-path-angle rate). No latch, no link loss.
#   logs:               a sealed run log, then 340 damaged copies of it (truncated, bit flips, garbage,
#                       events removed, END_OF_RUN removed) into replay, loginfo and log2csv:
#                       no crash, no sanitizer report, no damaged log called identical.
set -u
case_name="$1"; dir="$2"
repo="$(cd "$(dirname "$0")/../.." && pwd)"
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$dir"; mkdir -p "$dir"
export dir repo
netns() {
  unshare -n true 2>/dev/null || fail "'unshare -n' is not permitted: these tests need a private network namespace"
  unshare -n -- bash -c 'ip link set lo up; ip route add 224.0.0.0/4 dev lo; '"$1"
}

case "$case_name" in
  guidance_wire)
    netns '
      export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"
      for pass in clean fuzzed; do
        junk=0; [[ $pass == fuzzed ]] && junk=55
        "$REENTRY_FSW_BIN" --mission x33 --mode lockstep --link-timeout-ticks 100 --status-json "$dir/$pass.status.json" \
          --log "$dir/$pass.fsw.lcm" > "$dir/$pass.fsw.txt" 2>&1 & fsw=$!
        sleep 0.3
        "$WIRE_FUZZ" guidance --mission x33 --ticks 2000 --junk-per-tick $junk --commands "$dir/$pass.commands" \
          --expect "$dir/$pass.expect.json" || { kill $fsw; echo "fuzzer failed ($pass)"; exit 1; }
        wait $fsw; rc=$?
        echo "$pass: reentry_fsw exit $rc"; cat "$dir/$pass.fsw.txt"
        [[ $rc -eq 0 ]] || exit 1
      done' || fail "guidance process did not survive the wire fuzzing"
    cmp -s "$dir/clean.commands" "$dir/fuzzed.commands" || fail "the flown commands changed under fuzzing ($(diff "$dir/clean.commands" "$dir/fuzzed.commands" | head -3))"
    echo "commands bit-identical over $(wc -l < "$dir/clean.commands") ticks"
    /usr/bin/python3 - "$dir" <<'PY' || exit 1
import json, sys, os
d = sys.argv[1]
e = json.load(open(os.path.join(d, "fuzzed.expect.json")))
g = json.load(open(os.path.join(d, "fuzzed.status.json")))
c = json.load(open(os.path.join(d, "clean.status.json")))
fails = []
for k in ["bad_datagrams", "bad_messages", "duplicate_ticks", "nav_rejected_tick", "nav_rejected_values", "invalid_nav"]:
    print("%-20s expected %7d  reported %7d  (clean run %d)" % (k, e[k], g[k], c[k]))
    if g[k] != e[k]: fails.append(k)
if e["sent"] < 100000: fails.append("only %d malformed datagrams" % e["sent"])
if g["rx_kernel_drops"] != 0: fails.append("kernel dropped %d datagrams" % g["rx_kernel_drops"])
if e["held_wrong"] != 0: fails.append("%d implausible samples not answered with the held command" % e["held_wrong"])
if g["exit"] != "ok": fails.append("exit %s" % g["exit"])
print("malformed datagrams sent:", e["sent"], "| fsw log records:", g["log_recorded"], "dropped:", g["log_dropped"])
for f in fails: print("FAIL:", f)
sys.exit(1 if fails else 0)
PY
    ;;
  simulator_commands)
    netns '
      export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"
      "$WIRE_FUZZ" simulator --expect "$dir/expect.json" > "$dir/fuzz.txt" 2>&1 & fz=$!
      sleep 0.3
      "$REENTRY_SIM_BIN" --mission x33 --mode lockstep --stop-after 60 --link-timeout-ticks 100 \
        --summary-json "$dir/summary.json" > "$dir/sim.txt" 2>&1; rc=$?
      wait $fz; frc=$?
      echo "reentry_sim_lcm exit $rc, fuzzer exit $frc"; cat "$dir/fuzz.txt"
      [[ $rc -eq 0 && $frc -eq 0 ]]' || fail "simulator did not survive the command fuzzing"
    /usr/bin/python3 - "$dir" <<'PY' || exit 1
import json, sys, os
d = sys.argv[1]
e = json.load(open(os.path.join(d, "expect.json")))
s = json.load(open(os.path.join(d, "summary.json")))
fails = []
print("simulator: ticks %s, event %s, bad_commands %s (sent %s), bad_messages %s (sent %s), max bank rate %.0f deg/s, "
      "flown bank at tick %s: %.3f rad" % (s["ticks"], s["event"], s["bad_commands"], e["bad_commands"], s["bad_messages"],
      e["bad_messages"], s["max_sigma_rate_deg_s"], e["last_truth_tick"], e["last_truth_sigma_rad"]))
if s["ticks"] != 600: fails.append("the run did not reach the 60 s stop (ticks %s)" % s["ticks"])
if s["bad_commands"] != e["bad_commands"]: fails.append("bad_commands")
if s["bad_messages"] != e["bad_messages"]: fails.append("bad_messages")
if abs(e["last_truth_sigma_rad"] - 1.0) > 1e-9: fails.append("later commands were not flown (latched)")
if s["max_sigma_rate_deg_s"] > 600.0: fails.append("an implausible command was flown")
for f in fails: print("FAIL:", f)
sys.exit(1 if fails else 0)
PY
    ;;
  hostile_repro)
    netns '
      export LCM_DEFAULT_URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"
      bad=0
      for sc in frag_wrap tick_jump time_jump tick_max tick_overflow tick_negative_start first_absurd first_wrong \
                radial_velocity; do
        "$REENTRY_FSW_BIN" --mission x33 --mode lockstep --link-timeout-ticks 100 --status-json "$dir/$sc.json" \
          > "$dir/$sc.fsw.txt" 2>&1 & fsw=$!
        sleep 0.3
        "$WIRE_FUZZ" repro --scenario $sc; frc=$?
        for _ in $(seq 1 100); do kill -0 $fsw 2>/dev/null || break; sleep 0.05; done
        kill -0 $fsw 2>/dev/null && { kill $fsw; echo "$sc: guidance still running"; bad=1; }
        wait $fsw; rc=$?
        counts=$(/usr/bin/python3 -c "import json,sys; g=json.load(open(sys.argv[1])); print(g[\"bad_datagrams\"], g[\"invalid_nav\"], g[\"skipped_ticks\"])" "$dir/$sc.json")
        read -r dg inv skip <<< "$counts"
        want_dg=0 want_inv=1; [[ $sc == frag_wrap ]] && { want_dg=5; want_inv=0; }; [[ $sc == tick_overflow ]] && want_inv=2
        [[ $sc == first_wrong ]] && want_inv=2  # accepted, then 2 real samples refused until 3 replace it
        echo "$sc: reentry_fsw exit $rc; bad_datagrams $dg (want $want_dg), invalid_nav $inv (want $want_inv), skipped_ticks $skip (want 0)"
        [[ $rc -eq 0 && $frc -eq 0 && $dg -eq $want_dg && $inv -eq $want_inv && $skip -eq 0 ]] || bad=1
      done
      exit $bad' || fail "a reproduction crashed, latched or was not answered"
    ;;
  logs)
    /usr/bin/python3 "$repo/tests/sil/log_fuzz.py" --dir "$dir" --repo "$repo" || fail "damaged logs were mishandled"
    ;;
  *) fail "unknown case $case_name" ;;
esac
echo PASS

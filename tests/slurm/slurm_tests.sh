#!/bin/bash
# tests/slurm/slurm_tests.sh campaign|resume WORKDIR REPO (CTest, label slurm)
#   campaign: a 40-run X-33 campaign as 4 array tasks through `tools/mc --slurm --wait` on a
#             local single-node cluster gives the records of the same campaign flown in process
#             (compare_runs.py: every field but the timing ones); so does a 6-run stress-set
#             oracle campaign (the options pass through to the shards).
#   resume:   one shard of such a campaign is cancelled (scancel) while it runs: --wait names it
#             CANCELLED and fails; `--resume DIR` resubmits that shard alone, and the merged
#             records are again those of the in-process campaign.
# Each case starts its own cluster (tools/slurm_local, own directory, free ports picked at
# random so that test runs of two checkouts on one machine do not meet) and stops it in an EXIT
# trap; every step runs under `timeout` with what is left of a 780 s budget, inside the CTest
# limit (900 s), so the trap always runs.
set -u
case_="$1"; work="$2"; repo="$3"
mc="$repo/tools/mc"; local_="$repo/tools/slurm_local"; compare="$repo/tools/montecarlo/compare_runs.py"
[[ "$(id -u)" -eq 0 ]] || { echo "SKIP: the local Slurm cluster needs root (slurmd)"; exit 77; }
rm -rf "$work"; mkdir -p "$work"
cluster="$(mktemp -d /tmp/reentry-slurm-test.XXXXXX)"
deadline=$((SECONDS + 780))
left() { local l=$((deadline - SECONDS)); echo $((l > 1 ? l : 1)); }

cleanup() {
  local rc=$?
  [[ -n "${first:-}" ]] && kill "$first" 2>/dev/null  # a --wait still following
  if [[ $rc -ne 0 ]]; then
    echo "--- slurm logs ($case_ failed, exit $rc)"
    tail -n 15 "$cluster"/log/slurmctld.log "$cluster"/log/slurmd.log 2>/dev/null
    for f in "$work"/slurm/slurm/logs/*.out; do [[ -f "$f" ]] && { echo "--- $f"; tail -n 5 "$f"; }; done
  fi
  "$local_" down --dir "$cluster" >/dev/null 2>&1
  [[ -d "$cluster" ]] && rmdir "$cluster" 2>/dev/null
  exit $rc
}
trap cleanup EXIT
trap 'exit 143' TERM INT HUP
fail() { echo "FAIL: $*" >&2; exit 1; }
now() { date +%s.%N; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

t=$(now)
for _ in 1 2 3 4 5; do
  port=$((20000 + 2 * (RANDOM % 6000)))  # below the ephemeral range (32768-)
  env_line="$(timeout 90 "$local_" up --dir "$cluster" --port "$port")" && break
done
[[ -n "${env_line:-}" ]] || fail "tools/slurm_local up"
eval "$env_line"
echo "cluster up in $(secs "$t" "$(now)") s ($SLURM_CONF)"

# The same campaign flown in process (all cores): the reference records.
campaign=(--mission x33 --runs 40 --seed 7)
t=$(now)
timeout "$(left)" "$mc" "${campaign[@]}" --out "$work/inproc" >"$work/inproc.log" 2>&1 || fail "in-process campaign"
inproc_s=$(secs "$t" "$(now)")

array_job() { /usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["submissions"][int(sys.argv[2])]["array_job"])' \
  "$work/slurm/slurm/campaign.json" "$1"; }
task_states() { scontrol -o show job "$1" | grep -o 'ArrayTaskId=[^ ]* .*JobState=[A-Z_]*' |
  sed -E 's/ArrayTaskId=([^ ]*).*JobState=([A-Z_]*)/\1:\2/' | sort | tr '\n' ' '; }

case "$case_" in
campaign)
  t=$(now)
  timeout "$(left)" "$mc" "${campaign[@]}" --out "$work/slurm" --slurm --array-tasks 4 --cpus-per-task 1 --wait --poll 1 \
    >"$work/slurm.log" 2>&1 || { cat "$work/slurm.log"; fail "tools/mc --slurm --wait"; }
  slurm_s=$(secs "$t" "$(now)")
  cat "$work/slurm.log"
  a="$(array_job 0)"
  [[ "$(task_states "$a")" == "0:COMPLETED 1:COMPLETED 2:COMPLETED 3:COMPLETED " ]] ||
    fail "array job $a: tasks $(task_states "$a")"
  for i in 0 1 2 3; do
    n=$(wc -l <"$work/slurm/shards/$i/runs_shard_${i}_of_4.jsonl")
    [[ "$n" -eq 10 ]] || fail "shard $i holds $n records, not 10"
  done
  /usr/bin/python3 "$compare" "$work/inproc" "$work/slurm" || fail "merged records differ from the in-process campaign"
  /usr/bin/python3 -c 'import json,sys; assert [json.loads(l)["run"] for l in open(sys.argv[1])] == list(range(40))' \
    "$work/slurm/runs.jsonl" || fail "merged runs.jsonl does not hold runs 0..39 in order"
  # reentry_mc's options pass through to the shards: stress dispersions and the oracle (its
  # worker processes, 2 CPUs per task) give the records of the same campaign in process.
  extra=(--mission x33 --runs 6 --seed 7 --dispersions stress --oracle)
  timeout "$(left)" "$mc" "${extra[@]}" --jobs 2 --out "$work/oracle_inproc" >"$work/oracle_inproc.log" 2>&1 ||
    fail "in-process stress oracle campaign"
  timeout "$(left)" "$mc" "${extra[@]}" --out "$work/oracle_slurm" --slurm --array-tasks 3 --cpus-per-task 2 --wait --poll 1 \
    >"$work/oracle_slurm.log" 2>&1 || { cat "$work/oracle_slurm.log"; fail "stress oracle campaign through Slurm"; }
  grep -q "oracle: [0-9]*/6 runs feasible" "$work/oracle_slurm.log" || fail "no oracle summary in the merge"
  /usr/bin/python3 "$compare" "$work/oracle_inproc" "$work/oracle_slurm" || fail "stress oracle records differ"
  # A second submission into the campaign directory is refused; a resume of a complete campaign
  # submits nothing.
  "$mc" "${campaign[@]}" --out "$work/slurm" --slurm >/dev/null 2>&1 && fail "a second campaign into $work/slurm accepted"
  timeout "$(left)" "$mc" --slurm --resume "$work/slurm" | grep -q "nothing to resubmit" || fail "resume of a complete campaign"
  echo "wall time: in process ${inproc_s} s, through Slurm ${slurm_s} s (40 runs, 4 array tasks, 1 CPU each)"
  ;;
resume)
  # One task at a time (2 CPUs each on this node), so shard 1 is cancelled while it flies.
  timeout "$(left)" "$mc" "${campaign[@]}" --out "$work/slurm" --slurm --array-tasks 4 --cpus-per-task 2 --wait --poll 1 \
    >"$work/first.log" 2>&1 &
  first=$!
  until [[ -s "$work/slurm/slurm/campaign.json" || $SECONDS -ge $deadline ]]; do sleep 0.2; done
  a="$(array_job 0)" || fail "no submission recorded"
  # RUNNING in squeue means allocated, not flying: a cancel in the moment before slurmstepd
  # has started the batch script can be lost, and the shard then flies to the end. reentry_mc
  # prints its first progress line ("0/10 runs") once its signal handler is set and its workers
  # fly, so the cancel waits for that line; the shard then stops and writes no records.
  shard_log="$work/slurm/slurm/logs/shard_1_job_${a}.out"
  until grep -qs " runs, " "$shard_log" || [[ $SECONDS -ge $deadline ]]; do sleep 0.05; done
  scancel "${a}_1" || fail "scancel ${a}_1"
  wait "$first"; rc=$?
  cat "$work/first.log"
  [[ $rc -eq 1 ]] || fail "--wait with a cancelled shard exited $rc, not 1"
  grep -q "shard 1 (job ${a}_1): CANCELLED" "$work/first.log" || fail "the cancelled shard is not named with its state"
  [[ "$(task_states "$a")" == "0:COMPLETED 1:CANCELLED 2:COMPLETED 3:COMPLETED " ]] ||
    fail "array job $a: tasks $(task_states "$a")"
  [[ -e "$work/slurm/runs.jsonl" ]] && fail "a campaign with a cancelled shard was merged"
  timeout "$(left)" "$mc" --slurm --resume "$work/slurm" --wait --poll 1 >"$work/resume.log" 2>&1 ||
    { cat "$work/resume.log"; fail "tools/mc --slurm --resume --wait"; }
  cat "$work/resume.log"
  grep -q "resubmitting 1 of 4 shards (1:" "$work/resume.log" || fail "resume did not resubmit shard 1 alone"
  b="$(array_job 1)"
  [[ "$(task_states "$b")" == "1:COMPLETED " ]] || fail "resubmitted array job $b: tasks $(task_states "$b")"
  /usr/bin/python3 "$compare" "$work/inproc" "$work/slurm" || fail "resumed campaign differs from the in-process one"
  ;;
*) fail "unknown case $case_" ;;
esac
echo PASS

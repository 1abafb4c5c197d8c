#!/usr/bin/python3
"""The end of a tools/sil run: DIR/summary.json from what the two processes and the log tools
reported, the printed summary and the exit status (the table in tools/README.md).

sil_summary.py DIR SIM_RC FSW_RC FSW_STOPPED T0 T1 MERGE_RC MODE INTERRUPTED INFO_RC MSGS

MSGS holds what the processes printed (sim_err.txt, fsw.txt, merge.txt, logger.txt), kept outside
DIR while they ran: their reasons survive a full DIR. They are copied into DIR here."""
import json
import os
import shutil
import signal
import sys

MESSAGE_FILES = ("sim_err.txt", "fsw.txt", "merge.txt", "logger.txt")

OK, MISSION_FAILURE, USAGE, LINK_LOSS, LOG_INCOMPLETE, LOG_DAMAGED, TRANSPORT, WRITE_FAILED = 0, 1, 2, 3, 5, 6, 7, 8


def load(out, name):
    """A process's JSON, or {} (absent, empty or cut short: the exit statuses say why)."""
    try:
        with open(os.path.join(out, name)) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def signal_name(number):
    try:
        return signal.Signals(number).name
    except ValueError:
        return "signal %d" % number


def died(rc):
    return "killed by signal %s" % signal_name(rc - 128) if rc > 128 else None


def link_state(a, s, g, problems):
    """Who died or lost the link, and who detected it."""
    sim_rc, fsw_rc, stopped = a["sim_rc"], a["fsw_rc"], a["fsw_stopped"]
    link = {"sim_exit": sim_rc, "fsw_exit": fsw_rc, "died": None, "detected_by": None, "detection_ms": None}
    if a["interrupted"] or USAGE in (sim_rc, fsw_rc):
        return link  # both were asked to stop, or the mission was refused: nobody died
    if died(sim_rc):
        link["died"] = "simulator"
        problems.append("the simulator died (%s)" % died(sim_rc))
    if died(fsw_rc) and not stopped:
        link["died"] = "guidance" if link["died"] is None else "both"
        problems.append("the guidance process died (%s)" % died(fsw_rc))
    if stopped:
        problems.append("the guidance process did not end after the simulator (stopped by tools/sil)")
    if fsw_rc == LINK_LOSS:
        link["detected_by"] = "guidance"
        link["detection_ms"] = g.get("link_silent_ms")
        problems.append("the guidance process detected the link loss after %.0f ms of silence and held its safe command"
                        % (g.get("link_silent_ms") or float("nan")))
    if sim_rc == LINK_LOSS:
        link["detected_by"] = "simulator" if link["detected_by"] is None else "both"
        ll = s.get("link_loss") or {}
        link["detection_ms"] = ll.get("silent_ms", link["detection_ms"])
        problems.append("the simulator detected the link loss at tick %s after %.0f ms of silence and ended the run"
                        % (ll.get("tick"), ll.get("silent_ms") or float("nan")))
    return link


def log_state(summary, info, a):
    """log_complete / log_problem, and whether a problem is damage (6) or something missing (5)."""
    run = info.get("run") or {}
    if a["mode"] == "realtime":
        # Realtime guidance flies the newest sample of each period and may skip a tick (counted in
        # skipped_ticks); the log is whole when it holds everything both processes sent.
        whole = run.get("sealed") and not info.get("malformed") and run.get("first_tick") == 0 and \
            run.get("missing_ticks") == 0 and run.get("end_of_run")
        summary["unanswered_ticks"] = run.get("unanswered_ticks")
    else:
        whole = run.get("complete")
    summary["log_complete"] = bool(whole) and a["merge_rc"] == 0
    summary["log_problem"] = None if summary["log_complete"] else (
        run.get("problem") or "run log unreadable (see %s/merge.txt)" % a["out"])
    summary["log_events"] = info.get("events")
    return LOG_DAMAGED if info.get("malformed") or a["merge_rc"] == LOG_DAMAGED else LOG_INCOMPLETE


def build_summary(a):
    out = a["out"]
    s, g, info = load(out, "sim_summary.json"), load(out, "guidance.json"), load(out, "run_info.json")
    summary = {k: s.get(k) for k in ["mission", "success", "event", "taem_miss_km", "miss_along_km", "miss_cross_km",
                                     "final_alt_km", "final_mach", "final_gamma_deg", "heading_err_deg",
                                     "max_heat_flux_kW_m2", "heat_load_MJ_m2", "max_g", "max_q_kPa",
                                     "max_q_alpha_kPa_deg", "violations"]}
    # Timing: in lockstep a plan the simulator had to wait for is a plan wait, not an overrun;
    # plan_overruns are plans slower than their L/f budget, cycle_us_max the cycle's own compute
    # time; cycle_overruns and jitter are realtime figures (deadline misses, wake-up lateness), and
    # sim_deadline_misses the simulator's own.
    summary.update({k: g.get(k) for k in ["planner_runs", "planner_ms_max", "plan_overruns", "plan_waits",
                                          "plan_wait_ms_max", "plan_wait_ms_total", "cycle_us_max"]})
    summary["jitter_us_max"] = g.get("jitter_us_max")
    summary["cycle_overruns"] = g.get("cycle_overruns")
    summary["sim_deadline_misses"] = s.get("deadline_misses")
    summary["wall_s"] = round(a["t1"] - a["t0"], 3)
    summary["sim_exit"], summary["fsw_exit"] = a["sim_rc"], a["fsw_rc"]
    summary["interrupted"] = signal_name(a["interrupted"]) if a["interrupted"] else None
    problems = []
    summary["link"] = link_state(a, s, g, problems)
    log_rc = log_state(summary, info, a)
    summary["log_dropped"] = {"sim": s.get("log_dropped"), "fsw": g.get("log_dropped")}
    summary["bad_messages"] = {"sim": s.get("bad_messages"), "fsw": g.get("bad_messages")}
    summary["nav_rejected"] = {"values": g.get("nav_rejected_values"), "tick": g.get("nav_rejected_tick"),
                               "reacquired": g.get("nav_reacquired")}
    processes_ok = a["sim_rc"] == 0 and a["fsw_rc"] == 0 and not a["fsw_stopped"]
    summary["success"] = bool(s.get("success")) and processes_ok and not a["interrupted"]
    if summary["violations"] is None:
        summary["violations"] = []
    for k, v in s.items():  # everything else the simulator reported (plot context, mission file)
        summary.setdefault(k, v)
    return summary, problems, log_rc, processes_ok


def exit_status(summary, a, log_rc, processes_ok):
    """The run's exit status and, when it is not a flight verdict, why (tools/README.md's order)."""
    rcs = (a["sim_rc"], a["fsw_rc"])
    if a["interrupted"]:
        return 128 + a["interrupted"], "interrupted by %s: both processes ended, their logs sealed" % \
            signal_name(a["interrupted"])
    if WRITE_FAILED in rcs or a["merge_rc"] == WRITE_FAILED or a["info_rc"] == WRITE_FAILED:
        said = [line for name in MESSAGE_FILES for line in lines(a["msgs"], name) if "write failed" in line]
        return WRITE_FAILED, "write failed: an output of the run is not whole: %s" % \
            ("; ".join(said) if said else "see %s/sim_err.txt, fsw.txt, merge.txt" % a["out"])
    if USAGE in rcs:
        return USAGE, "the mission was refused: %s" % last_line(a["msgs"], "sim_err.txt" if a["sim_rc"] == USAGE
                                                                 else "fsw.txt")
    if TRANSPORT in rcs:
        return TRANSPORT, "the network failed (see %s/sim_err.txt, fsw.txt)" % a["out"]
    if not processes_ok:
        return LINK_LOSS, None
    if not summary["log_complete"]:
        return log_rc, "the run log is incomplete: %s" % summary["log_problem"]
    return (OK if summary["success"] else MISSION_FAILURE), None


def lines(msgs, name):
    """The non-empty lines a process printed, [] when it printed nothing."""
    try:
        with open(os.path.join(msgs, name), errors="replace") as f:
            return [line.strip() for line in f if line.strip()]
    except OSError:
        return []


def last_line(msgs, name):
    said = lines(msgs, name)
    return said[-1] if said else "(no message)"


def copy_messages(a):
    """The processes' messages into DIR; a copy that fails is a write failure, named."""
    for name in MESSAGE_FILES:
        src = os.path.join(a["msgs"], name)
        if not os.path.exists(src):
            continue
        try:
            shutil.copyfile(src, os.path.join(a["out"], name))
        except OSError as e:
            return "%s: %s" % (os.path.join(a["out"], name), e.strerror or e)
    return None


def print_summary(summary, a):
    if summary["mission"] is None:
        print("summary: none: the simulator wrote no summary (its last message: %s)" % last_line(a["msgs"], "sim_err.txt"))
        return

    def f(k, fmt="%.2f"):
        v = summary.get(k)
        return fmt % v if isinstance(v, (int, float)) and not isinstance(v, bool) else "n/a"
    print("summary: %s %s | event %s | miss %s km (along %s, across %s) | alt %s km | Mach %s | gamma %s deg | "
          "heading err %s deg" % (summary["mission"], "SUCCESS" if summary["success"] else "FAILURE", summary["event"],
                                  f("taem_miss_km"), f("miss_along_km", "%+.2f"), f("miss_cross_km", "%+.2f"),
                                  f("final_alt_km"), f("final_mach"), f("final_gamma_deg"), f("heading_err_deg")))
    print("         max qdot %s kW/m2 | max n %s g | max q %s kPa | planner %s runs, max %s ms, %s waits | wall %s s | "
          "violations: %s" % (f("max_heat_flux_kW_m2", "%.0f"), f("max_g"), f("max_q_kPa"), summary.get("planner_runs"),
                              f("planner_ms_max"), summary.get("plan_waits"), f("wall_s"),
                              ", ".join(summary["violations"]) or "none"))
    print("         run log: %s" % ("complete, %s events" % summary["log_events"] if summary["log_complete"]
                                    else "INCOMPLETE: %s" % summary["log_problem"]))


def main():
    v = sys.argv[1:]
    a = {"out": v[0], "sim_rc": int(v[1]), "fsw_rc": int(v[2]), "fsw_stopped": int(v[3]) == 1, "t0": float(v[4]),
         "t1": float(v[5]), "merge_rc": int(v[6]), "mode": v[7], "interrupted": int(v[8]), "info_rc": int(v[9]),
         "msgs": v[10]}
    summary, problems, log_rc, processes_ok = build_summary(a)
    rc, why = exit_status(summary, a, log_rc, processes_ok)
    copy_failed = copy_messages(a)
    if copy_failed:
        print("tools/sil: write failed: %s" % copy_failed, file=sys.stderr)
        if rc < 128 and rc != WRITE_FAILED:
            rc, why = WRITE_FAILED, None
    summary["exit_code"] = rc
    summary["exit"] = {0: "ok", 1: "mission_failure", 2: "usage", 3: "link_loss", 5: "log_incomplete",
                       6: "log_damaged", 7: "transport_error", 8: "write_failed"}.get(rc, "interrupted")
    path = os.path.join(a["out"], "summary.json")
    try:
        with open(path, "w") as out:
            json.dump(summary, out, indent=2)
            out.write("\n")
    except OSError as e:
        print("tools/sil: write failed: %s: %s" % (path, e.strerror or e), file=sys.stderr)
        if rc < 128 and rc != WRITE_FAILED:
            rc, why = WRITE_FAILED, None
    print_summary(summary, a)
    for p in problems:
        print("tools/sil: " + p, file=sys.stderr)
    if why:
        print("tools/sil: %s; exit %d" % (why, rc), file=sys.stderr)
    return rc


if __name__ == "__main__":
    sys.exit(main())

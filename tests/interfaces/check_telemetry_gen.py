#!/usr/bin/python3
"""CTest check of the telemetry generator's rules (interfaces/README.md).

usage: check_telemetry_gen.py --repo DIR --cxx COMPILER --include DIR [--include DIR ...] --work DIR

1. gen_telemetry.py refuses inconsistent tags in a .lcm file, naming the file and line.
2. The generated fill functions (the build's <reentry/telemetry_fill.hpp>) do not compile when a
   field has no source or two, when a copy narrows, when an enum source's values differ from the
   field's constants or an enum source has none, or when a flag's source is not a bool; a
   complete source compiles (the control).
"""
import argparse
import os
import shutil
import subprocess
import sys

FAILURES = []

GOOD_CMD = """
#include <cstdint>
#include <reentry/telemetry_fill.hpp>
enum class Phase : std::int8_t { kInitialDescent, kTracking, kReversal, kTerminal, kSafe };
struct Out { double alpha_rad; double sigma_rad; Phase phase; int plan_seq; std::int32_t health_flags; };
"""

TRACKER = """
#include <cstdint>
#include <reentry/telemetry_fill.hpp>
enum class TP : std::int8_t { kInitialDescent, kPlanned, kHeadingCorridor, kTerminalRange, kFinalReversal };
struct T {
  TP phase;
  bool reversing; bool final_reversal_done; bool final_correction_done; bool pullout_arrested; bool saturated;
  double drag_ref_mps2, drag_err_mps2, drag_integral_mps, omega_radps, drag_ratio, lift_over_drag_ratio;
  double corridor_half_width_rad, heading_err_rad, terminal_increment_mps2, time_to_go_s, mean_bank_rad;
  double cross_track_m, along_track_m;
};
"""

# name -> (source text, call, text the compiler must print)
COMPILE_CASES = {
    "control": (GOOD_CMD, "reentry::guidance_cmd_t m{}; reentry::fill(m, Out{});", None),
    "missing_field": (GOOD_CMD.replace(" double sigma_rad;", ""), "reentry::guidance_cmd_t m{}; reentry::fill(m, Out{});",
                      "guidance_cmd_t.sigma_rad: exactly one source must have a member sigma_rad"),
    "two_sources": (GOOD_CMD + "struct Extra { double alpha_rad; };",
                    "reentry::guidance_cmd_t m{}; reentry::fill(m, Out{}, Extra{});",
                    "guidance_cmd_t.alpha_rad: exactly one source must have a member alpha_rad"),
    "narrowing": (GOOD_CMD.replace("int plan_seq", "std::int64_t plan_seq"),
                  "reentry::guidance_cmd_t m{}; reentry::fill(m, Out{});",
                  "guidance_cmd_t.plan_seq: the type of plan_seq narrows"),
    "enum_out_of_step": (GOOD_CMD.replace("kTracking, kReversal", "kReversal, kTracking"),
                         "reentry::guidance_cmd_t m{}; reentry::fill(m, Out{});",
                         "MODE_TRACKING differs from the source enum's kTracking"),
    "enum_without_constants": (GOOD_CMD.replace("int plan_seq", "Phase plan_seq"),
                               "reentry::guidance_cmd_t m{}; reentry::fill(m, Out{});",
                               "declare its values as PLAN_SEQ_* constants"),
    "tracker_control": (TRACKER, "reentry::tracker_status_t m{}; reentry::fill(m, T{});", None),
    "flag_not_bool": (TRACKER.replace("bool reversing;", "int reversing;"),
                      "reentry::tracker_status_t m{}; reentry::fill(m, T{});",
                      "FLAGS_REVERSING needs exactly one source with a bool reversing"),
}

LCM_HEAD = "package reentry;\n\n"
# name -> (.lcm text, text the generator must print)
GEN_CASES = {
    "bits_not_one_bit": (LCM_HEAD + "// @fill\nstruct a_t\n{\n    const int8_t FLAGS_X = 3;\n    int64_t utime;\n"
                         "    int64_t tick;\n    int8_t flags;  // @bits\n}\n", "FLAGS_X = 3 is not one bit"),
    "bits_repeated": (LCM_HEAD + "// @fill\nstruct a_t\n{\n    const int8_t FLAGS_X = 2;\n    const int8_t FLAGS_Y = 2;\n"
                      "    int8_t flags;  // @bits\n}\n", "FLAGS_Y = 2 repeats a bit"),
    "bits_without_constants": (LCM_HEAD + "// @fill\nstruct a_t\n{\n    int8_t flags;  // @bits\n}\n",
                               "@bits needs one constant FLAGS_<NAME>"),
    "unknown_tag": (LCM_HEAD + "// @fill\nstruct a_t\n{\n    double x;  // @frm y\n}\n", "unknown tag @frm"),
    "from_on_core": (LCM_HEAD + "// @core ns::A\nstruct a_t\n{\n    double x;  // @from y\n}\n",
                     "do not apply to a @core message"),
    "enum_without_constants": (LCM_HEAD + "// @core ns::A\nstruct a_t\n{\n    int8_t phase;  // @enum ns::P \"p.hpp\"\n}\n",
                               "@enum needs the values as constants PHASE_*"),
    "field_tag_on_struct": (LCM_HEAD + "// @bits\nstruct a_t\n{\n    double x;\n}\n", "belongs on a field"),
}


def expect(cond, msg):
    if not cond:
        FAILURES.append(msg)
        print(f"FAIL: {msg}")


def check_generator(a):
    gen = os.path.join(a.repo, "tools", "logtools", "gen_telemetry.py")
    for name, (text, want) in GEN_CASES.items():
        path = os.path.join(a.work, name + ".lcm")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        p = subprocess.run([sys.executable, gen, "--core", os.path.join(a.work, "core.hpp"),
                            "--fill", os.path.join(a.work, "fill.hpp"), path], capture_output=True, text=True)
        expect(p.returncode != 0, f"generator accepted {name}")
        expect(want in p.stderr and f"{name}.lcm:" in p.stderr, f"generator on {name}: {p.stderr.strip()!r}")


def check_compiler(a):
    includes = [f"-I{d}" for d in a.include]
    for name, (head, call, want) in COMPILE_CASES.items():
        path = os.path.join(a.work, name + ".cpp")
        with open(path, "w", encoding="utf-8") as f:
            f.write(head + "\nint main() {\n  " + call + "\n  return 0;\n}\n")
        p = subprocess.run([a.cxx, "-std=c++17", "-fsyntax-only", *includes, path], capture_output=True, text=True)
        if want is None:
            expect(p.returncode == 0, f"{name} does not compile: {p.stderr[:2000]}")
        else:
            expect(p.returncode != 0, f"{name} compiles")
            expect(want in p.stderr, f"{name}: the compiler does not say '{want}': {p.stderr[:2000]}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repo", required=True)
    ap.add_argument("--cxx", required=True)
    ap.add_argument("--include", action="append", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    check_generator(a)
    check_compiler(a)
    if FAILURES:
        print(f"{len(FAILURES)} failure(s)")
        return 1
    print(f"ok ({len(GEN_CASES)} generator cases, {len(COMPILE_CASES)} compile cases)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

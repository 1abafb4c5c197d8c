// Fixed-rate guidance executive (DESIGN §2-§3): one cycle per navigation tick,
//   validate nav -> adopt a due plan -> track + filter -> command + status -> request a plan.
// The planner runs on a worker thread started at init; requests and results cross threads
// through preallocated lock-free SPSC queues (spsc_queue.hpp). The planner and the per-cycle
// command law (tracker + rate filter) are injected through small interfaces so the executive
// can be tested with deterministic doubles; the guidance process wires the real components.
// No heap allocation, no exceptions, no I/O after init; every wait is bounded.
#pragma once

#include <atomic>
#include <cstdint>
#include <thread>

#include "exec/spsc_queue.hpp"
#include "physics/earth_constants.hpp"
#include "guidance_types.hpp"

namespace reentry::fsw::exec {

/// How plans are computed and adopted.
enum class PlanMode : std::int8_t {
  kLockstep = 0,     // worker thread; plan requested at tick k adopted exactly at k + L: when it is
                     // late, step() returns awaiting_plan and the caller resumes the cycle (a plan wait)
  kRealtime = 1,     // worker thread; plan adopted at the first cycle after it is ready
  kSynchronous = 2,  // computed inline at the request, adopted at k + L (same results as lockstep)
};

/// Health flag bits (guidance_cmd_t / guidance_status_t health_flags).
enum HealthFlag : std::int32_t {
  kHealthNavInvalid = 1 << 0,     // last nav rejected: last valid command held
  kHealthPlanOverrun = 1 << 1,    // the plan adopted in this cycle took longer than its budget L / f
  kHealthPlanTimeout = 1 << 2,    // bounded wait for a plan expired; plan discarded
  kHealthPlannerFailed = 1 << 3,  // last plan returned a non-ok status (not adopted)
  kHealthNoPlan = 1 << 4,         // no plan adopted yet
  kHealthLinkLoss = 1 << 5,       // set by the process adapter on link loss
  kHealthRangeTooLong = 1 << 6,   // the active plan is the maximum-drag best effort: TAEM will be overflown
  kHealthPlanWait = 1 << 7,       // lockstep: the cycle of this tick waits for its plan (status heartbeat)
};

/// Why a navigation sample was not used (CycleOutput::nav_verdict).
enum class NavVerdict : std::int8_t {
  kAccepted = 0,
  kDuplicate = 1,       // tick already accepted: nothing new (the adapter may repeat its answer)
  kRejectedValues = 2,  // tick and time plausible, values not: answered with the held command, flagged
  kRejectedTick = 3,    // tick or time implausible (negative, backwards, too far ahead, t_s != tick / f,
                        // or a new tick while a lockstep cycle waits): not answered, nothing adopted
};

/// The mission's entry interface as the first-sample check sees it (the process layer fills it
/// from the mission and its dispersions at start-up). A sample with no accepted sample before
/// it must be reachable from this state in its time since the entry interface (t_s = tick / f):
/// radius, speed, flight-path angle and position within their tolerances plus what the windows'
/// rates allow over that time; energy (7.8) at most the entry's (an unpowered vehicle only
/// loses energy, dE/dt = -D V); the sensed aerodynamic force at most what the air can give at
/// the sample's radius and speed (density growing at most as exp(dh / H_min) below the entry).
struct EntryEnvelope {
  bool known = false;                       // false: a first sample meets the absolute windows only
  double radius_m = 0.0;                    // entry radius [m] (surface radius at the entry latitude + altitude)
  double radius_tol_m = 0.0;                // [m], >= 0: Earth shape (sphere or ellipsoid) + navigation error
  double velocity_mps = 0.0;                // Earth-relative entry speed [m/s], > 0
  double velocity_tol_mps = 0.0;            // [m/s], >= 0: entry-velocity dispersion + navigation error
  double flight_path_rad = 0.0;             // entry flight-path angle [rad]
  double flight_path_tol_rad = 0.0;         // [rad], >= 0: dispersion + navigation error
  double latitude_rad = 0.0;                // geocentric entry latitude [rad]
  double longitude_rad = 0.0;               // Earth-fixed entry longitude [rad]
  double position_tol_rad = 0.0;            // great-circle angle [rad], >= 0: position dispersion + navigation
  double energy_max_Jpkg = 0.0;             // highest energy (7.8) of a dispersed entry state, margin included
  double specific_force_max_mps2 = 0.0;     // highest sensed aero force at the entry radius and speed [m/s^2], > 0
  double density_scale_height_min_m = 4000.0;  // smallest density scale height below the entry interface [m], > 0
};

/// Plausibility windows every navigation sample must pass before guidance uses it. A sample
/// outside any window is rejected, never adopted; the rate windows are measured from the last
/// accepted sample and widen with the ticks since. The first sample is judged against the
/// mission's entry state (EntryEnvelope). A reference that was itself wrong cannot latch the
/// executive: reacquire_samples consecutive samples that are consistent with each other and
/// reachable from the entry state, but not with the reference, become the new reference.
/// Defaults are far outside any entry flight (X-33/HORUS/X-38/Orbiter peak at < 4 g,
/// < 8 km/s) and tight enough to reject corrupted or spoofed samples.
struct NavWindows {
  double time_tolerance_ticks = 0.25;     // |t_s - tick / f| bound [ticks], (0, 0.5]: nav time is tick / f
  std::int64_t max_tick_gap = 100;        // largest tick step from the last accepted sample [ticks], >= 1
  std::int64_t max_tick = 1000000000;     // no run is longer [ticks] (3 years at 10 Hz): also bounds a first sample
  double altitude_min_m = -10000.0;       // [m], below any landing site
  double altitude_max_m = 1.0e6;          // [m], far above an entry interface (120-150 km)
  double velocity_max_mps = 15000.0;      // Earth-relative speed [m/s] (escape speed 11.2 km/s + margin)
  double specific_force_max_mps2 = 490.0; // |drag|, |lift| sensed [m/s^2] (50 g)
  double climb_rate_max_mps = 15000.0;    // |dh/dt| between accepted samples [m/s]
  double speed_rate_max_mps2 = 600.0;     // |dV/dt| between accepted samples [m/s^2] (drag + gravity < 60 g)
  // Flight-path angle rate (2.33): |gamma'| <= (L + g + V^2/r) / V + 2 omega. Between two
  // samples L is taken as gamma_rate_lift_factor times the larger sensed lift of the two.
  double gamma_rate_lift_factor = 2.0;    // [-], >= 1: lift between the samples above both ends
  double gamma_rate_speed_min_mps = 100.0;  // V floor of the bound [m/s], > 0 (entry flight is faster)
  double gravity_max_mps2 = 9.9;          // g bound [m/s^2], >= the surface gravity (9.83 at the poles)
  double earth_rate_radps = 7.292115e-5;  // omega [rad/s]
  double gamma_tol_rad = 1.0e-3;          // [rad], >= 0: navigation noise on gamma
  int reacquire_samples = 3;              // consistent samples that replace a wrong reference, >= 2
  EntryEnvelope entry;
};

/// The planner, as seen by the executive. Called on the worker thread (or inline in
/// synchronous mode); must not allocate after init.
class PlanComputer {
 public:
  virtual ~PlanComputer() = default;
  virtual Status compute(const RelativeState& from, ReferenceProfile& out) = 0;
};

/// Per-cycle command law: tracker followed by the rate filter.
struct LawOutput {
  double alpha_rad = 0.0;
  double sigma_rad = 0.0;
  Phase phase = Phase::kInitialDescent;
  double lift_over_drag_scale = 1.0;  // in-flight L/D estimate over the model's, for the planner
  // The law's state (the fields of tracker_status_t, generated from its .lcm file), passed on
  // whole; its drag reference and error also schedule the drag-error replans.
  TrackerTelemetry tracker;
};

class CommandLaw {
 public:
  virtual ~CommandLaw() = default;
  virtual void set_profile(const ReferenceProfile& profile) = 0;
  /// `has_profile` is false until the first plan is adopted (the law holds its entry attitude).
  virtual Status step(const RelativeState& state, double dt_s, bool has_profile, LawOutput& out) = 0;
};

struct ExecConfig {
  double gnc_rate_hz = 10.0;
  int plan_latency_ticks = 5;               // L (>= 1: requested after the law step of tick k)
  double replan_period_s = 50.0;
  double replan_drag_error_frac = 0.15;
  double drag_error_replan_spacing_s = 5.0;  // least spacing of drag-error replans (a persistent error does not request every cycle)
  double initial_descent_drag_mps2 = 0.05 * physics::kStandardGravity_mps2;  // replan from the captured state once sensed drag exceeds this
  double plan_wait_limit_s = 30.0;          // bound of the lockstep wait for a late plan
  double replan_floor_energy_Jpkg = 0.0;    // no new plans below this energy (terminal phase)
  PlanMode mode = PlanMode::kLockstep;
  NavWindows nav;
};

/// One navigation sample, already converted to the Earth-relative state by the adapter.
struct NavInput {
  std::int64_t tick = 0;
  RelativeState state;          // state.t_s is the message time even when values_valid is false
  bool values_valid = true;     // false: the adapter could not convert the message (non-finite, r = 0)
};

struct CycleOutput {
  bool emitted = false;          // false: duplicate tick, nothing to publish
  std::int64_t tick = 0;
  double t_s = 0.0;
  double alpha_rad = 0.0;
  double sigma_rad = 0.0;
  Phase phase = Phase::kInitialDescent;
  int plan_seq = 0;
  std::int32_t health_flags = 0;
  bool plan_adopted = false;     // a plan was adopted in this cycle
  bool awaiting_plan = false;    // lockstep: the plan due at this tick is late; call resume()
  NavVerdict nav_verdict = NavVerdict::kAccepted;
  TrackerTelemetry tracker;      // the law's state this cycle (LawOutput::tracker), for telemetry
};

struct ExecCounters {
  double cycle_us_last = 0.0;     // the cycle's own compute time: plan waits and inline plans excluded
  double cycle_us_max = 0.0;
  int plan_overruns = 0;          // plans that took longer than their budget L / f (realtime: or came late)
  int plan_waits = 0;             // lockstep: cycles that waited for a plan not ready at k + L
  double plan_wait_ms_last = 0.0; // wall time of the last plan wait
  double plan_wait_ms_max = 0.0;
  double plan_wait_ms_total = 0.0;
  int plan_timeouts = 0;
  int planner_runs = 0;
  int planner_failures = 0;
  Status last_plan_status = Status::kOk;  // status of the last completed plan
  double planner_ms_last = 0.0;
  double planner_ms_max = 0.0;
  double plan_latency_ms = 0.0;   // request to adoption, wall time
  double plan_adopted_t_s = -1.0; // simulation time of the last adoption
  int invalid_nav = 0;            // every rejected sample (both verdicts below)
  int nav_rejected_values = 0;    // of which: values outside a window (answered with the held command)
  int nav_rejected_tick = 0;      // of which: tick / time implausible (not answered)
  int nav_reacquired = 0;         // references replaced by a consistent run of samples (a wrong one was held)
  int duplicate_ticks = 0;
  int skipped_ticks = 0;
  int plans_adopted = 0;
  int plan_requests = 0;
};

/// Propagate the state over n ticks of dt with the simple energy model used for the
/// planning snapshot: altitude and angles frozen, V' = -D, E' = -D V (dE = -D V dt of sec. 2.6.2,
/// the time derivative of the energy E = V^2/2 - mu/r + const (7.8)),
/// D held at the sensed value. Documented as a first-order prediction over L ticks.
RelativeState predict_state(const RelativeState& s, int n_ticks, double dt_s);

class Executive {
 public:
  Executive() = default;
  ~Executive();
  Executive(const Executive&) = delete;
  Executive& operator=(const Executive&) = delete;

  /// Starts the worker thread (lockstep/realtime). Objects must outlive the executive.
  Status init(const ExecConfig& cfg, PlanComputer& planner, CommandLaw& law);
  /// Stops and joins the worker thread.
  void shutdown();
  /// Clock of the cycle-time figures [ns] (start-up): steady wall time by default; the process
  /// adapter passes its thread's CPU-time clock, so that cycle_us is the cycle's own compute
  /// time and not the time the OS gave other threads while the cycle ran.
  void set_cycle_clock(std::int64_t (*clock_ns)()) { cycle_clock_ns_ = clock_ns; }

  /// One cycle on a navigation sample. In lockstep, when the plan due at this tick is not
  /// ready, returns with awaiting_plan set and nothing emitted: the caller keeps its I/O
  /// going (heartbeats, link supervision) and calls resume() until the cycle completes.
  CycleOutput step(const NavInput& nav);
  /// Continues the cycle that is waiting for its plan (no-op output when none is waiting).
  /// Never blocks: returns awaiting_plan again while the plan is late, or the completed
  /// cycle once it is adopted (or abandoned after plan_wait_limit_s).
  CycleOutput resume();
  bool awaiting_plan() const { return awaiting_; }
  /// The tick whose cycle waits for its plan (valid while awaiting_plan()).
  std::int64_t awaiting_tick() const { return awaiting_nav_.tick; }
  /// True when a sample with this tick would pass the tick window (used by the realtime
  /// adapter to pick the newest plausible sample of a burst).
  bool tick_in_window(std::int64_t tick) const;

  const ExecCounters& counters() const { return counters_; }
  const ReferenceProfile& active_profile() const { return active_; }
  bool has_profile() const { return has_profile_; }
  /// The last command emitted for an accepted sample (what is held on rejection / link loss).
  const CycleOutput& last_valid_output() const { return last_valid_; }

 private:
  struct PlanRequest {
    std::uint64_t id = 0;
    RelativeState from;
  };
  struct PlanResult {
    std::uint64_t id = 0;
    Status status = Status::kInvalidInput;
    double compute_ms = 0.0;
    ReferenceProfile profile;
  };

  static bool finite_state(const RelativeState& s);
  /// How a sample that passed its tick and time checks compares with the reference.
  enum class Fit : std::int8_t { kFits = 0, kAbsurd = 1, kInconsistent = 2, kTooFar = 3 };
  NavVerdict validate(const NavInput& nav, Fit* fit) const;
  bool in_absolute_windows(const RelativeState& s) const;
  bool reachable_from_entry(const RelativeState& s, std::int64_t tick) const;
  bool consistent(const RelativeState& from, std::int64_t from_tick, const RelativeState& s, std::int64_t tick) const;
  double gamma_rate_bound_radps(const RelativeState& a, const RelativeState& b) const;
  bool reacquire(const NavInput& nav, Fit fit);
  CycleOutput held_output(const NavInput& nav, NavVerdict verdict);
  CycleOutput finish_cycle(const NavInput& nav, CycleOutput& out, std::int64_t t_start_ns);
  void worker_loop();
  // False when a lockstep plan is due and not ready (the cycle must wait).
  bool try_adopt(std::int64_t tick, double t_s, CycleOutput& out);
  void adopt(PlanResult& r, std::int64_t tick, double t_s, CycleOutput& out);
  void request_plan(std::int64_t tick, const RelativeState& s);
  bool pop_expected();
  void finish_timing(std::int64_t t_start_ns);
  std::int64_t cycle_now_ns() const;
  void count_skipped(std::int64_t tick);
  double dt_s() const { return 1.0 / cfg_.gnc_rate_hz; }

  ExecConfig cfg_;
  PlanComputer* planner_ = nullptr;
  CommandLaw* law_ = nullptr;
  bool initialised_ = false;

  // Cross-thread handoff.
  SpscQueue<PlanRequest, 2> requests_;
  SpscQueue<PlanResult, 2> results_;
  std::thread worker_;
  std::atomic<bool> stop_{false};
  PlanResult worker_result_;      // touched by the worker thread only

  // Executive-thread state.
  PlanResult pending_;            // result waiting for its adoption tick (lockstep/sync)
  bool pending_ready_ = false;
  PlanRequest request_buffer_;
  std::uint64_t expected_id_ = 0;
  std::int32_t sticky_flags_ = 0;  // planner failure (until the next good plan)
  std::int32_t cycle_flags_ = 0;   // overrun / timeout of this cycle
  bool in_flight_ = false;
  std::uint64_t next_request_id_ = 1;
  std::int64_t due_tick_ = 0;
  std::int64_t request_tick_ = 0;
  std::int64_t request_wall_ns_ = 0;
  double last_request_t_s_ = -1.0;
  int next_plan_seq_ = 1;
  bool first_plan_requested_ = false;
  bool capture_plan_requested_ = false;
  bool replan_after_reversal_ = false;
  double lift_over_drag_scale_ = 1.0;  // latest in-flight L/D estimate of the law (planner input)
  Phase last_phase_ = Phase::kInitialDescent;

  ReferenceProfile active_;
  bool has_profile_ = false;

  bool have_last_nav_ = false;
  std::int64_t last_tick_ = 0;     // last accepted tick (reference of the windows)
  std::int64_t last_seen_tick_ = -1;  // highest tick accepted or answered (skip accounting)
  RelativeState last_state_;       // last accepted state
  // Re-acquisition: the run of consecutive, mutually consistent samples the reference refused.
  int candidate_run_ = 0;
  std::int64_t candidate_tick_ = 0;
  RelativeState candidate_state_;
  ExecCounters counters_;
  // Lockstep plan wait: the accepted sample whose cycle waits, and the cycle's time so far.
  bool awaiting_ = false;
  NavInput awaiting_nav_;
  CycleOutput awaiting_out_;
  std::int64_t wait_start_ns_ = 0;
  std::int64_t cycle_ns_so_far_ = 0;  // cycle clock
  std::int64_t (*cycle_clock_ns_)() = nullptr;
  std::int64_t inline_plan_ns_ = 0;  // synchronous plan computed inside this cycle (excluded)
  CycleOutput last_valid_;
  double last_drag_err_ = 0.0;
  double last_drag_ref_ = 0.0;
};

}  // namespace reentry::fsw::exec

#include "exec/executive.hpp"

#include <chrono>
#include <cmath>
#include <limits>

namespace reentry::fsw::exec {
namespace {

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

RelativeState predict_state(const RelativeState& s, int n_ticks, double dt_s) {
  RelativeState p = s;
  for (int i = 0; i < n_ticks; ++i) {
    p.energy_Jpkg -= p.drag_mps2 * p.velocity_mps * dt_s;  // dE/dt = -D V  (sec. 2.6.2; E of (7.8))
    p.velocity_mps -= p.drag_mps2 * dt_s;                  // dV/dt = -D (gravity along track neglected)
    if (p.velocity_mps < 0.0) p.velocity_mps = 0.0;
    p.t_s += dt_s;
  }
  return p;
}

Executive::~Executive() { shutdown(); }

bool Executive::finite_state(const RelativeState& s) {
  const double v[] = {s.t_s, s.radius_m, s.altitude_m, s.longitude_rad, s.latitude_rad,
                      s.velocity_mps, s.flight_path_rad, s.heading_rad, s.energy_Jpkg,
                      s.drag_mps2, s.lift_mps2};
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

bool Executive::tick_in_window(std::int64_t tick) const {
  if (tick < 0 || tick > cfg_.nav.max_tick) return false;
  if (!have_last_nav_) return true;
  // Both ticks are >= 0, so the difference cannot overflow.
  return tick > last_tick_ && tick - last_tick_ <= cfg_.nav.max_tick_gap;
}

bool Executive::in_absolute_windows(const RelativeState& s) const {
  const NavWindows& w = cfg_.nav;
  return finite_state(s) && s.altitude_m >= w.altitude_min_m && s.altitude_m <= w.altitude_max_m &&
         s.velocity_mps >= 0.0 && s.velocity_mps <= w.velocity_max_mps &&
         std::fabs(s.drag_mps2) <= w.specific_force_max_mps2 && std::fabs(s.lift_mps2) <= w.specific_force_max_mps2;
}

double Executive::gamma_rate_bound_radps(const RelativeState& a, const RelativeState& b) const {
  // (2.33): gamma' = (L cos(sigma) - (g - V^2/r) cos(gamma)) / V + 2 omega cos(lat) sin(chi).
  const NavWindows& w = cfg_.nav;
  const double lift = w.gamma_rate_lift_factor * std::fmax(std::fabs(a.lift_mps2), std::fabs(b.lift_mps2));
  const double v = std::fmax(w.gamma_rate_speed_min_mps, std::fmin(a.velocity_mps, b.velocity_mps));
  const double v_max = std::fmax(a.velocity_mps, b.velocity_mps);
  const double r = std::fmax(1.0, std::fmin(a.radius_m, b.radius_m));
  return (lift + w.gravity_max_mps2 + v_max * v_max / r) / v + 2.0 * w.earth_rate_radps;
}

bool Executive::consistent(const RelativeState& from, std::int64_t from_tick, const RelativeState& s,
                           std::int64_t tick) const {
  // Rates from `from` (both ticks >= 0 and tick > from_tick: no overflow).
  const NavWindows& w = cfg_.nav;
  if (tick <= from_tick || tick - from_tick > w.max_tick_gap) return false;
  const double elapsed_s = static_cast<double>(tick - from_tick) * dt_s();
  return std::fabs(s.altitude_m - from.altitude_m) <= w.climb_rate_max_mps * elapsed_s &&
         std::fabs(s.velocity_mps - from.velocity_mps) <= w.speed_rate_max_mps2 * elapsed_s &&
         std::fabs(s.flight_path_rad - from.flight_path_rad) <=
             gamma_rate_bound_radps(from, s) * elapsed_s + w.gamma_tol_rad;
}

bool Executive::reachable_from_entry(const RelativeState& s, std::int64_t tick) const {
  const NavWindows& w = cfg_.nav;
  const EntryEnvelope& e = w.entry;
  if (!e.known) return true;
  const double t = static_cast<double>(tick) * dt_s();  // time since the entry interface
  const double v_max = e.velocity_mps + e.velocity_tol_mps + w.speed_rate_max_mps2 * t;
  // Great-circle angle between the sample and the entry point (haversine).
  const double dlat = s.latitude_rad - e.latitude_rad, dlon = s.longitude_rad - e.longitude_rad;
  const double hav = std::sin(0.5 * dlat) * std::sin(0.5 * dlat) +
                     std::cos(s.latitude_rad) * std::cos(e.latitude_rad) * std::sin(0.5 * dlon) * std::sin(0.5 * dlon);
  const double angle_rad = 2.0 * std::asin(std::sqrt(std::fmin(1.0, std::fmax(0.0, hav))));
  RelativeState entry = s;
  entry.velocity_mps = e.velocity_mps;
  entry.radius_m = e.radius_m;
  entry.lift_mps2 = w.specific_force_max_mps2;  // the most lift the windows allow since the entry
  const double gamma_rate = gamma_rate_bound_radps(entry, s);
  // The air gives at most rho V^2 / 2 (C S / m): density grows at most as exp(dh / H_min) below
  // the entry radius, q as V^2.
  const double v_ratio = s.velocity_mps / e.velocity_mps;
  const double force_max = e.specific_force_max_mps2 * v_ratio * v_ratio *
                           std::exp(std::fmin(700.0, (e.radius_m - s.radius_m) / e.density_scale_height_min_m));
  const double force = std::hypot(s.drag_mps2, s.lift_mps2);
  return std::fabs(s.radius_m - e.radius_m) <= e.radius_tol_m + v_max * t &&
         std::fabs(s.velocity_mps - e.velocity_mps) <= e.velocity_tol_mps + w.speed_rate_max_mps2 * t &&
         std::fabs(s.flight_path_rad - e.flight_path_rad) <= e.flight_path_tol_rad + gamma_rate * t &&
         angle_rad <= e.position_tol_rad + v_max * t / e.radius_m && s.energy_Jpkg <= e.energy_max_Jpkg &&
         force <= force_max;
}

NavVerdict Executive::validate(const NavInput& nav, Fit* fit) const {
  const NavWindows& w = cfg_.nav;
  const double dt = dt_s();
  *fit = Fit::kAbsurd;
  // Tick and time: ticks count from 0 at the entry interface and t_s = tick / f, so a sample
  // whose time does not match its tick carries a corrupted tick or time; neither can be trusted.
  if (nav.tick < 0 || nav.tick > w.max_tick) return NavVerdict::kRejectedTick;
  // The tick already accepted: nothing new, whatever it carries (the adapter answers again).
  if (have_last_nav_ && nav.tick == last_tick_) return NavVerdict::kDuplicate;
  if (!std::isfinite(nav.state.t_s) ||
      std::fabs(nav.state.t_s - static_cast<double>(nav.tick) * dt) > w.time_tolerance_ticks * dt) {
    return NavVerdict::kRejectedTick;
  }
  // Values: finite, inside the absolute windows, reachable from the mission's entry state.
  const RelativeState& s = nav.state;
  const bool values = nav.values_valid && in_absolute_windows(s) && reachable_from_entry(s, nav.tick);
  if (!tick_in_window(nav.tick)) {
    // Behind the reference (never a candidate) or too far ahead of it (a candidate when sane).
    if (values && have_last_nav_ && nav.tick > last_tick_) *fit = Fit::kTooFar;
    return NavVerdict::kRejectedTick;
  }
  if (!values) return NavVerdict::kRejectedValues;
  // Rates from the last accepted sample: a jump is rejected, the reference is kept.
  if (have_last_nav_ && !consistent(last_state_, last_tick_, s, nav.tick)) {
    *fit = Fit::kInconsistent;
    return NavVerdict::kRejectedValues;
  }
  *fit = Fit::kFits;
  return NavVerdict::kAccepted;
}

bool Executive::reacquire(const NavInput& nav, Fit fit) {
  // A sane sample the reference refuses extends the run of candidates when it is consistent
  // with the previous one; a long enough run means the reference was wrong: it is replaced.
  if (fit != Fit::kInconsistent && fit != Fit::kTooFar) return false;
  if (candidate_run_ > 0 && nav.tick == candidate_tick_) return false;  // the same sample again (republished)
  const bool extends = candidate_run_ > 0 && consistent(candidate_state_, candidate_tick_, nav.state, nav.tick);
  candidate_run_ = extends ? candidate_run_ + 1 : 1;
  candidate_tick_ = nav.tick;
  candidate_state_ = nav.state;
  if (candidate_run_ < cfg_.nav.reacquire_samples) return false;
  candidate_run_ = 0;
  ++counters_.nav_reacquired;
  return true;
}

Status Executive::init(const ExecConfig& cfg, PlanComputer& planner, CommandLaw& law) {
  if (initialised_) return Status::kInvalidInput;
  if (!(cfg.gnc_rate_hz > 0.0) || cfg.plan_latency_ticks < 1 || !(cfg.replan_period_s > 0.0) ||
      !(cfg.plan_wait_limit_s > 0.0)) {
    return Status::kInvalidInput;
  }
  const NavWindows& w = cfg.nav;
  if (!(w.time_tolerance_ticks > 0.0 && w.time_tolerance_ticks <= 0.5) || w.max_tick_gap < 1 || w.max_tick < 1 ||
      !(w.altitude_max_m > w.altitude_min_m) || !(w.velocity_max_mps > 0.0) || !(w.specific_force_max_mps2 > 0.0) ||
      !(w.climb_rate_max_mps > 0.0) || !(w.speed_rate_max_mps2 > 0.0) || !(w.gamma_rate_lift_factor >= 1.0) ||
      !(w.gamma_rate_speed_min_mps > 0.0) || !(w.gravity_max_mps2 > 0.0) || !(w.earth_rate_radps >= 0.0) ||
      !(w.gamma_tol_rad >= 0.0) || w.reacquire_samples < 2) {
    return Status::kInvalidInput;
  }
  const EntryEnvelope& e = w.entry;
  if (e.known && (!(e.radius_m > 0.0) || !(e.radius_tol_m >= 0.0) || !(e.velocity_mps > 0.0) ||
                  !(e.velocity_tol_mps >= 0.0) || !(e.flight_path_tol_rad >= 0.0) || !(e.position_tol_rad >= 0.0) ||
                  !std::isfinite(e.energy_max_Jpkg) || !(e.specific_force_max_mps2 > 0.0) ||
                  !(e.density_scale_height_min_m > 0.0) || !std::isfinite(e.flight_path_rad + e.latitude_rad + e.longitude_rad))) {
    return Status::kInvalidInput;
  }
  cfg_ = cfg;
  planner_ = &planner;
  law_ = &law;
  stop_.store(false, std::memory_order_release);
  if (cfg_.mode != PlanMode::kSynchronous) {
    worker_ = std::thread([this] { worker_loop(); });
  }
  last_valid_.phase = Phase::kSafe;
  last_valid_.health_flags = kHealthNoPlan;
  initialised_ = true;
  return Status::kOk;
}

void Executive::shutdown() {
  stop_.store(true, std::memory_order_release);
  if (worker_.joinable()) worker_.join();
}

void Executive::worker_loop() {
  // Static storage of the worker: one request and one result in flight at a time.
  PlanRequest req;
  PlanResult& result = worker_result_;
  while (!stop_.load(std::memory_order_acquire)) {
    if (!requests_.try_pop(req)) {
      std::this_thread::sleep_for(std::chrono::microseconds(100));
      continue;
    }
    const std::int64_t t0 = now_ns();
    result.id = req.id;
    result.status = planner_->compute(req.from, result.profile);
    result.compute_ms = static_cast<double>(now_ns() - t0) * 1e-6;
    // Only one request is in flight, so the two-slot queue is never full; bounded retry anyway.
    for (int i = 0; i < 100000 && !results_.try_push(result); ++i) std::this_thread::yield();
  }
}

void Executive::request_plan(std::int64_t tick, const RelativeState& s) {
  PlanRequest& req = request_buffer_;
  req.id = next_request_id_++;
  req.from = predict_state(s, cfg_.plan_latency_ticks, dt_s());
  req.from.lift_over_drag_scale = lift_over_drag_scale_;
  request_tick_ = tick;
  due_tick_ = tick + cfg_.plan_latency_ticks;
  request_wall_ns_ = now_ns();
  last_request_t_s_ = s.t_s;
  ++counters_.plan_requests;
  if (cfg_.mode == PlanMode::kSynchronous) {
    const std::int64_t t0 = now_ns(), c0 = cycle_now_ns();
    pending_.id = req.id;
    pending_.status = planner_->compute(req.from, pending_.profile);
    const std::int64_t t1 = now_ns();
    inline_plan_ns_ += cycle_now_ns() - c0;  // the planner's time, not the cycle's
    pending_.compute_ms = static_cast<double>(t1 - t0) * 1e-6;
    pending_ready_ = true;
    in_flight_ = true;
    return;
  }
  if (!requests_.try_push(req)) return;  // cannot happen with one request in flight
  in_flight_ = true;
  pending_ready_ = false;
  expected_id_ = req.id;
}

void Executive::adopt(PlanResult& r, std::int64_t tick, double t_s, CycleOutput& out) {
  in_flight_ = false;
  pending_ready_ = false;
  ++counters_.planner_runs;
  counters_.planner_ms_last = r.compute_ms;
  if (r.compute_ms > counters_.planner_ms_max) counters_.planner_ms_max = r.compute_ms;
  // Budget: the plan had L ticks of real time. Lockstep/synchronous runs are not real time,
  // so the compute time decides; in realtime a plan adopted after k + L is late as well.
  const double budget_ms = 1e3 * static_cast<double>(cfg_.plan_latency_ticks) * dt_s();
  if (r.compute_ms > budget_ms || (cfg_.mode == PlanMode::kRealtime && tick > due_tick_)) {
    ++counters_.plan_overruns;
    cycle_flags_ |= kHealthPlanOverrun;
  }
  counters_.last_plan_status = r.status;
  // A range-too-long plan is the maximum-drag profile inside the constraints: the shortest
  // range the vehicle can fly. It is flown (flagged) rather than no plan or a stale one,
  // both of which would fly further past the aim point and without the constraint bound.
  // Likewise a range-too-short plan (a law's longest-flying profile, not flagged).
  const bool best_effort = (r.status == Status::kRangeTooLong || r.status == Status::kRangeTooShort) &&
                           r.profile.n_points >= 2;
  if (r.status != Status::kOk && !best_effort) {
    ++counters_.planner_failures;
    sticky_flags_ |= kHealthPlannerFailed;
    return;
  }
  sticky_flags_ &= ~kHealthPlannerFailed;
  if (r.status == Status::kRangeTooLong) sticky_flags_ |= kHealthRangeTooLong;
  else sticky_flags_ &= ~kHealthRangeTooLong;
  active_ = r.profile;
  active_.seq = next_plan_seq_++;
  has_profile_ = true;
  law_->set_profile(active_);
  ++counters_.plans_adopted;
  counters_.plan_latency_ms = static_cast<double>(now_ns() - request_wall_ns_) * 1e-6;
  counters_.plan_adopted_t_s = t_s;
  out.plan_adopted = true;
}

bool Executive::pop_expected() {
  // Discard results of abandoned (timed-out) requests.
  for (int i = 0; i < 4; ++i) {
    if (!results_.try_pop(pending_)) return false;
    if (pending_.id == expected_id_) {
      pending_ready_ = true;
      return true;
    }
  }
  return false;
}

bool Executive::try_adopt(std::int64_t tick, double t_s, CycleOutput& out) {
  if (!in_flight_) return true;
  if (cfg_.mode == PlanMode::kRealtime) {
    if (pending_ready_ || pop_expected()) adopt(pending_, tick, t_s, out);
    return true;
  }
  if (tick < due_tick_) return true;
  if (cfg_.mode == PlanMode::kLockstep && !pending_ready_ && !pop_expected()) {
    // Late plan: the cycle waits for it (the caller resumes), so the run stays deterministic.
    if (!awaiting_) return false;
    if (now_ns() - wait_start_ns_ <= static_cast<std::int64_t>(cfg_.plan_wait_limit_s * 1e9)) return false;
    ++counters_.plan_timeouts;
    cycle_flags_ |= kHealthPlanTimeout;
    in_flight_ = false;  // abandoned: its result is discarded when it arrives
    return true;
  }
  if (pending_ready_) adopt(pending_, tick, t_s, out);
  return true;
}

void Executive::count_skipped(std::int64_t tick) {
  // Ticks never received between the highest one seen and this one (both >= 0: no overflow).
  if (last_seen_tick_ >= 0 && tick - 1 > last_seen_tick_) {  // tick >= 0: no overflow
    const std::int64_t gap = tick - last_seen_tick_ - 1;
    const std::int64_t room = std::numeric_limits<int>::max() - counters_.skipped_ticks;
    counters_.skipped_ticks += static_cast<int>(gap < room ? gap : room);
  }
  if (tick > last_seen_tick_) last_seen_tick_ = tick;
}

CycleOutput Executive::held_output(const NavInput& nav, NavVerdict verdict) {
  ++counters_.invalid_nav;
  CycleOutput out;
  out.tick = nav.tick;
  out.t_s = nav.state.t_s;
  out.nav_verdict = verdict;
  if (verdict == NavVerdict::kRejectedTick) {
    ++counters_.nav_rejected_tick;
    out.emitted = false;  // an implausible tick is not answered: the answer could be taken for a real one
    return out;
  }
  ++counters_.nav_rejected_values;
  count_skipped(nav.tick);
  out = last_valid_;
  out.emitted = true;
  out.tick = nav.tick;
  out.t_s = nav.state.t_s;
  out.plan_adopted = false;
  out.awaiting_plan = false;
  out.nav_verdict = verdict;
  out.health_flags = last_valid_.health_flags | kHealthNavInvalid;
  return out;
}

std::int64_t Executive::cycle_now_ns() const { return cycle_clock_ns_ != nullptr ? cycle_clock_ns_() : now_ns(); }

CycleOutput Executive::step(const NavInput& nav) {
  const std::int64_t t_start = cycle_now_ns();
  CycleOutput out;
  out.tick = nav.tick;
  out.t_s = nav.state.t_s;
  if (!initialised_) {
    out.emitted = false;
    return out;
  }
  if (awaiting_) {
    // A lockstep cycle waits for its plan: its sample was accepted, a repeat is a duplicate,
    // anything else cannot belong to this lockstep exchange.
    if (nav.tick == awaiting_nav_.tick) {
      ++counters_.duplicate_ticks;
      out.nav_verdict = NavVerdict::kDuplicate;
      out.awaiting_plan = true;
      return out;
    }
    ++counters_.invalid_nav;
    ++counters_.nav_rejected_tick;
    out.nav_verdict = NavVerdict::kRejectedTick;
    out.awaiting_plan = true;
    return out;
  }
  cycle_flags_ = 0;
  inline_plan_ns_ = 0;

  // 1. Validate the navigation sample.
  Fit fit = Fit::kAbsurd;
  NavVerdict verdict = validate(nav, &fit);
  if (verdict == NavVerdict::kAccepted) candidate_run_ = 0;
  if (reacquire(nav, fit)) verdict = NavVerdict::kAccepted;
  if (verdict == NavVerdict::kDuplicate) {
    ++counters_.duplicate_ticks;
    out.emitted = false;
    out.nav_verdict = verdict;
    return out;  // duplicate: the command for this tick was already produced
  }
  if (verdict != NavVerdict::kAccepted) {
    // Rejected: nothing of the sample is kept (the windows' reference stays the last accepted
    // sample, so the next good one is accepted again); the last valid command is held.
    out = held_output(nav, verdict);
    finish_timing(t_start);
    return out;
  }
  count_skipped(nav.tick);
  have_last_nav_ = true;
  last_tick_ = nav.tick;
  last_state_ = nav.state;

  // 2. Adopt a due plan (lockstep: wait for it if it is late).
  if (!try_adopt(nav.tick, nav.state.t_s, out)) {
    awaiting_ = true;
    awaiting_nav_ = nav;
    awaiting_out_ = out;
    wait_start_ns_ = now_ns();
    cycle_ns_so_far_ = cycle_now_ns() - t_start;
    ++counters_.plan_waits;
    CycleOutput wait;
    wait.tick = nav.tick;
    wait.t_s = nav.state.t_s;
    wait.awaiting_plan = true;
    return wait;
  }
  return finish_cycle(nav, out, t_start);
}

CycleOutput Executive::resume() {
  CycleOutput out;
  if (!awaiting_) return out;
  const std::int64_t t_start = cycle_now_ns();
  const std::int64_t wall_now = now_ns();
  CycleOutput cycle = awaiting_out_;
  if (!try_adopt(awaiting_nav_.tick, awaiting_nav_.state.t_s, cycle)) {
    out.tick = awaiting_nav_.tick;
    out.t_s = awaiting_nav_.state.t_s;
    out.awaiting_plan = true;
    return out;
  }
  awaiting_ = false;
  counters_.plan_wait_ms_last = static_cast<double>(wall_now - wait_start_ns_) * 1e-6;
  counters_.plan_wait_ms_total += counters_.plan_wait_ms_last;
  if (counters_.plan_wait_ms_last > counters_.plan_wait_ms_max) counters_.plan_wait_ms_max = counters_.plan_wait_ms_last;
  // The cycle's own time: before the wait plus from here on (the wait itself is excluded).
  return finish_cycle(awaiting_nav_, cycle, t_start - cycle_ns_so_far_);
}

CycleOutput Executive::finish_cycle(const NavInput& nav, CycleOutput& out, std::int64_t t_start) {
  out.nav_verdict = NavVerdict::kAccepted;
  // 3-4. Track and filter.
  LawOutput law;
  const Status law_status = law_->step(nav.state, dt_s(), has_profile_, law);
  out.emitted = true;
  if (law_status != Status::kOk || !std::isfinite(law.alpha_rad) || !std::isfinite(law.sigma_rad)) {
    // Law could not produce a command: hold the last one.
    out.alpha_rad = last_valid_.alpha_rad;
    out.sigma_rad = last_valid_.sigma_rad;
    out.phase = last_valid_.phase;
  } else {
    out.alpha_rad = law.alpha_rad;
    out.sigma_rad = law.sigma_rad;
    out.phase = law.phase;
  }
  out.tracker = law.tracker;
  if (law_status == Status::kOk && std::isfinite(law.lift_over_drag_scale) && law.lift_over_drag_scale > 0.0) {
    lift_over_drag_scale_ = law.lift_over_drag_scale;
  }
  out.plan_seq = has_profile_ ? active_.seq : 0;

  // 5. Plan scheduling: entry (end of the initial descent), period, after the reversal,
  //    large drag error. One request in flight at a time.
  if (last_phase_ == Phase::kReversal && law.phase != Phase::kReversal) replan_after_reversal_ = true;
  last_phase_ = law.phase;
  if (!in_flight_ && nav.state.energy_Jpkg > cfg_.replan_floor_energy_Jpkg) {
    const RelativeState& s = nav.state;
    bool want = false;
    if (!first_plan_requested_) {
      // At the entry interface: a plan from the entry state, flown once the drag is captured.
      want = true;
      first_plan_requested_ = true;
      capture_plan_requested_ = s.drag_mps2 >= cfg_.initial_descent_drag_mps2;  // already captured
    } else if (!capture_plan_requested_ && s.drag_mps2 >= cfg_.initial_descent_drag_mps2) {
      // End of the initial descent: plan again from the actual (captured) state.
      want = true;
      capture_plan_requested_ = true;
    } else if (replan_after_reversal_) {
      want = true;
      replan_after_reversal_ = false;
    } else if (s.t_s - last_request_t_s_ >= cfg_.replan_period_s - 1e-9) {
      want = true;
    } else if (has_profile_ && law.tracker.drag_ref_mps2 > 0.0 &&
               std::fabs(law.tracker.drag_err_mps2) > cfg_.replan_drag_error_frac * law.tracker.drag_ref_mps2 &&
               s.t_s - last_request_t_s_ >= cfg_.drag_error_replan_spacing_s) {
      want = true;
    }
    if (want) {
      RelativeState from = s;
      from.bank_rad = out.sigma_rad;  // the attitude the law flies (planner input)
      from.alpha_rad = out.alpha_rad;
      request_plan(nav.tick, from);
    }
  }

  std::int32_t flags = sticky_flags_ | cycle_flags_;
  if (!has_profile_) flags |= kHealthNoPlan;
  out.health_flags = flags;
  last_valid_ = out;
  finish_timing(t_start);
  return out;
}

void Executive::finish_timing(std::int64_t t_start_ns) {
  counters_.cycle_us_last = static_cast<double>(cycle_now_ns() - t_start_ns - inline_plan_ns_) * 1e-3;
  inline_plan_ns_ = 0;
  if (counters_.cycle_us_last > counters_.cycle_us_max) counters_.cycle_us_max = counters_.cycle_us_last;
}

}  // namespace reentry::fsw::exec

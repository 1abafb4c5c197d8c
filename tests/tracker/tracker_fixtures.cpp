#include "tracker_fixtures.hpp"

#include <cmath>

#include "planner/entry_planner.hpp"

namespace reentry::fsw::test {

const X33Plan* x33_plan() {
  static const std::unique_ptr<X33Plan> plan = [] {
    auto p = std::make_unique<X33Plan>();
    const auto loaded = config::load_mission("x33");
    if (!loaded.ok) return std::unique_ptr<X33Plan>();
    p->mission = loaded.mission;
    auto planner = std::make_unique<EntryPlanner>();
    if (init_from_mission(*planner, p->mission) != Status::kOk ||
        planner->plan(planner->entry_state(), p->profile) != Status::kOk) {
      return std::unique_ptr<X33Plan>();
    }
    return p;
  }();
  return plan.get();
}

RelativeState level_state_on_profile(const ReferenceProfile& p, int k) {
  RelativeState s{};
  s.radius_m = p.radius_m[k];
  s.altitude_m = p.radius_m[k] - kEarthRadius_m;
  s.velocity_mps = p.velocity_mps[k];
  s.heading_rad = p.heading_rad[k];
  s.energy_Jpkg = p.energy_Jpkg[k];
  s.drag_mps2 = p.drag_mps2[k];
  s.lift_mps2 = p.drag_mps2[k] * p.lift_over_drag[k];
  return s;
}

std::unique_ptr<X33Point> x33_point(int k) {
  const X33Plan* plan = x33_plan();
  if (plan == nullptr) return nullptr;
  auto a = std::make_unique<X33Point>();
  if (init_from_mission(a->models, plan->mission) != Status::kOk) return nullptr;
  a->state = level_state_on_profile(plan->profile, k);
  a->alpha_rad = plan->profile.alpha_rad[k];
  a->mach = a->models.mach(a->state.altitude_m, a->state.velocity_mps);
  return a;
}

std::unique_ptr<X33Point> x33_mid_plan() {
  const X33Plan* plan = x33_plan();
  return plan == nullptr ? nullptr : x33_point(plan->profile.n_points / 2);
}

std::unique_ptr<MidProfile> mid_profile_tracker(double profile_fraction) {
  const X33Plan* plan = x33_plan();
  if (plan == nullptr) return nullptr;
  auto m = std::make_unique<MidProfile>();
  m->mission = plan->mission;
  if (init_from_mission(m->tracker, m->mission) != Status::kOk) return nullptr;
  m->tracker.set_profile(plan->profile);
  m->profile = &plan->profile;
  m->state = level_state_on_profile(plan->profile, static_cast<int>(profile_fraction * (plan->profile.n_points - 1)));
  return m;
}

double profile_time_to_go_s(const ReferenceProfile& p, int j) {
  const int last = p.n_points - 1;
  return (p.energy_Jpkg[j] - p.energy_Jpkg[last]) / (p.drag_mps2[j] * 0.5 * (p.velocity_mps[j] + p.velocity_mps[last]));
}

int profile_index_at_time_to_go(const ReferenceProfile& p, double t_go_s) {
  int k = p.n_points - 1;
  while (k > 0 && profile_time_to_go_s(p, k) < t_go_s) --k;
  return k;
}

double profile_range_to_go_m(const ReferenceProfile& p, int k) {
  double range_m = 0.0;
  for (int j = k; j < p.n_points - 1; ++j) {
    range_m += (p.energy_Jpkg[j] - p.energy_Jpkg[j + 1]) * 0.5 * (1.0 / p.drag_mps2[j] + 1.0 / p.drag_mps2[j + 1]);
  }
  return range_m;
}

double place_from_aim_point(const config::TaemInterface& taem, double distance_m, double offset_rad,
                            RelativeState& st) {
  const double back = taem.heading_rad + M_PI + offset_rad, arc = distance_m / kEarthRadius_m;
  st.latitude_rad = std::asin(std::sin(taem.latitude_rad) * std::cos(arc) +
                              std::cos(taem.latitude_rad) * std::sin(arc) * std::cos(back));
  st.longitude_rad = taem.longitude_rad + std::atan2(std::sin(back) * std::sin(arc) * std::cos(taem.latitude_rad),
                                                     std::cos(arc) - std::sin(taem.latitude_rad) * std::sin(st.latitude_rad));
  const double dlon = taem.longitude_rad - st.longitude_rad;
  return std::atan2(std::sin(dlon) * std::cos(taem.latitude_rad),
                    std::cos(st.latitude_rad) * std::sin(taem.latitude_rad) -
                        std::sin(st.latitude_rad) * std::cos(taem.latitude_rad) * std::cos(dlon));
}

RelativeState sinking_below_reference(const MidProfile& m, int k, double gamma_rad) {
  RelativeState s = m.state;
  s.drag_mps2 = 0.8 * m.profile->drag_mps2[k];
  s.lift_mps2 = s.drag_mps2 * m.profile->lift_over_drag[k];
  s.flight_path_rad = gamma_rad;
  return s;
}

double heat_limit_for_drag_bound(const OnboardModels& models, const RelativeState& s, double alpha_rad,
                                 double drag_bound_mps2) {
  const double cd = models.drag_coefficient(alpha_rad, s.energy_Jpkg, s.altitude_m);
  const double q = s.drag_mps2 / (cd * models.area_over_mass());
  const double heat = models.heat_flux_Wpm2(2.0 * q / (s.velocity_mps * s.velocity_mps), s.velocity_mps, alpha_rad);
  return heat * std::sqrt(drag_bound_mps2 / s.drag_mps2) / 0.97;
}

double pullout_bottom_drag_mps2(const OnboardModels& models, const RelativeState& s, double sigma0_rad,
                                double sigma_rate_radps) {
  const double H = -1.0 / models.dlnrho_dr_fd(s.altitude_m, 100.0);
  const double v_h = s.velocity_mps * std::cos(s.flight_path_rad);
  const double g_eff = level_flight_lift_need_mps2(s.radius_m, v_h, s.latitude_rad, s.heading_rad);
  const double lod = s.lift_mps2 / s.drag_mps2;
  const double t_roll = sigma0_rad > 0.0 ? sigma0_rad / sigma_rate_radps : 0.0;
  auto accel = [&](double t, double h) {
    const double sigma = t < t_roll ? sigma0_rad - sigma_rate_radps * t : 0.0;
    return lod * s.drag_mps2 * std::exp(-h / H) * std::cos(sigma) - g_eff;
  };
  const double h = rk4_pullout_bottom_m(accel, s.velocity_mps * std::sin(s.flight_path_rad), t_roll);
  return s.drag_mps2 * std::exp(-h / H);
}

}  // namespace reentry::fsw::test

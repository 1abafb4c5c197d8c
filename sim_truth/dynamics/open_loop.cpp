#include "dynamics/open_loop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <ostream>
#include <sstream>

#include "physics/earth_constants.hpp"

namespace reentry::truth {

namespace {
using physics::kRadPerDeg;

// Command step of open-loop flights: the mission's GNC tick (10 Hz when the mission gives none).
double gnc_tick_s(const Simulator& sim) {
  const double rate = sim.mission().guidance.gnc_rate_hz;
  return 1.0 / (rate > 0.0 ? rate : 10.0);
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, ',')) out.push_back(trim(field));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

bool parse_number(const std::string& s, double* v) {
  if (s.empty()) return false;
  char* end = nullptr;
  *v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(*v);
}
}  // namespace

void OpenLoopProfile::command_at(double xq, double* a, double* s) const {
  const int n = static_cast<int>(x.size());
  if (xq <= x.front()) {
    *a = alpha_rad.front();
    *s = sigma_rad.front();
    return;
  }
  if (xq >= x.back()) {
    *a = alpha_rad.back();
    *s = sigma_rad.back();
    return;
  }
  const int j = static_cast<int>(std::upper_bound(x.begin(), x.end(), xq) - x.begin()) - 1;
  const int k = std::min(j + 1, n - 1);
  const double w = (xq - x[j]) / (x[k] - x[j]);
  *a = alpha_rad[j] + w * (alpha_rad[k] - alpha_rad[j]);
  *s = sigma_rad[j] + w * (sigma_rad[k] - sigma_rad[j]);
}

bool load_open_loop_profile(const std::string& path, OpenLoopProfile* p, std::string* error) {
  auto fail = [&](int line, const std::string& msg) {
    if (error) *error = path + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + msg;
    return false;
  };
  std::ifstream in(path);
  if (!in) return fail(0, "cannot open open-loop profile");
  *p = OpenLoopProfile{};
  std::string line;
  int line_no = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const auto f = split_csv(t);
    if (!have_header) {
      if (f.size() != 3 || f[1] != "alpha_deg" || f[2] != "sigma_deg" || (f[0] != "t_s" && f[0] != "E_norm"))
        return fail(line_no, "header must be 't_s,alpha_deg,sigma_deg' or 'E_norm,alpha_deg,sigma_deg', got '" + t + "'");
      p->variable = f[0] == "t_s" ? OpenLoopProfile::Variable::kTime : OpenLoopProfile::Variable::kEnergyNorm;
      have_header = true;
      continue;
    }
    if (f.size() != 3) return fail(line_no, "expected 3 columns, got " + std::to_string(f.size()) + " in '" + t + "'");
    double v[3];
    static const char* kNames[3] = {"x", "alpha_deg", "sigma_deg"};
    for (int i = 0; i < 3; ++i)
      if (!parse_number(f[i], &v[i]))
        return fail(line_no, std::string("column ") + (i == 0 ? (p->variable == OpenLoopProfile::Variable::kTime ? "t_s" : "E_norm") : kNames[i]) +
                                 ": not a finite number: '" + f[i] + "'");
    if (std::fabs(v[1]) > 90.0) return fail(line_no, "alpha_deg out of [-90, 90]: '" + f[1] + "'");
    if (std::fabs(v[2]) > 180.0) return fail(line_no, "sigma_deg out of [-180, 180]: '" + f[2] + "'");
    if (p->variable == OpenLoopProfile::Variable::kTime && v[0] < 0.0)
      return fail(line_no, "t_s must not be negative: '" + f[0] + "'");
    if (!p->x.empty()) {
      const bool inc = p->x.size() < 2 || p->x[1] > p->x[0];
      if (v[0] == p->x.back() || (p->x.size() >= 2 && ((v[0] > p->x.back()) != inc)) ||
          (p->variable == OpenLoopProfile::Variable::kTime && v[0] < p->x.back()))
        return fail(line_no, "first column must be strictly monotonic (t_s increasing): '" + f[0] + "'");
    }
    p->x.push_back(v[0]);
    p->alpha_rad.push_back(v[1] * kRadPerDeg);
    p->sigma_rad.push_back(v[2] * kRadPerDeg);
  }
  if (!have_header) return fail(0, "empty file (no header)");
  if (p->x.empty()) return fail(0, "no data rows");
  if (p->x.size() >= 2 && p->x[1] < p->x[0]) {  // decreasing E_norm: store increasing
    std::reverse(p->x.begin(), p->x.end());
    std::reverse(p->alpha_rad.begin(), p->alpha_rad.end());
    std::reverse(p->sigma_rad.begin(), p->sigma_rad.end());
  }
  return true;
}

RunSummary run_open_loop(Simulator& sim, const OpenLoopProfile& profile, double out_dt_s,
                         const std::function<void(const TruthSample&)>& on_sample) {
  const double tick_s = gnc_tick_s(sim);
  const double E_entry = sim.entry_energy_Jpkg();
  long long tick = 0, out_index = 1;
  double t_last_out = sim.time_s();
  while (!sim.finished()) {
    const TruthSample now = sim.sample();
    const double x = profile.variable == OpenLoopProfile::Variable::kTime ? now.t_s : now.E_Jpkg / E_entry;
    double alpha = 0.0, sigma = 0.0;
    profile.command_at(x, &alpha, &sigma);
    sim.set_command(alpha, sigma);
    if (tick == 0 && on_sample) on_sample(sim.sample());  // initial row with the first command
    const double t_tick = static_cast<double>(tick + 1) * tick_s;
    // Output instants inside this GNC interval (commands do not change there).
    while (out_dt_s > 0.0 && !sim.finished()) {
      const double t_out = static_cast<double>(out_index) * out_dt_s;
      if (t_out > t_tick + 1e-9 * tick_s) break;
      if (sim.advance_to(t_out) == SimEvent::kNone && on_sample) {
        on_sample(sim.sample());
        t_last_out = sim.time_s();
      }
      ++out_index;
    }
    if (!sim.finished()) sim.advance_to(t_tick);
    ++tick;
  }
  const RunSummary summary = sim.summary();
  if (on_sample && summary.final_state.t_s != t_last_out) on_sample(summary.final_state);
  return summary;
}

RunMaxima wings_level_pullout_maxima(Simulator& sim, double alpha_rad) {
  const double tick_s = gnc_tick_s(sim);
  sim.set_command(alpha_rad, 0.0);
  // The climb that follows the pull-out is not part of it: stop at the first gamma >= 0.
  while (!sim.finished() && sim.sample().gamma_rad < 0.0) sim.advance_to(sim.time_s() + tick_s);
  return sim.summary().maxima;
}

void write_trajectory_header(std::ostream& out) {
  out << "t_s,h_m,r_m,lat_deg,lon_deg,V_mps,gamma_deg,chi_deg,mach,rho_kgpm3,q_Pa,qdot_Wpm2,Q_Jpm2,n_g,"
         "D_mps2,L_mps2,E_Jpkg,alpha_deg,sigma_deg\n";
}

void write_trajectory_row(std::ostream& out, const TruthSample& s) {
  char buf[640];
  std::snprintf(buf, sizeof(buf),
                "%.6f,%.4f,%.4f,%.9f,%.9f,%.6f,%.8f,%.8f,%.6f,%.9e,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,%.6f,%.6f\n",
                s.t_s, s.h_m, s.r_m, s.lat_rad / kRadPerDeg, s.lon_rad / kRadPerDeg, s.V_mps, s.gamma_rad / kRadPerDeg, s.chi_rad / kRadPerDeg,
                s.mach, s.rho_kgpm3, s.q_Pa, s.qdot_Wpm2, s.Q_Jpm2, s.n_g, s.D_mps2, s.L_mps2, s.E_Jpkg,
                s.alpha_rad / kRadPerDeg, s.sigma_rad / kRadPerDeg);
  out << buf;
}

std::string summary_json(const RunSummary& r, const Simulator& sim) {
  const TruthSample& f = r.final_state;
  const ResolvedSimSettings& st = sim.settings();
  nlohmann::json j;
  j["mission"] = sim.mission().name;
  j["event"] = to_string(r.event);
  if (!r.message.empty()) j["message"] = r.message;
  j["final"] = {{"t_s", f.t_s},           {"h_m", f.h_m},
                {"lat_deg", f.lat_rad / kRadPerDeg}, {"lon_deg", f.lon_rad / kRadPerDeg},
                {"V_mps", f.V_mps},       {"gamma_deg", f.gamma_rad / kRadPerDeg},
                {"chi_deg", f.chi_rad / kRadPerDeg}, {"mach", f.mach},
                {"E_Jpkg", f.E_Jpkg},     {"Q_Jpm2", f.Q_Jpm2},
                {"range_to_taem_m", f.range_to_taem_m}, {"heading_to_taem_deg", f.heading_to_taem_rad / kRadPerDeg}};
  j["max"] = {{"qdot_Wpm2", r.maxima.qdot_Wpm2}, {"qdot_t_s", r.maxima.qdot_t_s},
              {"n_g", r.maxima.n_g},             {"n_g_t_s", r.maxima.n_g_t_s},
              {"q_Pa", r.maxima.q_Pa},           {"q_t_s", r.maxima.q_t_s},
              {"q_alpha_Pa_rad", r.maxima.q_alpha_Pa_rad}, {"q_alpha_t_s", r.maxima.q_alpha_t_s}};
  j["wall_s"] = r.wall_s;
  j["derivative_evaluations"] = r.derivative_evaluations;
  j["steps_accepted"] = r.steps_accepted;
  j["steps_rejected"] = r.steps_rejected;
  j["settings"] = {{"gravity", st.gravity},       {"atmosphere", st.atmosphere}, {"wind", st.wind},
                   {"shape", st.shape},           {"integrator", st.integrator}, {"attitude", st.attitude},
                   {"rel_tol", st.rel_tol},       {"trim", st.trim}};
  if (st.dispersion.dispersed) {
    const DispersionDraw& d = st.dispersion;
    j["dispersion"] = {{"seed", d.seed},
                       {"entry_gamma_deg", d.entry_flight_path_rad / kRadPerDeg},
                       {"entry_heading_deg", d.entry_heading_rad / kRadPerDeg},
                       {"entry_velocity_mps", d.entry_velocity_mps},
                       {"entry_lat_deg", d.entry_latitude_rad / kRadPerDeg},
                       {"entry_lon_deg", d.entry_longitude_rad / kRadPerDeg},
                       {"density_scale", d.density_scale},
                       {"cl_scale", d.cl_scale},
                       {"cd_scale", d.cd_scale},
                       {"mass_scale", d.mass_scale},
                       {"wind_scale", d.wind_scale}};
  }
  return j.dump();
}

}  // namespace reentry::truth

#include "guidance/mission_adapter.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>
#include <vector>

namespace reentry::fsw {
namespace {

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

/// Applies one mission value to the field its key names, if the key is in this list.
struct TuningApplier {
  const config::TuningValue& value;
  std::string prefix;  // "planner." or "tracker." or ""
  bool found = false;
  std::string error;   // "what is wrong" (the caller adds file and key)

  template <class T>
  void operator()(const char* key, T& field, ParamUnit unit, double lo, double hi, const char* /*doc*/) {
    if (found || value.key != prefix + key) return;
    found = true;
    if (!(value.value >= lo && value.value <= hi)) {
      error = "value " + fmt(value.value) + " out of range [" + fmt(lo) + ", " + fmt(hi) + "]";
      return;
    }
    if constexpr (std::is_integral_v<T>) {
      if (!value.integer) {
        error = "expected an integer, got " + fmt(value.value);
        return;
      }
      field = static_cast<T>(value.value);
    } else {
      field = param_to_si(value.value, unit);
    }
  }
};

/// Appends "key = value  [lo, hi]  doc" lines.
struct ParamPrinter {
  std::string prefix;
  std::ostringstream* out;
  template <class T>
  void operator()(const char* key, const T& field, ParamUnit unit, double lo, double hi, const char* doc) {
    const double v = std::is_integral_v<T> ? static_cast<double>(field) : param_from_si(static_cast<double>(field), unit);
    *out << prefix << key << " = " << fmt(v) << "   [" << fmt(lo) << ", " << fmt(hi) << "]   " << doc << "\n";
  }
};

std::string key_error(const config::Mission& m, const std::string& key, const std::string& what) {
  return m.source_file + ": key 'guidance." + key + "': " + what;
}

constexpr const char* kPcPrefix = "predictor_corrector.";

}  // namespace

std::string read_atmosphere_table(const std::string& path, std::vector<double>& h, std::vector<double>& rho,
                                  std::vector<double>& t) {
  std::FILE* f = std::fopen(path.c_str(), "r");
  if (f == nullptr) return path + ": cannot open the on-board atmosphere table";
  char line[256];
  for (int guard = 0; guard < 100000 && std::fgets(line, sizeof line, f) != nullptr; ++guard) {
    if (line[0] == '%' || line[0] == '#') continue;
    double hi = 0.0, rhoi = 0.0, p = 0.0, ti = 0.0;
    if (std::sscanf(line, "%lf %lf %lf %lf", &hi, &rhoi, &p, &ti) != 4) continue;
    h.push_back(hi);
    rho.push_back(rhoi);
    t.push_back(ti);
  }
  std::fclose(f);
  return {};
}

Status trim_data_from_aero(const config::AeroModel& aero, TrimAeroData& d) {
  const std::size_t na = aero.cl.alpha_rad.size(), nm = aero.cl.mach.size(), nodes = na * nm;
  if (na > TrimAeroData::kMaxAlpha || nm > TrimAeroData::kMaxMach || nodes > TrimSurfaceData::kMaxNodes) {
    return Status::kCapacityExceeded;
  }
  auto same_grid = [&](const config::Table2D& t) {
    return t.alpha_rad == aero.cl.alpha_rad && t.mach == aero.cl.mach && t.values.size() == nodes;
  };
  if (!same_grid(aero.cl) || !same_grid(aero.cd) || !same_grid(aero.cm)) return Status::kInvalidInput;
  d.n_alpha = static_cast<int>(na);
  d.n_mach = static_cast<int>(nm);
  std::memcpy(d.alpha_rad, aero.cl.alpha_rad.data(), sizeof(double) * na);
  std::memcpy(d.mach, aero.cl.mach.data(), sizeof(double) * nm);
  std::memcpy(d.cl, aero.cl.values.data(), sizeof(double) * nodes);
  std::memcpy(d.cd, aero.cd.values.data(), sizeof(double) * nodes);
  std::memcpy(d.cm, aero.cm.values.data(), sizeof(double) * nodes);
  d.n_surfaces = 0;
  for (const char* name : {"body_flap", "elevon"}) {
    for (const config::ControlSurface& cs : aero.surfaces) {
      if (cs.name != name) continue;
      const std::size_t nd = cs.deflection_rad.size();
      if (nd > TrimSurfaceData::kMaxDeflections) return Status::kCapacityExceeded;
      if (cs.dcl.size() != nd || cs.dcd.size() != nd || cs.dcm.size() != nd) return Status::kInvalidInput;
      TrimSurfaceData& s = d.surface[d.n_surfaces++];
      s.count = cs.count;
      s.min_rad = cs.min_rad;
      s.max_rad = cs.max_rad;
      s.n_deflections = static_cast<int>(nd);
      for (std::size_t k = 0; k < nd; ++k) {
        if (!same_grid(cs.dcl[k]) || !same_grid(cs.dcd[k]) || !same_grid(cs.dcm[k])) return Status::kInvalidInput;
        s.deflection_rad[k] = cs.deflection_rad[k];
        std::memcpy(s.dcl[k], cs.dcl[k].values.data(), sizeof(double) * nodes);
        std::memcpy(s.dcd[k], cs.dcd[k].values.data(), sizeof(double) * nodes);
        std::memcpy(s.dcm[k], cs.dcm[k].values.data(), sizeof(double) * nodes);
      }
      break;  // the first surface of each kind trims (as in the truth model)
    }
  }
  return d.n_surfaces > 0 ? Status::kOk : Status::kInvalidInput;
}
GuidanceMission to_guidance_mission(const config::Mission& m) {
  GuidanceMission g;
  g.entry = m.entry;
  g.taem = m.taem;
  g.limits = m.constraints;
  return g;
}

std::string guidance_params_from_mission(const config::Mission& m, GuidanceLawParams& p) {
  p = GuidanceLawParams{};
  const config::GuidanceParams& g = m.guidance;
  if (g.drag_profile == "three_segment") p.planner.drag_profile = DragProfileKind::kThreeSegment;
  else if (g.drag_profile == "smooth") p.planner.drag_profile = DragProfileKind::kSmooth;
  else return key_error(m, "drag_profile", "value \"" + g.drag_profile + "\" is not one of \"three_segment\", \"smooth\"");
  if (g.initial_drag == "actual") p.planner.initial_drag = InitialDrag::kActual;
  else if (g.initial_drag == "lmin") p.planner.initial_drag = InitialDrag::kLmin;
  else return key_error(m, "initial_drag", "value \"" + g.initial_drag + "\" is not one of \"actual\", \"lmin\"");
  p.tracker.initial_descent_drag_mps2 = g.initial_descent_drag_mps2;
  for (const config::TuningValue& v : g.tuning) {
    TuningApplier shared{v, "", false, {}}, planner{v, "planner.", false, {}}, tracker{v, "tracker.", false, {}};
    visit_shared_guidance_params(p, shared);
    visit_planner_params(p.planner, planner);
    visit_tracker_params(p.tracker, tracker);
    for (const TuningApplier* a : {&shared, &planner, &tracker}) {
      if (a->found && !a->error.empty()) return key_error(m, v.key, a->error);
    }
    if (v.key.rfind(kPcPrefix, 0) == 0) continue;  // the predictor-corrector's (pc_params_from_mission)
    if (!shared.found && !planner.found && !tracker.found) {
      return key_error(m, v.key, "unknown key (value " + fmt(v.value) +
                                     "); check spelling and unit suffix (reentry_config_check --params lists the keys)");
    }
  }
  if (const char* bad = guidance_params_inconsistency(p)) {
    const std::string key = bad;
    const std::string full = key.rfind("planner.", 0) == 0 || key == "terminal_span_fraction" ? key : "tracker." + key;
    return key_error(m, full, "inconsistent with the related parameters (see its documented relation)");
  }
  return {};
}

std::string pc_params_from_mission(const config::Mission& m, GuidanceLaw& law, PredictorCorrectorParams& p) {
  p = PredictorCorrectorParams{};
  const std::string& name = m.guidance.law;
  if (name == "drag_tracking") law = GuidanceLaw::kDragTracking;
  else if (name == "predictor_corrector") law = GuidanceLaw::kPredictorCorrector;
  else return key_error(m, "law", "value \"" + name + "\" is not one of \"drag_tracking\", \"predictor_corrector\"");
  for (const config::TuningValue& v : m.guidance.tuning) {
    if (v.key.rfind(kPcPrefix, 0) != 0) continue;
    TuningApplier pc{v, kPcPrefix, false, {}};
    visit_pc_params(p, pc);
    if (pc.found && !pc.error.empty()) return key_error(m, v.key, pc.error);
    if (!pc.found) {
      return key_error(m, v.key, "unknown key (value " + fmt(v.value) +
                                     "); check spelling and unit suffix (reentry_config_check --params lists the keys)");
    }
  }
  if (const char* bad = pc_params_inconsistency(p)) {
    return key_error(m, std::string(kPcPrefix) + bad, "inconsistent with the related parameters (see its documented relation)");
  }
  return {};
}

std::string onboard_models_from_mission(const config::Mission& m, OnboardModels& models) {
  const config::Vehicle& v = m.vehicle;
  const std::string where = m.source_file + ": vehicle '" + v.name + "'";
  const HeatFluxModel heating = v.heating_model == config::HeatingModel::kBettsLeadingEdge
                                    ? HeatFluxModel::kBettsLeadingEdge
                                    : HeatFluxModel::kChapmanStagnation;
  if (models.init_vehicle(v.mass_kg, v.reference_area_m2, v.nose_radius_m, heating) != Status::kOk) {
    return where + ": mass, reference area and nose radius must be positive";
  }
  const config::AeroModel& a = v.aero;
  const int na = static_cast<int>(a.cl.alpha_rad.size()), nm = static_cast<int>(a.cl.mach.size());
  if (a.cd.alpha_rad != a.cl.alpha_rad || a.cd.mach != a.cl.mach || static_cast<int>(a.cl.values.size()) != na * nm ||
      static_cast<int>(a.cd.values.size()) != na * nm) {
    return where + ": CL and CD tables must share one (alpha, Mach) grid";
  }
  // Trimmed tables where the vehicle has moment and control-surface data (thesis 3.4), solved
  // on board at start-up by its own trim solve (onboard_trim.hpp).
  const bool trimmed = m.guidance.onboard_trim && !a.cm.empty() && !a.surfaces.empty();
  Status st = Status::kOk;
  if (trimmed) {
    auto data = std::make_unique<TrimAeroData>();  // start-up only (about 0.8 MB)
    st = trim_data_from_aero(a, *data);
    if (st == Status::kOk) st = models.aero().init_trimmed(*data);
  } else {
    st = models.aero().init(a.cl.alpha_rad.data(), na, a.cl.mach.data(), nm, a.cl.values.data(), a.cd.values.data());
  }
  models.set_aero_trimmed(trimmed);
  if (st == Status::kCapacityExceeded) {
    return where + ": aero table of " + std::to_string(na) + " alpha x " + std::to_string(nm) +
           " Mach values exceeds the on-board capacity " + std::to_string(OnboardAero::kMaxAlpha) + " x " +
           std::to_string(OnboardAero::kMaxMach);
  }
  if (st != Status::kOk) return where + ": aero tables rejected on board (" + to_string(st) + ")";
  if (m.guidance.onboard_atmosphere != "table") {
    models.atmosphere().init_exponential();
    return {};
  }
  std::string path = m.environment.us76_table;
  if (!path.empty() && path[0] != '/' && !m.source_file.empty()) {
    const auto slash = m.source_file.find_last_of('/');
    if (slash != std::string::npos) path = m.source_file.substr(0, slash + 1) + path;
  }
  std::vector<double> h, rho, t;
  const std::string err = read_atmosphere_table(path, h, rho, t);
  if (!err.empty()) return err;
  const Status at = models.atmosphere().init_table(h.data(), rho.data(), t.data(), static_cast<int>(h.size()));
  if (at == Status::kCapacityExceeded) {
    return path + ": " + std::to_string(h.size()) + " rows exceed the on-board atmosphere capacity " +
           std::to_string(OnboardAtmosphere::kCapacity);
  }
  if (at != Status::kOk) return path + ": on-board atmosphere table needs >= 2 rows, increasing altitude, positive density and temperature";
  return {};
}

std::string alpha_profile_from_mission(const config::Mission& m, AlphaProfile& profile) {
  const config::Table1D& t = m.alpha_profile;
  const Status st = t.x.size() != t.y.size()
                        ? Status::kInvalidInput
                        : profile.init(t.x.data(), t.y.data(), static_cast<int>(t.x.size()));
  if (st == Status::kCapacityExceeded) {
    return m.source_file + ": [alpha_profile] has " + std::to_string(t.x.size()) + " points; the on-board capacity is " +
           std::to_string(AlphaProfile::kCapacity) + " (at least 1)";
  }
  if (st != Status::kOk) return m.source_file + ": [alpha_profile] rejected on board (" + to_string(st) + ")";
  return {};
}

std::string make_guidance_setup(const config::Mission& m, GuidanceSetup& out) {
  out.mission = to_guidance_mission(m);
  std::string err = guidance_params_from_mission(m, out.params);
  if (err.empty()) err = pc_params_from_mission(m, out.law, out.pc_params);
  if (err.empty()) err = onboard_models_from_mission(m, out.models);
  if (err.empty()) err = alpha_profile_from_mission(m, out.alpha_profile);
  return err;
}

std::string describe_guidance_params(const GuidanceLawParams& p) {
  std::ostringstream os;
  visit_shared_guidance_params(p, ParamPrinter{"guidance.", &os});
  visit_planner_params(p.planner, ParamPrinter{"guidance.planner.", &os});
  visit_tracker_params(p.tracker, ParamPrinter{"guidance.tracker.", &os});
  return os.str();
}

std::string describe_pc_params(const PredictorCorrectorParams& p) {
  std::ostringstream os;
  visit_pc_params(p, ParamPrinter{std::string("guidance.") + kPcPrefix, &os});
  return os.str();
}

namespace {
template <class F>
Status with_setup(const config::Mission& m, F&& init) {
  auto setup = std::make_unique<GuidanceSetup>();
  if (!make_guidance_setup(m, *setup).empty()) return Status::kInvalidInput;
  return init(*setup);
}
}  // namespace

Status init_from_mission(EntryPlanner& planner, const config::Mission& m) {
  return with_setup(m, [&](const GuidanceSetup& s) { return planner.init(s.models, s.alpha_profile, s.mission, s.params); });
}
Status init_from_mission(PredictorCorrectorPlanner& planner, const config::Mission& m) {
  const PcPlanTiming timing{m.guidance.plan_latency_ticks, 1.0 / m.guidance.gnc_rate_hz};
  return with_setup(m, [&](const GuidanceSetup& s) {
    return planner.init(s.models, s.alpha_profile, s.mission, s.pc_params, s.params.tracker.initial_descent_drag_mps2,
                        timing);
  });
}
Status init_from_mission(EntryTracker& tracker, const config::Mission& m) {
  return with_setup(m, [&](const GuidanceSetup& s) { return tracker.init(s.models, s.alpha_profile, s.mission, s.params); });
}
Status init_from_mission(AlphaPlanner& planner, const config::Mission& m) {
  // The alpha planner runs before an alpha profile exists: models and mission data only.
  auto models = std::make_unique<OnboardModels>();
  if (!onboard_models_from_mission(m, *models).empty()) return Status::kInvalidInput;
  return planner.init(*models, to_guidance_mission(m));
}
Status init_from_mission(OnboardModels& models, const config::Mission& m) {
  return onboard_models_from_mission(m, models).empty() ? Status::kOk : Status::kInvalidInput;
}
Status init_from_mission(AlphaProfile& profile, const config::Mission& m) {
  return alpha_profile_from_mission(m, profile).empty() ? Status::kOk : Status::kInvalidInput;
}

}  // namespace reentry::fsw

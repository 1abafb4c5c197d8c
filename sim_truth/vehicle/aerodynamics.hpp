// Aerodynamic coefficients and pitch trim of the truth simulator (thesis 3.4).
#pragma once

#include "reentry/config/mission.hpp"

#include <optional>
#include <string>

namespace reentry::truth {

struct AeroCoefficients {
  double cl = 0.0;
  double cd = 0.0;
  double cm_total = 0.0;     // pitching moment with the trim deflections (0 when trimmed)
  double flap_rad = 0.0;     // body-flap deflection used
  double elevon_rad = 0.0;   // elevon deflection used (each of `count` elevons)
  bool trimmed = false;      // total Cm driven to zero
  bool saturated = false;    // trim impossible within the limits: surfaces at the limit
  bool out_of_range = false; // query outside the tables with OutOfRangePolicy::kError
};

class Aerodynamics {
 public:
  /// Validates the tables (grid sizes, monotonic axes, finite values); nullopt + *error.
  static std::optional<Aerodynamics> create(const config::AeroModel& model, std::string* error = nullptr);

  /// Bilinear interpolation over (alpha, Mach). With trim and moment data: body flap first,
  /// then elevons (3.24); below q_flap_fixed_Pa the flap is fixed and the elevons trim.
  /// cl/cd include the increments of the trim deflections, then are scaled.
  AeroCoefficients coefficients(double alpha_rad, double mach, double q_Pa, bool trim,
                                double cl_scale = 1.0, double cd_scale = 1.0) const;

  bool has_moment_data() const { return !model_.cm.empty(); }
  const config::AeroModel& model() const { return model_; }

 private:
  Aerodynamics() = default;
  config::AeroModel model_;
  int flap_index_ = -1;
  int elevon_index_ = -1;
};

}  // namespace reentry::truth

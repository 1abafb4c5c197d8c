#include "environment/wind.hpp"

#include "environment/interpolation.hpp"
#include "reentry/config/environment_files.hpp"


namespace reentry::truth {
namespace {
void set_error(std::string* error, const std::string& msg) {
  if (error) *error = msg;
}
}  // namespace

Wind Wind::disabled() { return Wind(); }

std::optional<Wind> Wind::create(const std::string& earthgram_file, std::string* error) {
  config::WindProfile profile;
  const std::string err = config::read_wind_profile(earthgram_file, profile);
  if (!err.empty()) {
    set_error(error, err);
    return std::nullopt;
  }
  Wind w;
  w.enabled_ = true;
  w.h_m_ = std::move(profile.h_m);
  w.north_ = std::move(profile.north_mps);
  w.east_ = std::move(profile.east_mps);
  w.up_ = std::move(profile.up_mps);
  w.north_m2_ = detail::natural_spline_moments(w.h_m_, w.north_);
  w.east_m2_ = detail::natural_spline_moments(w.h_m_, w.east_);
  w.up_m2_ = detail::natural_spline_moments(w.h_m_, w.up_);
  return w;
}

}  // namespace reentry::truth

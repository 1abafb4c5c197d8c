#include "models/onboard_trim.hpp"

#include <cmath>

namespace reentry::fsw {
namespace {

using Table = double[TrimSurfaceData::kMaxNodes];

// Increment of one surface at a node, linear in the deflection between the tabulated ones and
// held at the end values outside them.
double increment(const Table* table, const TrimSurfaceData& s, int node, double delta_rad) {
  const int n = s.n_deflections;
  if (n == 1 || delta_rad <= s.deflection_rad[0]) return table[0][node];
  if (delta_rad >= s.deflection_rad[n - 1]) return table[n - 1][node];
  int k = 0;
  while (k + 2 < n && delta_rad > s.deflection_rad[k + 1]) ++k;
  const double w = (delta_rad - s.deflection_rad[k]) / (s.deflection_rad[k + 1] - s.deflection_rad[k]);
  return table[k][node] + w * (table[k + 1][node] - table[k][node]);
}

struct SurfaceTrim {
  double delta_rad = 0.0;
  double cm = 0.0;   // moment left with this deflection
  bool trimmed = false;
};

// Deflection in [min, max] that zeroes cm_before + count dCm(delta) (3.24 for the elevon pair).
// The moment is linear in delta between consecutive break points (the limits and the tabulated
// deflections inside them), so each segment's root is exact; of several roots the smallest
// deflection is taken. Without a root: the limit with the smaller |C_m|.
SurfaceTrim trim_with(const TrimSurfaceData& s, int node, double cm_before) {
  double pts[TrimSurfaceData::kMaxDeflections + 2];
  int np = 0;
  pts[np++] = s.min_rad;
  for (int k = 0; k < s.n_deflections; ++k) {
    if (s.deflection_rad[k] > s.min_rad && s.deflection_rad[k] < s.max_rad) pts[np++] = s.deflection_rad[k];
  }
  pts[np++] = s.max_rad;
  auto moment = [&](double d) { return cm_before + s.count * increment(s.dcm, s, node, d); };
  SurfaceTrim best;
  double f_a = moment(pts[0]);
  for (int i = 0; i + 1 < np; ++i) {
    const double a = pts[i], b = pts[i + 1];
    const double f_b = moment(b);
    double root = 0.0;
    bool found = false;
    if (f_a == 0.0) { root = a; found = true; }
    else if (f_b == 0.0) { root = b; found = true; }
    else if ((f_a < 0.0) != (f_b < 0.0)) { root = a + (b - a) * f_a / (f_a - f_b); found = true; }
    if (found && (!best.trimmed || std::fabs(root) < std::fabs(best.delta_rad))) {
      best.delta_rad = root;
      best.trimmed = true;
    }
    f_a = f_b;
  }
  if (best.trimmed) {
    best.cm = 0.0;
    return best;
  }
  const double f_min = moment(s.min_rad), f_max = moment(s.max_rad);
  best.delta_rad = std::fabs(f_min) <= std::fabs(f_max) ? s.min_rad : s.max_rad;
  best.cm = std::fabs(f_min) <= std::fabs(f_max) ? f_min : f_max;
  return best;
}

bool increasing(const double* x, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x[i]) || (i > 0 && !(x[i] > x[i - 1]))) return false;
  }
  return true;
}

bool finite(const double* x, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) return false;
  }
  return true;
}

}  // namespace

Status solve_trimmed_coefficients(const TrimAeroData& data, double* cl_out, double* cd_out, TrimNode* nodes_out) {
  const int na = data.n_alpha, nm = data.n_mach, nodes = na * nm;
  if (na < 2 || nm < 1 || na > TrimAeroData::kMaxAlpha || nm > TrimAeroData::kMaxMach ||
      nodes > TrimSurfaceData::kMaxNodes || data.n_surfaces < 1 || data.n_surfaces > TrimAeroData::kMaxSurfaces) {
    return Status::kCapacityExceeded;
  }
  if (cl_out == nullptr || cd_out == nullptr) return Status::kInvalidInput;
  if (!increasing(data.alpha_rad, na) || !increasing(data.mach, nm) || !finite(data.cl, nodes) ||
      !finite(data.cd, nodes) || !finite(data.cm, nodes)) {
    return Status::kInvalidInput;
  }
  for (int j = 0; j < data.n_surfaces; ++j) {
    const TrimSurfaceData& s = data.surface[j];
    if (s.n_deflections < 1 || s.n_deflections > TrimSurfaceData::kMaxDeflections || s.count < 1 ||
        !(s.min_rad < s.max_rad) || !increasing(s.deflection_rad, s.n_deflections)) {
      return Status::kInvalidInput;
    }
    for (int k = 0; k < s.n_deflections; ++k) {
      if (!finite(s.dcl[k], nodes) || !finite(s.dcd[k], nodes) || !finite(s.dcm[k], nodes)) return Status::kInvalidInput;
    }
  }
  for (int node = 0; node < nodes; ++node) {
    double cm = data.cm[node];
    double cl = data.cl[node], cd = data.cd[node];
    TrimNode t;
    bool trimmed = false;
    for (int j = 0; j < data.n_surfaces; ++j) {
      const TrimSurfaceData& s = data.surface[j];
      double delta = 0.0;  // a surface not needed stays neutral
      if (!trimmed) {
        const SurfaceTrim st = trim_with(s, node, cm);
        delta = st.delta_rad;
        cm = st.cm;
        trimmed = st.trimmed;
      }
      t.deflection_rad[j] = delta;
      cl += s.count * increment(s.dcl, s, node, delta);
      cd += s.count * increment(s.dcd, s, node, delta);
    }
    if (!(cd > 0.0) || !std::isfinite(cl)) return Status::kInvalidInput;
    t.trimmed = trimmed;
    t.cm_residual = cm;
    cl_out[node] = cl;
    cd_out[node] = cd;
    if (nodes_out != nullptr) nodes_out[node] = t;
  }
  return Status::kOk;
}

}  // namespace reentry::fsw

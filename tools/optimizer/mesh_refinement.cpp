#include "mesh_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace reentry::optimal {

namespace {
constexpr int kX = EntryProblem::kStates;
constexpr int kU = EntryProblem::kControls;

double norm3(const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The table model's dynamics, as the integrators take them.
struct TableDynamics {
  const EntryProblem& pb;
  mutable std::vector<double> path;
  explicit TableDynamics(const EntryProblem& p) : pb(p), path(static_cast<size_t>(std::max(1, p.n_path()))) {}
  void operator()(double t, const double* x, const double* u, double* xdot) const {
    pb.point_on_tables(t, x, u, xdot, path.data());
  }
};
}  // namespace

PointBias model_bias(const EntryProblem& pb, const Trajectory& tr) {
  const int n = tr.points(), np = pb.n_path();
  PointBias b;
  b.f.assign(static_cast<size_t>(n * kX), 0.0);
  b.path.assign(static_cast<size_t>(std::max(1, n * np)), 0.0);
  std::vector<double> gs(static_cast<size_t>(std::max(1, np))), gt(gs.size());
  for (int j = 0; j < n; ++j) {
    const double* x = &tr.x[static_cast<size_t>(j * kX)];
    const double* u = &tr.u[static_cast<size_t>(j * kU)];
    double fs[kX], ft[kX];
    pb.point(tr.time(j), x, u, fs, gs.data());
    pb.point_on_tables(tr.time(j), x, u, ft, gt.data());
    for (int i = 0; i < kX; ++i) b.f[static_cast<size_t>(j * kX + i)] = ft[i] - fs[i];
    for (int i = 0; i < np; ++i) b.path[static_cast<size_t>(j * np + i)] = gt[static_cast<size_t>(i)] - gs[static_cast<size_t>(i)];
  }
  return b;
}

double table_flight_end_error_m(const EntryProblem& pb, const Trajectory& tr, int substeps) {
  const std::vector<double> x = fly_controls<kX, kU>(tr, substeps, TableDynamics(pb));
  const double* xf = &tr.x[static_cast<size_t>((tr.points() - 1) * kX)];
  const double d[3] = {x[0] - xf[0], x[1] - xf[1], x[2] - xf[2]};
  return norm3(d);
}

std::vector<double> local_errors_m(const EntryProblem& pb, const Trajectory& tr, int substeps) {
  const std::vector<double> e = segment_errors<kX, kU>(tr, substeps, TableDynamics(pb));
  const int n_seg = (tr.points() - 1) / 2;
  std::vector<double> out(static_cast<size_t>(n_seg));
  const double tf = tr.time(tr.points() - 1);
  for (int k = 0; k < n_seg; ++k) {
    const double* ek = &e[static_cast<size_t>(k * kX)];
    out[static_cast<size_t>(k)] = norm3(ek) + norm3(ek + 3) * (tf - tr.time(2 * k + 2));
  }
  return out;
}

Mesh refine_mesh(const Mesh& mesh, const std::vector<double>& err, double reduction, int max_segments) {
  const int n = mesh.segments();
  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return err[static_cast<size_t>(a)] > err[static_cast<size_t>(b)]; });
  const double total = std::accumulate(err.begin(), err.end(), 0.0);
  const double goal = total / std::max(1.0, reduction);
  std::vector<bool> split(static_cast<size_t>(n), false);
  double remaining = total;
  int segments = n;
  for (int k : order) {
    if (remaining <= goal || segments >= max_segments) break;
    split[static_cast<size_t>(k)] = true;
    remaining -= err[static_cast<size_t>(k)] * (1.0 - 1.0 / 16.0);
    ++segments;
  }
  Mesh out;
  for (int k = 0; k < n; ++k) {
    out.tau.push_back(mesh.tau[static_cast<size_t>(k)]);
    if (split[static_cast<size_t>(k)]) out.tau.push_back(0.5 * (mesh.tau[static_cast<size_t>(k)] + mesh.tau[static_cast<size_t>(k) + 1]));
  }
  out.tau.push_back(1.0);
  return out;
}

}  // namespace reentry::optimal

// Mesh refinement and model correction of an entry solve.
//
// The collocated trajectory obeys the optimizer's smooth models at its points; the truth flies
// the tables. Two errors separate the two: the discretisation (Hermite-Simpson's local error,
// O(h^5) per segment) and the model difference (the C2 fits against the bilinear tables, about
// 1 % of C_L between the table nodes). After a solve:
// - model correction: the difference table - smooth of the dynamics and of the path rows at
//   every collocation point becomes a constant offset of that point (PointBias), so the next
//   solve meets the collocation equations of the tables' values at the points, with the smooth
//   models' derivatives;
// - error estimate: the solution's controls are flown through the table model by RK4 from the
//   entry state (the end point's distance from the collocated end: the estimate of what the
//   truth's open-loop replay will show), and from each segment's start over that segment (its
//   local error, in metres of position plus the velocity error times the time left);
// - refinement: while the estimated end-point error exceeds the target, the segments with the
//   largest local errors are halved, the solution is carried onto the new mesh (its Hermite
//   cubics) and solved again, warm.
#pragma once

#include <vector>

#include "entry_problem.hpp"
#include "hermite_simpson.hpp"

namespace reentry::optimal {

struct RefinementOptions {
  int max_passes = 4;                 // solves after the first
  int max_segments = 400;
  double end_error_target_m = 600.0;  // estimated end-point error at which refinement stops
  bool model_correction = true;
  int substeps = 8;                   // RK4 steps per segment of the error estimates
  int a_priori_passes = 0;            // refinements of the first mesh by the start's local errors
  double a_priori_reduction = 4.0;    // ... each aiming at this reduction of their sum
};

/// One solve of the refinement sequence.
struct MeshPass {
  int segments = 0;
  SolveStatus status = SolveStatus::kFailure;
  int iterations = 0;
  double wall_s = 0.0;
  double end_error_m = 0.0;  // the estimate after this solve
  bool corrected = false;    // solved with the model correction
};

/// The model correction at the points of `tr`: tables minus smooth models, dynamics and path rows.
PointBias model_bias(const EntryProblem& pb, const Trajectory& tr);

/// Distance between the end of the controls of `tr` flown through the table model (RK4) and the
/// collocated end, at the same time.
double table_flight_end_error_m(const EntryProblem& pb, const Trajectory& tr, int substeps);

/// Local error of each segment in the table model, as metres at the end: |dr| + |dv| (t_f - t).
std::vector<double> local_errors_m(const EntryProblem& pb, const Trajectory& tr, int substeps);

/// The mesh with the segments of the largest local errors halved, enough of them (largest
/// first) that the sum of the errors falls by `reduction` if each halving divides a segment's
/// error by 16; at most max_segments in all.
Mesh refine_mesh(const Mesh& mesh, const std::vector<double>& local_error_m, double reduction, int max_segments);

}  // namespace reentry::optimal

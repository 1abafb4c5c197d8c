// On-board pitch trim (thesis 3.4): trimmed C_L and C_D over the aerodynamic table's
// (alpha, Mach) grid, solved once at start-up from the base tables and the control-surface
// increments, body flap first, elevons second. The planner and the tracker then look up the
// trimmed tables like the basic ones: trim costs nothing in plans and cycles (the thesis
// needed 20-26 s per plan with trim in the loop).
//
// Independent code from the truth model's trim (sim_truth/vehicle/aerodynamics): the truth
// trims at each flight condition (interpolated tables, Brent in the deflection); on board the
// moment is trimmed at the grid nodes, where every increment is piecewise linear in the
// deflection between its tabulated deflections, so each segment's root is exact, and the
// trimmed coefficients are interpolated bilinearly between the nodes like the basic tables.
// The low-q rule of the truth (body flap held fixed below q_flap_fixed, thesis 5.5) is not
// modelled: below 100 Pa the drag is a few hundredths of a g and the guidance flies the
// initial descent open loop.
//
// Plain fixed-capacity data, no loader types: the process layer (or the config conversion in
// OnboardModels::init) fills TrimAeroData. It is large (about 0.8 MB at full capacity) and
// start-up only: allocate it at start-up, solve, and drop it.
#pragma once

#include "guidance_types.hpp"

namespace reentry::fsw {

struct TrimSurfaceData {
  static constexpr int kMaxDeflections = 16;
  static constexpr int kMaxNodes = 1024;     // alpha x Mach grid nodes
  int count = 1;                             // identical surfaces acting together (elevons: 2, thesis 3.24)
  double min_rad = 0.0;                      // deflection limits
  double max_rad = 0.0;
  int n_deflections = 0;
  double deflection_rad[kMaxDeflections] = {};  // strictly increasing
  // Increment of ONE surface at each tabulated deflection, row-major over the grid
  // (node = i_alpha * n_mach + i_mach).
  double dcl[kMaxDeflections][kMaxNodes] = {};
  double dcd[kMaxDeflections][kMaxNodes] = {};
  double dcm[kMaxDeflections][kMaxNodes] = {};
};

struct TrimAeroData {
  static constexpr int kMaxAlpha = 64;
  static constexpr int kMaxMach = 16;
  static constexpr int kMaxSurfaces = 2;     // trim priority order: body flap, then elevons
  int n_alpha = 0;
  int n_mach = 0;
  double alpha_rad[kMaxAlpha] = {};
  double mach[kMaxMach] = {};
  double cl[TrimSurfaceData::kMaxNodes] = {};  // basic (surfaces neutral), row-major
  double cd[TrimSurfaceData::kMaxNodes] = {};
  double cm[TrimSurfaceData::kMaxNodes] = {};
  int n_surfaces = 0;
  TrimSurfaceData surface[kMaxSurfaces];
};

/// Deflections found at one grid node.
struct TrimNode {
  double deflection_rad[TrimAeroData::kMaxSurfaces] = {};
  double cm_residual = 0.0;  // 0 when trimmed; else the surfaces are at the limit nearest trim
  bool trimmed = false;
};

/// Checks the data (sizes within capacity, increasing axes and deflections, limits ordered,
/// finite values) and solves the trim at every node: each surface in turn drives the
/// remaining moment to zero with the smallest deflection inside its limits that does, or goes
/// to the limit leaving the smallest |C_m|; C_L and C_D include the increments of the
/// deflections found. cl_out, cd_out: n_alpha * n_mach values; nodes_out (optional) the same
/// count of TrimNode. Bounded loops, no allocation.
Status solve_trimmed_coefficients(const TrimAeroData& data, double* cl_out, double* cd_out,
                                  TrimNode* nodes_out = nullptr);

}  // namespace reentry::fsw

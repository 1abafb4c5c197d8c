// The mesh refinement's pieces on problems with known answers: the carried trajectory of a
// cubic is the cubic, the RK4 error estimates vanish on an exact solution and return a defect
// put into it, and refinement halves the worst segments first.
#include <gtest/gtest.h>

#include <cmath>

#include "hermite_simpson.hpp"
#include "mesh_refinement.hpp"

namespace reentry::optimal {
namespace {

// x' = 3 t^2 + u, u the control: with u = 0 the solution from x(0) = 0 is t^3.
struct Cubic {
  static constexpr int kStates = 1, kControls = 1, kParams = 1;
  int n_path() const { return 0; }
  template <class T>
  void point(const T& t, const T*, const T* u, T* xdot, T*) const {
    xdot[0] = 3.0 * t * t + u[0];
  }
};

Trajectory cubic_on(const Mesh& mesh, double tf) {
  Trajectory tr;
  tr.tau = mesh.point_tau();
  tr.p = {tf};
  for (double s : tr.tau) {
    const double t = s * tf;
    tr.x.push_back(t * t * t);
    tr.u.push_back(0.0);
  }
  return tr;
}

TEST(MeshRefinement, ACubicCarriedOntoAnotherMeshIsTheCubic) {
  const Trajectory tr = cubic_on(Mesh::uniform(3), 2.0);
  const Mesh fine{{0.0, 0.1, 0.25, 0.5, 0.6, 0.99, 1.0}};
  const Trajectory out = interpolate(Cubic{}, tr, fine);
  ASSERT_EQ(out.points(), 2 * fine.segments() + 1);
  for (int j = 0; j < out.points(); ++j) {
    const double t = out.tau[static_cast<size_t>(j)] * 2.0;
    EXPECT_NEAR(out.x[static_cast<size_t>(j)], t * t * t, 1e-12) << j;
  }
}

TEST(MeshRefinement, ErrorEstimatesVanishOnTheExactSolutionAndReturnADefect) {
  Trajectory tr = cubic_on(Mesh::uniform(4), 2.0);
  auto f = [](double t, const double*, const double* u, double* xdot) { xdot[0] = 3.0 * t * t + u[0]; };
  const std::vector<double> exact = segment_errors<1, 1>(tr, 4, f), end = fly_controls<1, 1>(tr, 4, f);
  for (double e : exact) EXPECT_NEAR(e, 0.0, 1e-12);
  EXPECT_NEAR(end[0], 8.0, 1e-12);
  tr.x[4] += 0.25;  // the node ending segment 1 (points 0..8: nodes at even indices)
  const std::vector<double> e = segment_errors<1, 1>(tr, 4, f);
  EXPECT_NEAR(e[1], -0.25, 1e-12);
  EXPECT_NEAR(e[2], 0.25, 1e-12);  // the next segment starts from the moved node
  EXPECT_NEAR(e[0], 0.0, 1e-12);
  EXPECT_NEAR(e[3], 0.0, 1e-12);
}

TEST(MeshRefinement, HalvesTheSegmentsWithTheLargestErrorsFirst) {
  const Mesh mesh = Mesh::uniform(5);
  const std::vector<double> err = {1.0, 50.0, 2.0, 30.0, 1.0};  // sum 84
  // Halving segment 1 leaves 84 - 50 (15/16) = 37.1: a reduction of 2 needs only it.
  const Mesh one = refine_mesh(mesh, err, 2.0, 100);
  ASSERT_EQ(one.segments(), 6);
  EXPECT_NEAR(one.tau[2], 0.3, 1e-15);
  // A reduction of 4 (to 21) also halves segment 3.
  const Mesh two = refine_mesh(mesh, err, 4.0, 100);
  ASSERT_EQ(two.segments(), 7);
  EXPECT_NEAR(two.tau[5], 0.7, 1e-15);
  // The segment limit bounds it.
  EXPECT_EQ(refine_mesh(mesh, err, 1e6, 6).segments(), 6);
}

}  // namespace
}  // namespace reentry::optimal

// Automatic differentiation scalars of the optimizer: Eigen's forward-mode AutoDiffScalar with
// a fixed-size gradient (no allocation per operation), and the same type nested once for second
// derivatives (forward over forward: the Hessian of a function of N variables in one pass).
#pragma once

// Eigen/Dense must come first: the AutoDiff module uses Eigen internals without including them.
#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

namespace reentry::optimal {

template <int N>
using Gradient = Eigen::Matrix<double, N, 1>;
/// First derivatives with respect to N variables.
template <int N>
using Ad1 = Eigen::AutoDiffScalar<Gradient<N>>;
/// First and second derivatives with respect to N variables: value().derivatives() is the
/// gradient, derivatives()[i].derivatives()[k] the Hessian entry (i, k).
template <int N>
using Ad2 = Eigen::AutoDiffScalar<Eigen::Matrix<Ad1<N>, N, 1>>;

/// Independent variables w[0..N-1] as first-order AD scalars.
template <int N>
void seed(const double* w, Ad1<N>* a) {
  for (int i = 0; i < N; ++i) a[i] = Ad1<N>(w[i], N, i);
}

/// Independent variables w[0..N-1] as second-order AD scalars.
template <int N>
void seed(const double* w, Ad2<N>* a) {
  for (int i = 0; i < N; ++i) {
    a[i].value() = Ad1<N>(w[i], N, i);
    for (int k = 0; k < N; ++k) a[i].derivatives()[k] = Ad1<N>(k == i ? 1.0 : 0.0, Gradient<N>::Zero());
  }
}

}  // namespace reentry::optimal

// Scalar-generic helpers of the truth models. Every truth-model evaluation is written once as
// a template over its scalar type: the simulator instantiates it with double, the trajectory
// optimizer (tools/optimal) with Eigen automatic-differentiation scalars, so both run one
// implementation of the physics. The double overloads below call exactly the <cmath>
// functions the models used before they were templated (std::fmin, std::hypot, ...), so the
// simulator's double path is unchanged bit for bit; the generic versions branch on the value
// (table cells, clamps and root brackets are chosen on values; derivatives follow the branch
// taken, i.e. one-sided at a kink).
#pragma once

#include <Eigen/Dense>

#include <cmath>
#include <type_traits>

namespace reentry::truth::scalar {

template <class T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

template <class T>
inline constexpr bool is_double = std::is_same_v<T, double>;

/// The double value of a scalar (an AD scalar's value, recursively for nested AD).
inline double value(double x) { return x; }
template <class T>
double value(const T& x) {
  return value(x.value());
}

inline double fmin(double a, double b) { return std::fmin(a, b); }
inline double fmax(double a, double b) { return std::fmax(a, b); }
template <class T>
T fmin(const T& a, double b) {
  return value(a) <= b ? a : T(b);
}
template <class T>
T fmax(const T& a, double b) {
  return value(a) >= b ? a : T(b);
}

inline double hypot(double a, double b) { return std::hypot(a, b); }
template <class T>
T hypot(const T& a, const T& b) {
  using std::sqrt;
  return sqrt(a * a + b * b);
}

/// x^y for x > 0 (Eigen's AutoDiff pow does not nest; exp(y ln x) does).
inline double pow(double x, double y) { return std::pow(x, y); }
template <class T>
T pow(const T& x, double y) {
  using std::exp;
  using std::log;
  return exp(y * log(x));
}

}  // namespace reentry::truth::scalar

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
#include <unsupported/Eigen/AutoDiff>

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

/// f(x) from the value f and the derivatives d1 = f'(x), d2 = f''(x) at value(x): the double
/// value itself, or for an Eigen AD scalar (first order, or nested once for second order) its
/// derivatives by the chain rule in one step. A function whose own arithmetic is long (a table
/// spline) costs the same in AD as in double this way.
inline double chain(double, double f, double, double) { return f; }
template <class Der>
Eigen::AutoDiffScalar<Der> chain(const Eigen::AutoDiffScalar<Der>& x, double f, double d1, double d2) {
  using Inner = typename Der::Scalar;
  if constexpr (std::is_same_v<Inner, double>) {
    return Eigen::AutoDiffScalar<Der>(f, Der(d1 * x.derivatives()));
  } else {
    const auto& g = x.value().derivatives();
    Der der = x.derivatives();
    for (Eigen::Index k = 0; k < der.size(); ++k) {
      const Inner& xk = x.derivatives()[k];
      der[k] = Inner(d1 * xk.value(), d1 * xk.derivatives() + (d2 * xk.value()) * g);
    }
    return Eigen::AutoDiffScalar<Der>(Inner(f, d1 * g), der);
  }
}

/// f(a, b) likewise from f, its gradient (fa, fb) and its Hessian (faa, fab, fbb) at the values.
struct Taylor2 {
  double f, fa, fb, faa, fab, fbb;
};
inline double chain(double, double, const Taylor2& t) { return t.f; }
template <class Der>
Eigen::AutoDiffScalar<Der> chain(const Eigen::AutoDiffScalar<Der>& a, const Eigen::AutoDiffScalar<Der>& b,
                                 const Taylor2& t) {
  using Inner = typename Der::Scalar;
  if constexpr (std::is_same_v<Inner, double>) {
    return Eigen::AutoDiffScalar<Der>(t.f, Der(t.fa * a.derivatives() + t.fb * b.derivatives()));
  } else {
    const auto& ga = a.value().derivatives();
    const auto& gb = b.value().derivatives();
    Der der = a.derivatives();
    for (Eigen::Index k = 0; k < der.size(); ++k) {
      const Inner& ak = a.derivatives()[k];
      const Inner& bk = b.derivatives()[k];
      const double ca = t.faa * ak.value() + t.fab * bk.value(), cb = t.fab * ak.value() + t.fbb * bk.value();
      der[k] = Inner(t.fa * ak.value() + t.fb * bk.value(),
                     t.fa * ak.derivatives() + t.fb * bk.derivatives() + ca * ga + cb * gb);
    }
    return Eigen::AutoDiffScalar<Der>(Inner(t.f, t.fa * ga + t.fb * gb), der);
  }
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

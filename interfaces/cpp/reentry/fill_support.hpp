// Support of the generated fill functions (<reentry/telemetry_fill.hpp>, written at build time by
// tools/logtools/gen_telemetry.py from interfaces/*.lcm; see interfaces/README.md).
//
// reentry::fill(msg, sources...) copies every field of a message from the one source struct
// that has a member of the field's name (or of its @from path). A probe per field tells, at
// compile time, which source has it; the generated code asserts that exactly one does, so a
// field without a source (or with two) does not build. Copies never narrow (int64 -> int32,
// double -> float do not build); an enum is copied by value after the generated check of its
// enumerators against the field's constants. No allocation, no branches beyond the bit packing.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace reentry {

/// The time stamp every message carries: utime [us] of the simulation time t_s, and the tick.
template <class Msg>
void stamp(Msg& m, double t_s, std::int64_t tick) {
  m.utime = std::llround(t_s * 1e6);
  m.tick = tick;
}

namespace fill_support {

/// Probe `Name` for the member `Path` (a name or a path such as `tracker.drag_err_mps2`):
/// Name::has<S>::value tells whether S has it, Name::get(s) reads it.
#define REENTRY_FILL_PROBE(Name, Path)                                                          \
  struct Name {                                                                                 \
    template <class S, class = void>                                                            \
    struct has : std::false_type {};                                                            \
    template <class S>                                                                          \
    struct has<S, std::void_t<decltype(std::declval<const S&>().Path)>> : std::true_type {};    \
    template <class S>                                                                          \
    static const auto& get(const S& s) {                                                        \
      return s.Path;                                                                            \
    }                                                                                           \
  }

/// How many of the sources S... have the probed member.
template <class Probe, class... S>
inline constexpr int sources_with = (0 + ... + (Probe::template has<S>::value ? 1 : 0));

/// The first source type with the probed member (void: none).
template <class Probe, class... S>
struct source_of {
  using type = void;
};
template <class Probe, class F, class... R>
struct source_of<Probe, F, R...> {
  using type = std::conditional_t<Probe::template has<F>::value, F, typename source_of<Probe, R...>::type>;
};

template <class Probe, class Src>
struct probe_value {
  using type = std::decay_t<decltype(Probe::get(std::declval<const Src&>()))>;
};
template <class Probe>
struct probe_value<Probe, void> {
  using type = void;
};
/// The type of the probed member in its source (void: no source has it).
template <class Probe, class... S>
using value_t = typename probe_value<Probe, typename source_of<Probe, S...>::type>::type;

/// The probed member of the first source that has it.
template <class Probe, class First, class... Rest>
const auto& pick(const First& first, const Rest&... rest) {
  if constexpr (Probe::template has<First>::value || sizeof...(Rest) == 0) {
    return Probe::get(first);
  } else {
    return pick<Probe>(rest...);
  }
}

/// True when T{v} is well formed for a V: the conversion does not narrow.
template <class T, class V, class = void>
struct converts_without_narrowing : std::false_type {};
template <class T, class V>
struct converts_without_narrowing<T, V, std::void_t<decltype(T{std::declval<const V&>()})>> : std::true_type {};

/// True when a V copied into a T narrows (void: no source, reported by its own check).
template <class T, class V>
inline constexpr bool narrows = !std::is_void_v<V> && !std::is_enum_v<V> && !converts_without_narrowing<T, V>::value;

/// A source value as the field's type: an enum by its value (its enumerators are checked
/// against the field's constants by the generated code), anything else without narrowing.
template <class T, class V>
constexpr T convert(const V& v) {
  if constexpr (std::is_enum_v<V>) {
    static_assert(std::is_integral_v<T>, "an enum source needs an integer field");
    return static_cast<T>(v);
  } else {
    static_assert(converts_without_narrowing<T, V>::value,
                  "the source member narrows into the field (e.g. int64 into int32, double into float, "
                  "an integer into a double): convert it in the source struct");
    return T{v};
  }
}

/// The compile-time length of a source array: a C array, or a fixed-size Eigen vector (-1: unknown).
template <class A, class = void>
struct fixed_length {
  static constexpr long long value = std::is_array_v<A> ? static_cast<long long>(std::extent_v<A>) : -1;
};
template <class A>
struct fixed_length<A, std::void_t<decltype(A::SizeAtCompileTime)>> {
  static constexpr long long value = A::SizeAtCompileTime;
};

/// A fixed-size message array from a source array or vector of the same compile-time length.
template <class T, std::size_t N, class A>
void copy_array(T (&dst)[N], const A& src) {
  static_assert(fixed_length<A>::value == static_cast<long long>(N),
                "an array field needs a source of the same compile-time length");
  for (std::size_t i = 0; i < N; ++i) dst[i] = convert<T>(src[i]);
}

}  // namespace fill_support
}  // namespace reentry

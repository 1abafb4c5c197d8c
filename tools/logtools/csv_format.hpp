// Number formatting for the CSV writers: shortest text that round-trips.
#pragma once
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>

namespace reentry::logtools {

template <class T>
inline void csv_put(std::string& out, T value) {
  static_assert(std::is_arithmetic_v<T>, "CSV cells are numbers or strings");
  char buf[64];
  if constexpr (std::is_floating_point_v<T>) {
    if (std::isnan(value)) {
      out += "nan";
      return;
    }
    if (std::isinf(value)) {
      out += value > 0 ? "inf" : "-inf";
      return;
    }
    const auto r = std::to_chars(buf, buf + sizeof buf, value);
    out.append(buf, r.ptr);
  } else {
    // int8_t / uint8_t / bool are printed as integers, never as characters.
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<int64_t>(value));
    out.append(buf, r.ptr);
  }
}

inline void csv_put(std::string& out, const std::string& value) {
  out += '"';
  for (char c : value) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

}  // namespace reentry::logtools

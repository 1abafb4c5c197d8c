// Allocation-free LCM decode/encode helpers for the guidance process (DESIGN §11):
// decode raw buffers into preallocated messages, encode into a preallocated buffer.
// Header-only; depends only on the lcm-gen generated types (no LCM runtime calls).
#pragma once

#include <cstdint>

namespace reentry::transport {

/// Decode `len` bytes into `msg`. Returns true on success; on a malformed or foreign
/// message (decode < 0, or trailing bytes) increments `bad_messages` and returns false.
template <class Msg>
bool decode_into(Msg& msg, const void* data, int len, std::int32_t& bad_messages) {
  if (data == nullptr || len <= 0) {
    ++bad_messages;
    return false;
  }
  const int used = msg.decode(data, 0, len);
  if (used < 0 || used != len) {
    ++bad_messages;
    return false;
  }
  return true;
}

/// Encode `msg` into `buf` (capacity `cap`). Returns the byte count, or -1 if it does not fit.
template <class Msg>
int encode_into(const Msg& msg, std::uint8_t* buf, int cap) {
  const int size = msg.getEncodedSize();
  if (size > cap) return -1;
  return msg.encode(buf, 0, cap);
}

}  // namespace reentry::transport

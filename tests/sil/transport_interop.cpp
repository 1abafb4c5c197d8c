// Our UDP-multicast transport speaks LCM's udpm wire format (CTest sil.transport_interop,
// inside a private network namespace): a message we publish is received by liblcm (what
// lcm-spy and lcm-logger use), and one liblcm publishes is received by us, byte for byte.
#include <lcm/lcm-cpp.hpp>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "transport/monotonic_clock.hpp"
#include "transport/udpm.hpp"

namespace tr = reentry::transport;

struct Got {
  const std::vector<std::uint8_t>* payload = nullptr;
  bool ok = false;
  void on(const lcm::ReceiveBuffer* rb, const std::string& ch) {
    ok = ok || (ch == "INTEROP_A" && rb->data_size == payload->size() &&
                std::memcmp(rb->data, payload->data(), payload->size()) == 0);
  }
};

int main() {
  const std::string url_text = tr::default_udpm_url();
  tr::UdpmUrl url;
  std::string err;
  auto ours = std::make_unique<tr::UdpmSocket>();
  if (!tr::parse_udpm_url(url_text, url, err) || !ours->open(url, err)) {
    std::fprintf(stderr, "interop: %s\n", err.c_str());
    return 2;
  }
  lcm::LCM theirs(url_text);
  if (!theirs.good()) return 2;
  std::vector<std::uint8_t> payload(9000);
  for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<std::uint8_t>(i * 31 + 7);
  // 1. us -> liblcm
  Got got;
  got.payload = &payload;
  theirs.subscribe("INTEROP_A", &Got::on, &got);
  for (int i = 0; i < 20 && !got.ok; ++i) {
    ours->publish("INTEROP_A", payload.data(), static_cast<int>(payload.size()));
    theirs.handleTimeout(100);
  }
  std::printf("our datagram received by liblcm: %s\n", got.ok ? "yes, byte for byte" : "NO");
  // 2. liblcm -> us
  bool back = false;
  tr::Datagram d;
  for (int i = 0; i < 20 && !back; ++i) {
    theirs.publish("INTEROP_B", payload.data(), static_cast<unsigned>(payload.size()));
    const std::int64_t until = tr::mono_ns() + 100000000;
    while (!back && ours->receive(d, until - tr::mono_ns()) == 1) {
      back = std::strcmp(d.channel, "INTEROP_B") == 0 && d.payload_len == static_cast<int>(payload.size()) &&
             std::memcmp(d.payload, payload.data(), payload.size()) == 0;
    }
  }
  std::printf("liblcm's datagram received by us: %s; our receive buffer %d bytes\n", back ? "yes, byte for byte" : "NO",
              ours->recv_buffer_bytes());
  return got.ok && back ? 0 : 1;
}

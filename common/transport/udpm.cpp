#include "transport/udpm.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "transport/monotonic_clock.hpp"

namespace reentry::transport {
namespace {

std::uint32_t read_be32(const std::uint8_t* p) {
  return (static_cast<std::uint32_t>(p[0]) << 24) | (static_cast<std::uint32_t>(p[1]) << 16) |
         (static_cast<std::uint32_t>(p[2]) << 8) | static_cast<std::uint32_t>(p[3]);
}

void write_be32(std::uint8_t* p, std::uint32_t v) {
  p[0] = static_cast<std::uint8_t>(v >> 24);
  p[1] = static_cast<std::uint8_t>(v >> 16);
  p[2] = static_cast<std::uint8_t>(v >> 8);
  p[3] = static_cast<std::uint8_t>(v);
}

bool channel_byte_ok(std::uint8_t c) { return c >= 0x21 && c <= 0x7e; }

// Strict decimal integer in [lo, hi]; the whole string must be consumed.
bool parse_int(const std::string& s, long lo, long hi, long& out) {
  if (s.empty() || s.size() > 12) return false;
  long v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
  }
  if (v < lo || v > hi) return false;
  out = v;
  return true;
}

}  // namespace

const char* to_string(DatagramStatus s) {
  switch (s) {
    case DatagramStatus::kOk: return "ok";
    case DatagramStatus::kTooShort: return "too_short";
    case DatagramStatus::kBadMagic: return "bad_magic";
    case DatagramStatus::kFragment: return "fragment_refused";
    case DatagramStatus::kChannelUnterminated: return "channel_unterminated";
    case DatagramStatus::kChannelEmpty: return "channel_empty";
    case DatagramStatus::kChannelInvalid: return "channel_invalid";
    case DatagramStatus::kTruncated: return "truncated";
  }
  return "unknown";
}

bool parse_udpm_url(const std::string& url, UdpmUrl& out, std::string& error) {
  const std::string scheme = "udpm://";
  if (url.compare(0, scheme.size(), scheme) != 0) {
    error = "URL '" + url + "': only udpm:// is supported";
    return false;
  }
  std::string rest = url.substr(scheme.size());
  std::string query;
  const std::size_t q = rest.find('?');
  if (q != std::string::npos) {
    query = rest.substr(q + 1);
    rest = rest.substr(0, q);
  }
  UdpmUrl u;
  const std::size_t colon = rest.find(':');
  const std::string host = rest.substr(0, colon);
  in_addr addr{};
  if (host.empty() || inet_pton(AF_INET, host.c_str(), &addr) != 1) {
    error = "URL '" + url + "': '" + host + "' is not an IPv4 address";
    return false;
  }
  u.group = ntohl(addr.s_addr);
  if ((u.group >> 28) != 0xE) {
    error = "URL '" + url + "': " + host + " is not a multicast address (224.0.0.0/4)";
    return false;
  }
  long v = 7667;
  if (colon != std::string::npos && !parse_int(rest.substr(colon + 1), 1, 65535, v)) {
    error = "URL '" + url + "': port '" + rest.substr(colon + 1) + "' is not in [1, 65535]";
    return false;
  }
  u.port = static_cast<std::uint16_t>(v);
  std::size_t pos = 0;
  while (pos < query.size()) {
    std::size_t amp = query.find('&', pos);
    if (amp == std::string::npos) amp = query.size();
    const std::string kv = query.substr(pos, amp - pos);
    pos = amp + 1;
    if (kv.empty()) continue;
    const std::size_t eq = kv.find('=');
    const std::string key = kv.substr(0, eq);
    const std::string val = eq == std::string::npos ? "" : kv.substr(eq + 1);
    if (key == "ttl") {
      if (!parse_int(val, 0, 255, v)) {
        error = "URL '" + url + "': ttl '" + val + "' is not in [0, 255]";
        return false;
      }
      u.ttl = static_cast<int>(v);
    } else if (key == "recv_buf_size") {
      if (!parse_int(val, 4096, 1L << 30, v)) {
        error = "URL '" + url + "': recv_buf_size '" + val + "' is not in [4096, 2^30]";
        return false;
      }
      u.recv_buf_bytes = static_cast<int>(v);
    } else {
      error = "URL '" + url + "': unknown option '" + key + "' (ttl, recv_buf_size)";
      return false;
    }
  }
  out = u;
  return true;
}

std::string default_udpm_url() {
  const char* env = std::getenv("LCM_DEFAULT_URL");
  return env != nullptr && env[0] != '\0' ? std::string(env) : std::string("udpm://239.255.76.67:7667?ttl=0");
}

DatagramStatus parse_datagram(const std::uint8_t* buf, int len, Datagram& out) {
  if (buf == nullptr || len < 4) return DatagramStatus::kTooShort;
  const std::uint32_t magic = read_be32(buf);
  if (magic == kMagicFragment) return DatagramStatus::kFragment;
  if (magic != kMagicShort) return DatagramStatus::kBadMagic;
  if (len < 9) return DatagramStatus::kTooShort;  // header + at least the NUL of the channel
  const std::uint8_t* ch = buf + 8;
  const int room = len - 8;
  const int limit = room < kMaxChannelBytes + 1 ? room : kMaxChannelBytes + 1;
  int n = 0;
  while (n < limit && ch[n] != 0) {
    if (!channel_byte_ok(ch[n])) return DatagramStatus::kChannelInvalid;
    ++n;
  }
  if (n == limit) return DatagramStatus::kChannelUnterminated;
  if (n == 0) return DatagramStatus::kChannelEmpty;
  out.seqno = read_be32(buf + 4);
  out.channel = reinterpret_cast<const char*>(ch);
  out.channel_len = n;
  out.payload = ch + n + 1;
  out.payload_len = room - n - 1;
  return DatagramStatus::kOk;
}

int frame_datagram(std::uint32_t seqno, const char* channel, const void* payload, int payload_len,
                   std::uint8_t* out, int cap) {
  if (channel == nullptr || payload_len < 0 || (payload == nullptr && payload_len > 0)) return -1;
  int n = 0;
  while (n <= kMaxChannelBytes && channel[n] != '\0') {
    if (!channel_byte_ok(static_cast<std::uint8_t>(channel[n]))) return -1;
    ++n;
  }
  if (n == 0 || n > kMaxChannelBytes) return -1;
  const long total = 8L + n + 1 + payload_len;
  if (total > cap || total > kMaxDatagramBytes) return -1;
  write_be32(out, kMagicShort);
  write_be32(out + 4, seqno);
  std::memcpy(out + 8, channel, static_cast<std::size_t>(n));
  out[8 + n] = 0;
  if (payload_len > 0) std::memcpy(out + 9 + n, payload, static_cast<std::size_t>(payload_len));
  return static_cast<int>(total);
}

UdpmSocket::~UdpmSocket() {
  if (rx_fd_ >= 0) ::close(rx_fd_);
  if (tx_fd_ >= 0) ::close(tx_fd_);
}

bool UdpmSocket::open(const UdpmUrl& url, std::string& error) {
  if (good()) return true;
  auto fail = [&](const char* what) {
    error = std::string(what) + ": " + std::strerror(errno);
    if (rx_fd_ >= 0) ::close(rx_fd_);
    if (tx_fd_ >= 0) ::close(tx_fd_);
    rx_fd_ = tx_fd_ = -1;
    return false;
  };
  group_ = url.group;
  port_ = url.port;
  rx_fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (rx_fd_ < 0) return fail("receive socket");
  const int one = 1, zero = 0;
  if (::setsockopt(rx_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0) return fail("SO_REUSEADDR");
  // The receive buffer is the only queue between the network and us: as large as asked, past
  // net.core.rmem_max when we may (SO_RCVBUFFORCE needs CAP_NET_ADMIN, e.g. root in tools/sil).
  const int want = url.recv_buf_bytes;
  if (::setsockopt(rx_fd_, SOL_SOCKET, SO_RCVBUFFORCE, &want, sizeof want) != 0) {
    ::setsockopt(rx_fd_, SOL_SOCKET, SO_RCVBUF, &want, sizeof want);
  }
  int got = 0;
  socklen_t got_len = sizeof got;
  if (::getsockopt(rx_fd_, SOL_SOCKET, SO_RCVBUF, &got, &got_len) == 0) recv_buffer_bytes_ = got / 2;  // kernel doubles it
  ::setsockopt(rx_fd_, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);  // drop counter on each datagram
  ::setsockopt(rx_fd_, IPPROTO_IP, IP_MULTICAST_ALL, &zero, sizeof zero);  // only the group we joined
  sockaddr_in bind_addr{};
  bind_addr.sin_family = AF_INET;
  bind_addr.sin_port = htons(port_);
  bind_addr.sin_addr.s_addr = htonl(group_);  // the group, not INADDR_ANY: other traffic to the port stays out
  if (::bind(rx_fd_, reinterpret_cast<const sockaddr*>(&bind_addr), sizeof bind_addr) != 0) return fail("bind");
  ip_mreq mreq{};
  mreq.imr_multiaddr.s_addr = htonl(group_);
  mreq.imr_interface.s_addr = htonl(INADDR_ANY);
  if (::setsockopt(rx_fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &mreq, sizeof mreq) != 0) {
    return fail("IP_ADD_MEMBERSHIP (is there a multicast route? ip route add 224.0.0.0/4 dev lo)");
  }
  tx_fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (tx_fd_ < 0) return fail("send socket");
  const unsigned char ttl = static_cast<unsigned char>(url.ttl), loop = 1;
  if (::setsockopt(tx_fd_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) != 0) return fail("IP_MULTICAST_TTL");
  if (::setsockopt(tx_fd_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0) return fail("IP_MULTICAST_LOOP");
  return true;
}

bool UdpmSocket::publish(const char* channel, const void* data, int len) {
  if (!good()) return false;
  const int n = frame_datagram(seqno_, channel, data, len, tx_buf_, static_cast<int>(sizeof tx_buf_));
  if (n < 0) {
    ++publish_failures_;
    return false;
  }
  ++seqno_;
  sockaddr_in dest{};
  dest.sin_family = AF_INET;
  dest.sin_port = htons(port_);
  dest.sin_addr.s_addr = htonl(group_);
  for (int attempt = 0; attempt < 3; ++attempt) {
    const ssize_t sent = ::sendto(tx_fd_, tx_buf_, static_cast<std::size_t>(n), 0,
                                  reinterpret_cast<const sockaddr*>(&dest), sizeof dest);
    if (sent == n) return true;
    if (sent < 0 && errno != EINTR && errno != ENOBUFS && errno != EAGAIN) break;
  }
  ++publish_failures_;
  return false;
}

int UdpmSocket::receive(Datagram& out, std::int64_t timeout_ns) {
  if (!good()) return -1;
  const std::int64_t deadline = mono_ns() + (timeout_ns > 0 ? timeout_ns : 0);
  for (;;) {
    iovec iov{rx_buf_, sizeof rx_buf_};
    alignas(8) char control[CMSG_SPACE(sizeof(std::uint32_t))] = {};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(rx_fd_, &msg, MSG_DONTWAIT);
    if (n >= 0) {
      for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
          std::uint32_t drops = 0;
          std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
          counters_.kernel_drops = drops;  // cumulative since the socket was created
        }
      }
      DatagramStatus st = (msg.msg_flags & MSG_TRUNC) != 0 ? DatagramStatus::kTruncated
                                                           : parse_datagram(rx_buf_, static_cast<int>(n), out);
      if (st == DatagramStatus::kOk) {
        ++counters_.datagrams;
        return 1;
      }
      ++counters_.bad_datagrams;
      if (st == DatagramStatus::kFragment) ++counters_.fragments;
      continue;
    }
    if (errno == EINTR) continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK) return -1;
    const std::int64_t left = deadline - mono_ns();
    if (left <= 0) return 0;
    pollfd pfd{rx_fd_, POLLIN, 0};
    timespec ts{static_cast<time_t>(left / 1000000000LL), static_cast<long>(left % 1000000000LL)};
    const int r = ::ppoll(&pfd, 1, &ts, nullptr);
    if (r < 0 && errno != EINTR) return -1;
  }
}

}  // namespace reentry::transport

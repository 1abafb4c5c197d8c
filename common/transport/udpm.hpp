// Our own receive and send path for LCM's UDP-multicast transport (the wire format of liblcm's
// `udpm://` provider, so lcm-spy and lcm-logger still see our traffic), used by both processes
// instead of liblcm's networking.
//
// Why not liblcm: in LCM 1.3.1 one datagram can crash the receiving process (an LC03 fragment
// whose fragment_offset + size wraps past 2^32 is copied out of bounds by the receive thread;
// reentry_fsw and lcm-logger segfault on it), and its per-subscription queue drops messages
// when the handling thread is starved of CPU. Here every datagram is validated before any byte
// of it is used (parse_datagram, a pure function fuzzed in CTest), fragments are refused (every
// message of ours fits one datagram: the largest, plan_t, is 9.7 kB), nothing is queued in user
// space (the kernel socket buffer is the only queue, and its drops are counted through
// SO_RXQ_OVFL), and nothing allocates after open().
#pragma once

#include <cstdint>
#include <string>

namespace reentry::transport {

inline constexpr int kMaxChannelBytes = 63;            // LCM's channel-name limit
inline constexpr int kMaxDatagramBytes = 65507;        // IPv4 UDP payload limit
inline constexpr std::uint32_t kMagicShort = 0x4c433032;     // "LC02": one message in one datagram
inline constexpr std::uint32_t kMagicFragment = 0x4c433033;  // "LC03": a fragment of a larger message
inline constexpr int kDefaultRecvBufferBytes = 4 << 20;

/// An LCM UDP-multicast provider URL: udpm://A.B.C.D:PORT?ttl=N&recv_buf_size=BYTES.
struct UdpmUrl {
  std::uint32_t group = 0;   // host byte order, must be a multicast address (224.0.0.0/4)
  std::uint16_t port = 0;
  int ttl = 0;
  int recv_buf_bytes = kDefaultRecvBufferBytes;
};

/// Parses an udpm:// URL; on failure returns false and says which part is wrong.
bool parse_udpm_url(const std::string& url, UdpmUrl& out, std::string& error);

/// $LCM_DEFAULT_URL when set, else LCM's default udpm://239.255.76.67:7667?ttl=0.
std::string default_udpm_url();

enum class DatagramStatus : std::int8_t {
  kOk = 0,
  kTooShort,             // shorter than the 8-byte header plus a channel
  kBadMagic,             // neither LC02 nor LC03
  kFragment,             // LC03: refused (no message of ours needs fragmenting)
  kChannelUnterminated,  // no NUL within the datagram / within 64 bytes
  kChannelEmpty,
  kChannelInvalid,       // a byte outside printable ASCII (0x21-0x7e)
  kTruncated,            // the kernel reported a datagram longer than the receive buffer
};
const char* to_string(DatagramStatus s);

/// One validated short message; pointers into the caller's buffer.
struct Datagram {
  std::uint32_t seqno = 0;
  const char* channel = nullptr;  // NUL-terminated
  int channel_len = 0;
  const std::uint8_t* payload = nullptr;
  int payload_len = 0;            // may be 0: the decoder rejects it
};

/// Validates `len` bytes as one LCM short message. Reads nothing outside [buf, buf + len).
DatagramStatus parse_datagram(const std::uint8_t* buf, int len, Datagram& out);

/// Writes channel + payload as one LC02 datagram into `out`; returns its size, or -1 when the
/// channel is invalid or the datagram would not fit `cap` or one UDP datagram.
int frame_datagram(std::uint32_t seqno, const char* channel, const void* payload, int payload_len,
                   std::uint8_t* out, int cap);

struct RxCounters {
  std::int64_t datagrams = 0;      // valid datagrams delivered to the caller
  std::int64_t bad_datagrams = 0;  // refused by parse_datagram (fragments included)
  std::int64_t fragments = 0;      // of which LC03
  std::int64_t kernel_drops = 0;   // datagrams the kernel dropped for a full receive buffer
};

class UdpmSocket {
 public:
  UdpmSocket() = default;
  ~UdpmSocket();
  UdpmSocket(const UdpmSocket&) = delete;
  UdpmSocket& operator=(const UdpmSocket&) = delete;

  /// Start-up: receive socket bound to the group and port (shared with other processes),
  /// joined to the group, with the requested receive buffer; send socket with the TTL.
  bool open(const UdpmUrl& url, std::string& error);
  bool good() const { return rx_fd_ >= 0 && tx_fd_ >= 0; }

  /// Sends one message as one datagram. No allocation. False when it cannot be framed or sent.
  bool publish(const char* channel, const void* data, int len);

  /// Waits at most timeout_ns (0: do not wait) for the next valid datagram; malformed ones are
  /// counted and skipped. Returns 1 with `out` pointing into the socket's buffer (valid until
  /// the next call), 0 on time-out, -1 on a socket error.
  int receive(Datagram& out, std::int64_t timeout_ns);

  const RxCounters& counters() const { return counters_; }
  /// The receive buffer the kernel granted (bytes of payload it can hold, as SO_RCVBUF reports).
  int recv_buffer_bytes() const { return recv_buffer_bytes_; }
  std::int64_t publish_failures() const { return publish_failures_; }

 private:
  int rx_fd_ = -1;
  int tx_fd_ = -1;
  std::uint32_t group_ = 0;
  std::uint16_t port_ = 0;
  std::uint32_t seqno_ = 0;
  int recv_buffer_bytes_ = 0;
  std::int64_t publish_failures_ = 0;
  RxCounters counters_;
  alignas(8) std::uint8_t rx_buf_[65536] = {};
  alignas(8) std::uint8_t tx_buf_[65536] = {};
};

}  // namespace reentry::transport

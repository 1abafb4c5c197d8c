// The guidance process's receive path in process (GuidanceNode::on_datagram, no network):
// 1.2e5 malformed messages of every type on its channels, interleaved with a clean navigation
// stream, and a sample with implausible values in place of every 20th real one. The commands
// must be bit-identical to those of a node that saw only the clean stream, every malformed
// message must be counted in GUIDANCE_STATUS by what it is, the implausible samples answered
// with the held command and flagged, and nothing may end the run. (The wire fuzzer of
// tests/sil does the same to the running reentry_fsw over the network.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "app/guidance_node.hpp"
#include "junk_messages.hpp"
#include "transport/lcm_codec.hpp"

namespace {

using reentry::fsw::Phase;
using reentry::fsw::ReferenceProfile;
using reentry::fsw::RelativeState;
using reentry::fsw::Status;
using reentry::testing::JunkEffect;
using reentry::testing::JunkGenerator;
namespace exec = reentry::fsw::exec;
namespace app = reentry::fsw::app;

constexpr double kRe = 6378137.0;
constexpr double kMu = 3.986004418e14;

// Inertial -> Earth-relative without Earth rotation (enough for the adapter's windows).
Status convert(const reentry::nav_state_t& nav, RelativeState& s, void*) {
  const double* r = nav.position_I_m;
  const double* v = nav.velocity_I_mps;
  const double* a = nav.aero_accel_I_mps2;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(r[i]) || !std::isfinite(v[i]) || !std::isfinite(a[i])) return Status::kNonFinite;
  }
  const double rn = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  const double vn = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(rn > 0.0) || !(vn > 0.0)) return Status::kInvalidInput;
  s.t_s = nav.t_s;
  s.radius_m = rn;
  s.altitude_m = rn - kRe;
  s.velocity_mps = vn;
  s.flight_path_rad = std::asin((r[0] * v[0] + r[1] * v[1] + r[2] * v[2]) / (rn * vn));
  s.energy_Jpkg = 0.5 * vn * vn - kMu / rn + kMu / kRe;
  s.drag_mps2 = -(a[0] * v[0] + a[1] * v[1] + a[2] * v[2]) / vn;
  const double a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  s.lift_mps2 = std::sqrt(std::fmax(0.0, a2 - s.drag_mps2 * s.drag_mps2));
  return Status::kOk;
}

class Planner : public exec::PlanComputer {
 public:
  Status compute(const RelativeState& from, ReferenceProfile& out) override {
    out.n_points = 2;
    out.energy_Jpkg[0] = from.energy_Jpkg;
    out.sigma_rad[0] = 0.8 + 0.01 * std::sin(from.t_s);
    out.drag_mps2[0] = from.drag_mps2;
    out.status = Status::kOk;
    return Status::kOk;
  }
};

class Law : public exec::CommandLaw {
 public:
  ReferenceProfile p;
  void set_profile(const ReferenceProfile& profile) override { p = profile; }
  Status step(const RelativeState& s, double, bool has_profile, exec::LawOutput& out) override {
    out.alpha_rad = 0.7 + 1e-6 * s.altitude_m * 1e-3;
    out.sigma_rad = (has_profile ? p.sigma_rad[0] : 0.0) + 0.1 * std::sin(1e-4 * s.energy_Jpkg);
    out.phase = has_profile ? Phase::kTracking : Phase::kInitialDescent;
    return Status::kOk;
  }
};

struct Stack {
  Planner planner;
  Law law;
  std::unique_ptr<exec::Executive> executive = std::make_unique<exec::Executive>();
  std::unique_ptr<app::GuidanceNode> node;
  Stack() {
    exec::ExecConfig cfg;
    cfg.gnc_rate_hz = 10.0;
    cfg.plan_latency_ticks = 3;
    cfg.replan_period_s = 20.0;
    cfg.mode = exec::PlanMode::kSynchronous;
    EXPECT_EQ(executive->init(cfg, planner, law), Status::kOk);
    node = std::make_unique<app::GuidanceNode>(*executive, &convert, nullptr, 10.0);
    node->attach(nullptr, app::RunMode::kLockstep);
  }
};

// A descending, decelerating entry: inside every plausibility window.
reentry::nav_state_t nav_at(std::int64_t k) {
  reentry::nav_state_t n{};
  const double t = 0.1 * static_cast<double>(k);
  n.utime = std::llround(t * 1e6);
  n.tick = k;
  n.t_s = t;
  const double h = 80000.0 - 40.0 * t, v = 7000.0 - 5.0 * t, ang = v * t / (kRe + h);
  n.position_I_m[0] = (kRe + h) * std::cos(ang);
  n.position_I_m[1] = (kRe + h) * std::sin(ang);
  n.velocity_I_mps[0] = -v * std::sin(ang);
  n.velocity_I_mps[1] = v * std::cos(ang);
  n.velocity_I_mps[2] = -40.0;
  for (int i = 0; i < 3; ++i) n.aero_accel_I_mps2[i] = -5.0 * n.velocity_I_mps[i] / v;
  n.earth_rotation_angle_rad = 0.0;
  return n;
}

bool same_cmd(const reentry::guidance_cmd_t& a, const reentry::guidance_cmd_t& b) {
  return std::memcmp(&a.alpha_rad, &b.alpha_rad, sizeof(double)) == 0 &&
         std::memcmp(&a.sigma_rad, &b.sigma_rad, sizeof(double)) == 0 && a.mode == b.mode && a.plan_seq == b.plan_seq &&
         a.tick == b.tick;
}

TEST(GuidanceNodeFuzz, MalformedMessagesOfEveryTypeAreCountedAndChangeNothing) {
  Stack clean, fuzzed;
  JunkGenerator junk(20261203);
  const int ticks = 2000, junk_per_tick = 60;
  std::int64_t undecodable = 0, duplicates = 0, bad_ticks = 0, bad_controls = 0, held = 0, sent = 0;
  for (std::int64_t k = 0; k < ticks; ++k) {
    const reentry::nav_state_t nav = nav_at(k);
    const auto bytes = reentry::testing::encoded(nav);
    clean.node->on_datagram("NAV_STATE", bytes.data(), static_cast<int>(bytes.size()));
    if (k % 20 == 10) {
      // Implausible values in place of the real sample: the held command answers, flagged.
      const reentry::guidance_cmd_t before = fuzzed.node->last_cmd();
      const auto bad = junk.bad_values(nav);
      fuzzed.node->on_datagram("NAV_STATE", bad.data(), static_cast<int>(bad.size()));
      const reentry::guidance_cmd_t& h = fuzzed.node->last_cmd();
      ASSERT_EQ(h.tick, k);
      ASSERT_EQ(std::memcmp(&h.alpha_rad, &before.alpha_rad, sizeof(double)), 0) << "tick " << k;
      ASSERT_EQ(std::memcmp(&h.sigma_rad, &before.sigma_rad, sizeof(double)), 0) << "tick " << k;
      ASSERT_NE(h.health_flags & exec::kHealthNavInvalid, 0) << "tick " << k;
      ++held;
    }
    fuzzed.node->on_datagram("NAV_STATE", bytes.data(), static_cast<int>(bytes.size()));
    ASSERT_TRUE(same_cmd(clean.node->last_cmd(), fuzzed.node->last_cmd())) << "tick " << k;
    ASSERT_EQ(fuzzed.node->last_cmd().health_flags & exec::kHealthNavInvalid, 0) << "tick " << k;
    for (int j = 0; j < junk_per_tick; ++j) {
      const reentry::testing::Junk m = junk.next(nav);
      fuzzed.node->on_datagram(m.channel, m.bytes.data(), static_cast<int>(m.bytes.size()));
      ++sent;
      switch (m.effect) {
        case JunkEffect::kUndecodable: ++undecodable; break;
        case JunkEffect::kDuplicate: ++duplicates; break;
        case JunkEffect::kBadTick: ++bad_ticks; break;
        case JunkEffect::kBadControl: ++bad_controls; break;
      }
      ASSERT_FALSE(fuzzed.node->end_of_run()) << m.kind << " ended the run at tick " << k;
    }
    // Duplicates of the accepted tick are answered again with the same command.
    ASSERT_TRUE(same_cmd(clean.node->last_cmd(), fuzzed.node->last_cmd())) << "tick " << k;
  }
  const exec::ExecCounters& c = fuzzed.executive->counters();
  EXPECT_GE(sent, 100000);
  EXPECT_EQ(fuzzed.node->bad_messages(), undecodable + bad_controls);
  EXPECT_EQ(c.duplicate_ticks, duplicates);
  EXPECT_EQ(c.nav_rejected_tick, bad_ticks);
  EXPECT_EQ(c.nav_rejected_values, held);
  EXPECT_EQ(c.invalid_nav, bad_ticks + held);
  EXPECT_EQ(c.skipped_ticks, 0);
  // GUIDANCE_STATUS of the next cycle counts every one of them.
  const auto last = reentry::testing::encoded(nav_at(ticks));
  fuzzed.node->on_datagram("NAV_STATE", last.data(), static_cast<int>(last.size()));
  const reentry::guidance_status_t& st = fuzzed.node->last_status();
  EXPECT_EQ(st.tick, ticks);
  EXPECT_EQ(st.bad_messages, undecodable + bad_controls);
  EXPECT_EQ(st.invalid_nav, bad_ticks + held);
  EXPECT_EQ(st.nav_rejected_tick, bad_ticks);
  EXPECT_EQ(st.duplicate_ticks, duplicates);
  EXPECT_EQ(clean.executive->counters().invalid_nav, 0);
  EXPECT_EQ(clean.node->bad_messages(), 0);
  std::printf("fuzzed the receive path with %lld messages: %lld undecodable, %lld duplicates, %lld bad ticks, "
              "%lld bad controls, %lld implausible samples held; commands identical over %d ticks\n",
              static_cast<long long>(sent), static_cast<long long>(undecodable), static_cast<long long>(duplicates),
              static_cast<long long>(bad_ticks), static_cast<long long>(bad_controls), static_cast<long long>(held),
              ticks);
  clean.executive->shutdown();
  fuzzed.executive->shutdown();
}

}  // namespace

// Protects a frame's tally of the returns on objects (io/run/flight_summary.hpp), what truth.csv's
// returns and summary.json's objects come from: read from the engine's object_returns bits or from
// the returns themselves, the hits are the same, in pulse order, and equal a plain recount — over
// random returns whose entries past a pulse's count hold stale indices, and returns behind fog.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <tuple>
#include <vector>

#include "io/run/flight_summary.hpp"

namespace owsim {
namespace {

constexpr std::size_t kNamed = 40;  // objects 0..39; 40 the terrain, 41.. fog volumes

struct RandomFrame {
  std::vector<Pulse> pulses;
  std::vector<PulseReturns> returns;
  std::vector<std::uint8_t> bits;              // computed here, as a recount
  std::vector<FrameTally::ObjectHit> recount;  // every valid return on an object, in order
};

RandomFrame random_frame(std::uint64_t seed, std::size_t pulses, double object_share) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<std::uint32_t> named(0, kNamed - 1);
  std::uniform_int_distribution<std::uint32_t> other(kNamed, kNamed + 3);
  RandomFrame out;
  for (std::size_t k = 0; k < pulses; ++k) {
    Pulse pulse;
    pulse.time_s = 0.001 * static_cast<double>(k);
    out.pulses.push_back(pulse);
    PulseReturns returns;
    returns.count = static_cast<int>(unit(rng) * 3.0);
    std::uint8_t bits = 0;
    for (int r = 0; r < 2; ++r) {  // entries past the count hold stale values all the same
      Return& ret = returns.returns[r];
      ret.object_index = unit(rng) < object_share ? named(rng) : other(rng);
      ret.true_range_m = 100.0 + unit(rng) * 900.0;
      ret.surface =
          static_cast<std::uint8_t>(unit(rng) < 0.2 ? SurfaceClass::fog : SurfaceClass::ground);
      if (unit(rng) < 0.1) {  // a false return (SENSOR-SPEC §11): no object
        ret.object_index = kNoObject;
        ret.surface = static_cast<std::uint8_t>(SurfaceClass::noise);
      }
    }
    for (int r = 0; r < returns.count; ++r) {
      const Return& ret = returns.returns[r];
      if (ret.object_index >= kNamed) continue;
      bits |= static_cast<std::uint8_t>(1u << r);
      const bool behind_fog =
          r == 1 && returns.returns[0].surface == static_cast<std::uint8_t>(SurfaceClass::fog);
      out.recount.push_back(
          {ret.object_index, behind_fog ? 1u : 0u, pulse.time_s, ret.true_range_m});
    }
    out.returns.push_back(returns);
    out.bits.push_back(bits);
  }
  return out;
}

auto as_tuples(const std::vector<FrameTally::ObjectHit>& hits) {
  std::vector<std::tuple<std::uint32_t, std::uint32_t, double, double>> out;
  for (const auto& h : hits) out.emplace_back(h.object, h.through_fog, h.time_s, h.true_range_m);
  return out;
}

TEST(FrameTally, ObjectHitsFromTheBitsFromTheReturnsAndARecountAgree) {
  // Sparse hits (as on real flights), dense ones, and lengths that are not multiples of eight.
  for (const auto& [seed, pulses, share] :
       {std::tuple{1u, 20352u, 0.03}, std::tuple{2u, 1021u, 0.6}, std::tuple{3u, 7u, 0.9}}) {
    const RandomFrame frame = random_frame(seed, pulses, share);
    for (std::size_t k = 0; k < frame.returns.size(); ++k) {
      ASSERT_EQ(object_return_bits(frame.returns[k], kNamed), frame.bits[k]) << k;
    }
    FrameTally from_bits, from_returns, summary;
    FlightSummary::tally(kNamed, frame.pulses, frame.returns, from_bits, TallyScope::object_hits,
                         frame.bits);
    FlightSummary::tally(kNamed, frame.pulses, frame.returns, from_returns,
                         TallyScope::object_hits);
    FlightSummary::tally(kNamed, frame.pulses, frame.returns, summary, TallyScope::summary);
    EXPECT_EQ(as_tuples(from_bits.object_hits), as_tuples(frame.recount)) << seed;
    EXPECT_EQ(as_tuples(from_returns.object_hits), as_tuples(frame.recount)) << seed;
    EXPECT_EQ(as_tuples(summary.object_hits), as_tuples(frame.recount)) << seed;
    EXPECT_GT(frame.recount.size(), pulses / 100) << seed;  // something to compare
  }
}

TEST(FrameTally, FalseReturnsAreNoObjectsAndCountAsNoise) {
  // Pulse 0: a false return, then wire 3; pulse 1: wire 5, then a false return; pulse 2: two false
  // returns. Object kNoObject is past every named object: bits and hits hold the wires alone.
  Return noise;
  noise.object_index = kNoObject;
  noise.surface = static_cast<std::uint8_t>(SurfaceClass::noise);
  Return wire3, wire5;
  wire3.object_index = 3;
  wire3.true_range_m = 250.0;
  wire5.object_index = 5;
  wire5.true_range_m = 310.0;
  std::vector<PulseReturns> returns(3);
  returns[0] = {2, 0, 0, {noise, wire3}};
  returns[1] = {2, 0, 0, {wire5, noise}};
  returns[2] = {2, 0, 0, {noise, noise}};
  EXPECT_EQ(object_return_bits(returns[0], kNamed), 2);
  EXPECT_EQ(object_return_bits(returns[1], kNamed), 1);
  EXPECT_EQ(object_return_bits(returns[2], kNamed), 0);
  std::vector<Pulse> pulses(3);
  FrameTally tally;
  FlightSummary::tally(kNamed, pulses, returns, tally);
  EXPECT_EQ(tally.returns_by_class[static_cast<std::size_t>(SurfaceClass::noise)], 4u);
  EXPECT_EQ(tally.returns_by_class[static_cast<std::size_t>(SurfaceClass::wire)], 2u);
  ASSERT_EQ(tally.object_hits.size(), 2u);
  EXPECT_EQ(tally.object_hits[0].object, 3u);
  EXPECT_EQ(tally.object_hits[0].through_fog, 0u);  // behind a false return, not fog: clear
  EXPECT_EQ(tally.object_hits[1].object, 5u);
  // truth.csv's tally (io/run/frame_encoder.cpp): the same hits from the returns and the bits.
  const std::vector<std::uint8_t> bits = {2, 1, 0};
  FrameTally from_returns, from_bits;
  FlightSummary::tally(kNamed, pulses, returns, from_returns, TallyScope::object_hits);
  FlightSummary::tally(kNamed, pulses, returns, from_bits, TallyScope::object_hits, bits);
  EXPECT_EQ(as_tuples(from_returns.object_hits), as_tuples(tally.object_hits));
  EXPECT_EQ(as_tuples(from_bits.object_hits), as_tuples(tally.object_hits));
}

TEST(FrameTally, BitsOfAnotherLengthAreNotTrusted) {
  const RandomFrame frame = random_frame(4, 64, 0.5);
  const std::vector<std::uint8_t> none(10, 0);  // not one a pulse: the returns are read instead
  FrameTally tally;
  FlightSummary::tally(kNamed, frame.pulses, frame.returns, tally, TallyScope::object_hits, none);
  EXPECT_EQ(as_tuples(tally.object_hits), as_tuples(frame.recount));
}

}  // namespace
}  // namespace owsim

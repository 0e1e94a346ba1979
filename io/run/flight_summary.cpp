#include "io/run/flight_summary.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>
#include <utility>

#include "geometry/error.hpp"

namespace owsim {

FlightSummaryCheckpoint FlightSummary::checkpoint() const {
  FlightSummaryCheckpoint out{counts_, objects_.size(), {}};
  out.seen.reserve(first_seen_order_.size());
  for (const std::uint32_t index : first_seen_order_) out.seen.push_back({index, objects_[index]});
  return out;
}

void FlightSummary::restore(const FlightSummaryCheckpoint& from) {
  if (from.object_count != objects_.size()) {
    throw Error("summary: cannot resume: the checkpoint tallies " +
                std::to_string(from.object_count) + " objects, this run " +
                std::to_string(objects_.size()));
  }
  std::vector<ObjectTruth> objects(objects_.size());
  std::vector<std::uint32_t> order;
  order.reserve(from.seen.size());
  for (const SeenObject& seen : from.seen) {
    if (seen.index >= objects.size() || !seen.truth.seen() || objects[seen.index].seen()) {
      throw Error("summary: cannot resume: object " + std::to_string(seen.index) +
                  " is out of range, unseen or given twice");
    }
    objects[seen.index] = seen.truth;
    order.push_back(seen.index);
  }
  counts_ = from.counts;
  objects_ = std::move(objects);
  first_seen_order_ = std::move(order);
}

void FlightSummary::tally(std::size_t object_count, std::span<const Pulse> pulses,
                          std::span<const PulseReturns> returns, FrameTally& out,
                          TallyScope scope, std::span<const std::uint8_t> object_returns) {
  out.pulses = pulses.size();
  out.returns_by_class.fill(0);
  out.second_returns = 0;
  out.object_hits.clear();
  const auto add_object_hit = [&](std::size_t k, int r) {
    const PulseReturns& pulse_returns = returns[k];
    const Return& ret = pulse_returns.returns[r];
    const bool through_fog =
        r == 1 && pulse_returns.returns[0].surface == static_cast<std::uint8_t>(SurfaceClass::fog);
    out.object_hits.push_back(
        {ret.object_index, through_fog ? 1u : 0u, pulses[k].time_s, ret.true_range_m});
  };
  const auto add_object_hits = [&](std::size_t k, unsigned bits) {
    if ((bits & 1u) != 0) add_object_hit(k, 0);
    if ((bits & 2u) != 0) add_object_hit(k, 1);
  };
  if (scope == TallyScope::object_hits && object_returns.size() == returns.size()) {
    // Eight pulses' bits at a time: most pulses (the ground's, no return) have none.
    const std::size_t count = object_returns.size();
    std::size_t k = 0;
    for (; k + 8 <= count; k += 8) {
      std::uint64_t word = 0;
      std::memcpy(&word, object_returns.data() + k, sizeof word);
      while (word != 0) {
        const auto byte = static_cast<std::size_t>(std::countr_zero(word)) / 8;
        add_object_hits(k + byte, object_returns[k + byte]);
        word &= ~(std::uint64_t{0xFF} << (8 * byte));
      }
    }
    for (; k < count; ++k) add_object_hits(k, object_returns[k]);
    return;
  }
  if (scope == TallyScope::object_hits) {
    // Without a branch on a pulse's return count (unpredictable) until a return on an object
    // (rare).
    for (std::size_t k = 0; k < returns.size(); ++k) {
      const unsigned bits = object_return_bits(returns[k], object_count);
      if (bits != 0) [[unlikely]] add_object_hits(k, bits);
    }
    return;
  }
  for (std::size_t k = 0; k < returns.size(); ++k) {
    const PulseReturns& pulse_returns = returns[k];
    if (pulse_returns.count >= 2) ++out.second_returns;
    for (int r = 0; r < pulse_returns.count; ++r) {
      const Return& ret = pulse_returns.returns[r];
      ++out.returns_by_class[std::min<std::size_t>(ret.surface, kSurfaceClassCount - 1)];
      if (ret.object_index < object_count) add_object_hit(k, r);  // else the terrain, fog
    }
  }
}

void FlightSummary::add_frame(std::int64_t frame, const FrameTally& tally) {
  ++counts_.frames;
  counts_.pulses += tally.pulses;
  counts_.second_returns += tally.second_returns;
  for (std::size_t c = 0; c < tally.returns_by_class.size(); ++c) {
    counts_.returns_by_class[c] += tally.returns_by_class[c];
  }
  if (objects_.empty()) return;  // no summary.json: the hits were tallied for truth.csv alone
  for (const FrameTally::ObjectHit& hit : tally.object_hits) {
    if (hit.object >= objects_.size()) {
      throw Error("summary: a return on object " + std::to_string(hit.object) + " of " +
                  std::to_string(objects_.size()));
    }
    ObjectTruth& truth = objects_[hit.object];
    if (!truth.seen()) {
      first_seen_order_.push_back(hit.object);
      truth.first_seen_s = hit.time_s;
      truth.first_seen_range_m = hit.true_range_m;
      truth.min_range_m = hit.true_range_m;
    }
    if (hit.through_fog != 0) {
      ++truth.seen_through_fog;
    } else if (!truth.seen_clear()) {
      truth.first_seen_clear_s = hit.time_s;
      truth.first_seen_clear_range_m = hit.true_range_m;
    }
    ++truth.returns;
    if (truth.last_frame_seen != frame) {
      ++truth.frames_seen;
      truth.last_frame_seen = frame;
    }
    truth.min_range_m = std::min(truth.min_range_m, hit.true_range_m);
  }
}

}  // namespace owsim

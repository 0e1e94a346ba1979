#pragma once
// summary.json of `owsim run` (INTERFACE.md): totals of the flight and, per scenario object (each
// conductor on its own), when and from how far the sensor first saw it — the ground truth that
// obstacle-detection software is scored against. Fed one frame at a time, in frame order;
// checkpoint() and restore() carry the totals across an interrupted run (`owsim run --resume`).
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometry/scene.hpp"
#include "sensor/receiver.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

struct ObjectTruth {
  std::string id;
  SurfaceClass surface = SurfaceClass::wire;
  std::uint64_t returns = 0;
  std::uint64_t frames_seen = 0;
  std::optional<double> first_seen_s;
  std::optional<double> first_seen_range_m;  // the true range of the first return on it
  std::optional<double> min_range_m;
  std::int64_t last_frame_seen = -1;
  friend bool operator==(const ObjectTruth&, const ObjectTruth&) = default;
};

// The flight's totals, by SurfaceClass for the returns.
struct FlightCounts {
  std::uint64_t frames = 0;
  std::uint64_t pulses = 0;
  std::array<std::uint64_t, 4> returns_by_class{};
  std::uint64_t second_returns = 0;
  friend bool operator==(const FlightCounts&, const FlightCounts&) = default;
};

// Everything a FlightSummary has accumulated.
struct FlightSummaryCheckpoint {
  FlightCounts counts;
  std::vector<ObjectTruth> objects;
  friend bool operator==(const FlightSummaryCheckpoint&, const FlightSummaryCheckpoint&) = default;
};

// One frame's part of the summary, tallied on any thread (FlightSummary::tally) so that adding it
// in frame order is a few additions. Reused frame after frame.
struct FrameTally {
  // A return on a scene object (not the ground), in pulse order.
  struct ObjectHit {
    std::uint32_t object = 0;
    double time_s = 0.0;  // the pulse's
    double true_range_m = 0.0;
  };
  std::uint64_t pulses = 0;
  std::array<std::uint64_t, 4> returns_by_class{};
  std::uint64_t second_returns = 0;
  std::vector<ObjectHit> object_hits;

  // Adds the tally of the pulses that follow this one's: counts summed, object hits after ours.
  void append(const FrameTally& later) {
    pulses += later.pulses;
    for (std::size_t c = 0; c < returns_by_class.size(); ++c) {
      returns_by_class[c] += later.returns_by_class[c];
    }
    second_returns += later.second_returns;
    object_hits.insert(object_hits.end(), later.object_hits.begin(), later.object_hits.end());
  }
};

class FlightSummary {
 public:
  // One entry per scene object, in object-index order (conductors, then cylinders).
  explicit FlightSummary(const Scene& scene);

  // One frame's returns tallied, for a scene of `object_count` objects (returns on an index at
  // or past it are the ground's); any thread.
  static void tally(std::size_t object_count, std::span<const Pulse> pulses,
                    std::span<const PulseReturns> returns, FrameTally& out);
  // Adds one frame's tally (frames must come in order).
  void add_frame(std::int64_t frame, const FrameTally& tally);

  [[nodiscard]] const std::vector<ObjectTruth>& objects() const { return objects_; }
  [[nodiscard]] std::uint64_t frames() const { return counts_.frames; }
  [[nodiscard]] std::uint64_t pulses() const { return counts_.pulses; }
  [[nodiscard]] std::uint64_t returns_of(SurfaceClass surface) const {
    return counts_.returns_by_class[static_cast<std::size_t>(surface)];
  }
  [[nodiscard]] std::uint64_t second_returns() const { return counts_.second_returns; }

  [[nodiscard]] FlightSummaryCheckpoint checkpoint() const { return {counts_, objects_}; }
  // Continues from the state of a summary of the same scene. Throws owsim::Error if the objects'
  // ids or classes differ from this scene's.
  void restore(FlightSummaryCheckpoint from);

  // Everything of INTERFACE.md's summary.json that the frames determine; the caller adds run
  // facts (scenario, seed, wall time, threads, version).
  [[nodiscard]] nlohmann::json to_json() const;

 private:
  std::vector<ObjectTruth> objects_;
  FlightCounts counts_;
};

}  // namespace owsim

#pragma once
// What summary.json of `owsim run` reports (INTERFACE.md; written by io/run/summary_json.hpp):
// totals of the flight and, per scenario object (each conductor on its own), when and from how far
// the sensor first saw it — the ground truth that obstacle-detection software is scored against.
// Fed one frame at a time, in frame order; checkpoint() and restore() carry the totals across an
// interrupted run (`owsim run --resume`).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/scene.hpp"
#include "sensor/receiver.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim {

// What the frames so far showed of one scene object: plain numbers, 72 bytes an object, so a
// forest of a million trees costs 72 MB here and nothing else per object. Its id and class are the
// scene's (object_ids(), summary_json.hpp). The ranges and first time mean something only once
// seen() (they are 0 before); the clear ones once seen_clear().
struct ObjectTruth {
  std::uint64_t returns = 0;
  std::uint64_t frames_seen = 0;
  double first_seen_s = 0.0;
  double first_seen_range_m = 0.0;  // the true range of the first return on it
  double min_range_m = 0.0;
  std::int64_t last_frame_seen = -1;
  // Returns that were a second return behind a fog return (SENSOR-SPEC §10 "seen through"), and
  // the first return on the object that was not.
  std::uint64_t seen_through_fog = 0;
  double first_seen_clear_s = 0.0;
  double first_seen_clear_range_m = 0.0;
  [[nodiscard]] bool seen() const { return returns > 0; }
  [[nodiscard]] bool seen_clear() const { return returns > seen_through_fog; }
  friend bool operator==(const ObjectTruth&, const ObjectTruth&) = default;
};

// The flight's totals, by SurfaceClass for the returns.
struct FlightCounts {
  std::uint64_t frames = 0;
  std::uint64_t pulses = 0;
  std::array<std::uint64_t, kSurfaceClassCount> returns_by_class{};
  std::uint64_t second_returns = 0;
  friend bool operator==(const FlightCounts&, const FlightCounts&) = default;
};

// An object with returns, by its object index.
struct SeenObject {
  std::uint32_t index = 0;
  ObjectTruth truth;
  friend bool operator==(const SeenObject&, const SeenObject&) = default;
};

// Everything a FlightSummary has accumulated: the totals, how many objects it tallies, and the
// objects seen so far in the order they were first seen — never the unseen ones, so a checkpoint
// costs nothing for the trees the flight never came near.
struct FlightSummaryCheckpoint {
  FlightCounts counts;
  std::uint64_t object_count = 0;
  std::vector<SeenObject> seen;
  friend bool operator==(const FlightSummaryCheckpoint&, const FlightSummaryCheckpoint&) = default;
};

// One frame's part of the summary, tallied on any thread (FlightSummary::tally) so that adding it
// in frame order is a few additions. Reused frame after frame.
struct FrameTally {
  // A return on a scene object (not the ground), in pulse order.
  struct ObjectHit {
    std::uint32_t object = 0;
    std::uint32_t through_fog = 0;  // 1: a second return behind a fog return
    double time_s = 0.0;            // the pulse's
    double true_range_m = 0.0;
  };
  std::uint64_t pulses = 0;
  std::array<std::uint64_t, kSurfaceClassCount> returns_by_class{};
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

// What a frame's tally counts: all summary.json reports, or the returns on objects alone (all
// truth.csv needs; the class and second-return counts are then left at zero).
enum class TallyScope { summary, object_hits };

class FlightSummary {
 public:
  // Tallies `object_count` objects (the scene's conductors, then cylinders, in object-index
  // order); 0 when summary.json is not written, so no per-object state is kept at all.
  explicit FlightSummary(std::size_t object_count) : objects_(object_count) {}

  // One frame's returns tallied, for a scene of `object_count` objects (returns on an index at
  // or past it are the ground's); any thread. `object_returns`, when given (one entry a pulse,
  // FrameView::object_returns), lets the object_hits scope visit only the pulses with a return on
  // an object instead of reading every pulse's returns; the tally is the same.
  static void tally(std::size_t object_count, std::span<const Pulse> pulses,
                    std::span<const PulseReturns> returns, FrameTally& out,
                    TallyScope scope = TallyScope::summary,
                    std::span<const std::uint8_t> object_returns = {});
  // Adds one frame's tally (frames must come in order). Throws owsim::Error for a hit on an
  // object index this summary does not tally; a summary of no objects takes the counts alone.
  void add_frame(std::int64_t frame, const FrameTally& tally);

  [[nodiscard]] std::span<const ObjectTruth> objects() const { return objects_; }
  [[nodiscard]] std::uint64_t frames() const { return counts_.frames; }
  [[nodiscard]] std::uint64_t pulses() const { return counts_.pulses; }
  [[nodiscard]] std::uint64_t returns_of(SurfaceClass surface) const {
    return counts_.returns_by_class[static_cast<std::size_t>(surface)];
  }
  [[nodiscard]] std::uint64_t second_returns() const { return counts_.second_returns; }

  // Costs the objects seen so far, not the objects tallied.
  [[nodiscard]] FlightSummaryCheckpoint checkpoint() const;
  // Continues from the state of a summary of the same scene and outputs. Throws owsim::Error if
  // it tallied another number of objects, or names an object twice or out of range.
  void restore(const FlightSummaryCheckpoint& from);

 private:
  std::vector<ObjectTruth> objects_;
  std::vector<std::uint32_t> first_seen_order_;  // the indices of the seen objects
  FlightCounts counts_;
};

}  // namespace owsim

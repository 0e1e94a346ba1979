#include "io/run/flight_summary.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "geometry/error.hpp"

namespace owsim {
namespace {

nlohmann::json optional_number(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

}  // namespace

FlightSummary::FlightSummary(const Scene& scene) {
  objects_.reserve(scene.conductors.size() + scene.cylinders.size());
  for (const Conductor& conductor : scene.conductors) {
    ObjectTruth& truth = objects_.emplace_back();
    truth.id = conductor.id;
    truth.surface = SurfaceClass::wire;
  }
  for (const Cylinder& cylinder : scene.cylinders) {
    ObjectTruth& truth = objects_.emplace_back();
    truth.id = cylinder.id;
    truth.surface = cylinder.surface;
  }
}

void FlightSummary::restore(FlightSummaryCheckpoint from) {
  bool same_objects = from.objects.size() == objects_.size();
  for (std::size_t i = 0; same_objects && i < objects_.size(); ++i) {
    same_objects =
        from.objects[i].id == objects_[i].id && from.objects[i].surface == objects_[i].surface;
  }
  if (!same_objects) {
    throw Error("summary: cannot resume: the checkpoint's " + std::to_string(from.objects.size()) +
                " objects are not the scene's " + std::to_string(objects_.size()));
  }
  counts_ = from.counts;
  objects_ = std::move(from.objects);
}

void FlightSummary::tally(std::size_t object_count, std::span<const Pulse> pulses,
                          std::span<const PulseReturns> returns, FrameTally& out) {
  out.pulses = pulses.size();
  out.returns_by_class.fill(0);
  out.second_returns = 0;
  out.object_hits.clear();
  for (std::size_t k = 0; k < returns.size(); ++k) {
    const PulseReturns& pulse_returns = returns[k];
    if (pulse_returns.count >= 2) ++out.second_returns;
    for (int r = 0; r < pulse_returns.count; ++r) {
      const Return& ret = pulse_returns.returns[r];
      ++out.returns_by_class[std::min<std::size_t>(ret.surface, 3)];
      if (ret.object_index >= object_count) continue;  // the ground
      out.object_hits.push_back({ret.object_index, pulses[k].time_s, ret.true_range_m});
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
  for (const FrameTally::ObjectHit& hit : tally.object_hits) {
    ObjectTruth& truth = objects_[hit.object];
    ++truth.returns;
    if (truth.last_frame_seen != frame) {
      ++truth.frames_seen;
      truth.last_frame_seen = frame;
    }
    if (!truth.first_seen_s) {
      truth.first_seen_s = hit.time_s;
      truth.first_seen_range_m = hit.true_range_m;
    }
    truth.min_range_m = std::min(truth.min_range_m.value_or(hit.true_range_m), hit.true_range_m);
  }
}

nlohmann::json FlightSummary::to_json() const {
  nlohmann::json objects = nlohmann::json::array();
  for (const ObjectTruth& truth : objects_) {
    objects.push_back({{"id", truth.id},
                       {"class", std::string(to_string(truth.surface))},
                       {"returns", truth.returns},
                       {"frames_seen", truth.frames_seen},
                       {"first_seen_s", optional_number(truth.first_seen_s)},
                       {"first_seen_range_m", optional_number(truth.first_seen_range_m)},
                       {"min_range_m", optional_number(truth.min_range_m)}});
  }
  return {{"frames", counts_.frames},
          {"pulses", counts_.pulses},
          {"returns",
           {{"wire", returns_of(SurfaceClass::wire)},
            {"pole", returns_of(SurfaceClass::pole)},
            {"tree", returns_of(SurfaceClass::tree)},
            {"ground", returns_of(SurfaceClass::ground)}}},
          {"second_returns", counts_.second_returns},
          {"objects", objects}};
}

}  // namespace owsim

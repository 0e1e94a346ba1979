#pragma once
// The reference tracer — the source's own method (ch. 7, ch. 11): every ray against every wire
// segment, every cylinder and every terrain triangle, no acceleration structure. It applies the
// same per-surface rules (sensor/pulse_candidates.hpp) as the Embree tracer, so the two must agree
// pulse for pulse; tests hold them to that, and benchmarks measure what the BVH buys.
#include <cstdint>
#include <span>
#include <utility>

#include "geometry/scene.hpp"
#include "geometry/terrain.hpp"
#include "sensor/pulse_candidates.hpp"
#include "sensor/receiver.hpp"

namespace owsim {

class BruteForceTracer {
 public:
  // `terrain_mesh` is the surface the Embree scene traces (EmbreeScene::terrain_mesh()).
  BruteForceTracer(const Scene& scene, TriangleMesh terrain_mesh, const ReceiverParams& receiver)
      : scene_(&scene), terrain_mesh_(std::move(terrain_mesh)), receiver_(receiver) {}

  // One pulse: fills `out` (cleared first).
  void trace(const PulseRay& ray, PulseCandidates& out) const;

  // Every pulse with active[i] != 0, serially.
  void trace(std::span<const PulseRay> rays, std::span<const std::uint8_t> active,
             std::span<PulseCandidates> candidates) const;

 private:
  const Scene* scene_;
  TriangleMesh terrain_mesh_;
  ReceiverParams receiver_;
};

}  // namespace owsim

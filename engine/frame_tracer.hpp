#pragma once
// Traces a frame's pulses through the Embree scene (DESIGN.md "Batching"): the rays are split into
// chunks handed to tbb::parallel_for, and each chunk goes through one of Embree's three query
// forms, so benchmarks can compare them. Each chunk is traced twice: first against the solids
// (the central ray's nearest pole, tree or ground hit; a flat ground is intersected beforehand,
// outside Embree, and the solids searched only up to it), then against the wires up to that hit, so
// each conductor's candidate is its strongest segment in front of the solid (SENSOR-SPEC §7
// pinned occlusion) however Embree orders its visits; a ray that misses the wires' bounds up to
// its solid hit is not handed to the wire pass at all. Every pulse's result depends only on its own
// ray, so the output is bit-identical whatever the thread count or the API.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "engine/embree_scene.hpp"
#include "sensor/pulse_candidates.hpp"

namespace owsim {

enum class TraceApi {
  per_ray,   // rtcIntersect1 for each ray
  stream,    // rtcIntersect1M over the chunk (coherent flag set)
  packet8,   // rtcIntersect8 over groups of 8 rays
  packet16,  // rtcIntersect16 over groups of 16 rays
};
// Every way of tracing, in the order above (the bench's and the tests' sweeps over them).
inline constexpr std::array<TraceApi, 4> kTraceApis = {TraceApi::per_ray, TraceApi::stream,
                                                       TraceApi::packet8, TraceApi::packet16};

[[nodiscard]] std::string_view to_string(TraceApi api);

// The widest packet the device traces natively: packet16 where Embree runs on AVX-512, else
// packet8 (Embree would split a 16-ray packet for narrower lanes).
[[nodiscard]] TraceApi widest_native_packet(const EmbreeDevice& device);

// What the tracer does with Embree's hits. `traversal_only` is a yardstick (`owsim bench`): the
// same two queries against the same BVHs, the callbacks reduced to recording the hit — the
// cylinders' exact test still decides their hits, the wire filter rejects every segment unread,
// the wire pass reaches as far as Embree's solid hit (or the level ground), culled the same way —
// and no candidates. What remains of a pulse's cost is Embree's traversal, and the level ground's
// test that stands in for the flat terrain's part of it.
enum class TraceWork { candidates, traversal_only };

class FrameTracer {
 public:
  static constexpr unsigned kChunk = 256;  // rays per task and per stream call

  // `noise`: the receiver's statistics, whose sunlight background each solid hit records
  // (SENSOR-SPEC §11); the default has none.
  FrameTracer(const EmbreeScene& scene, TraceApi api, const ReceiverNoise& noise = {},
              TraceWork work = TraceWork::candidates)
      : scene_(&scene), api_(api), noise_(noise), work_(work) {}

  // Traces rays[i] for every i with active[i] != 0 and fills candidates[i] (cleared first; an
  // inactive pulse — the reference fiber — gets none). Spans must have equal sizes. Runs the
  // chunks in parallel on the calling thread's TBB arena.
  void trace(std::span<const PulseRay> rays, std::span<const std::uint8_t> active,
             std::span<PulseCandidates> candidates) const;

  // The same for rays [begin, end) on the calling thread only.
  void trace_range(std::span<const PulseRay> rays, std::span<const std::uint8_t> active,
                   std::span<PulseCandidates> candidates, unsigned begin, unsigned end) const;

  [[nodiscard]] TraceApi api() const { return api_; }

 private:
  const EmbreeScene* scene_;
  TraceApi api_;
  ReceiverNoise noise_;
  TraceWork work_;
};

}  // namespace owsim

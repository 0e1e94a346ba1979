#pragma once
// The extended intersect context (DESIGN.md "Batching"): Embree hands it to every callback, and
// through it the callbacks reach the double-precision rays and the per-pulse candidate buffers of
// the chunk being traced. Ray ids index `rays` and `candidates`; the cylinder records are per
// chunk.
#include <embree3/rtcore.h>

#include <span>

#include "geometry/cylinder.hpp"
#include "sensor/pulse_candidates.hpp"

namespace owsim {

class EmbreeScene;

struct TraceContext {
  RTCIntersectContext rtc;  // first member: Embree sees only this part
  const EmbreeScene* scene = nullptr;
  std::span<const PulseRay> rays;         // by ray id
  std::span<PulseCandidates> candidates;  // by ray id
  // The last cylinder hit the user-geometry callback accepted for a ray, in double precision, by
  // ray id − chunk_begin: cylinder_prims holds its primitive (RTC_INVALID_GEOMETRY_ID for none,
  // set by the tracer for each ray before its query), cylinder_hits the hit, read only where
  // cylinder_prims names a cylinder. Apart, so that a ray's 4-byte reset does not open the line
  // of a 48-byte hit.
  std::span<unsigned> cylinder_prims;
  std::span<CylinderHit> cylinder_hits;
  unsigned chunk_begin = 0;
  double max_range_m = 0.0;     // the counter timeout range: nothing beyond it is a candidate
  bool traversal_only = false;  // TraceWork::traversal_only: the wire filter rejects unread
};

[[nodiscard]] inline TraceContext* trace_context(RTCIntersectContext* context) {
  return reinterpret_cast<TraceContext*>(context);
}
[[nodiscard]] inline const TraceContext* trace_context(const RTCIntersectContext* context) {
  return reinterpret_cast<const TraceContext*>(context);
}

}  // namespace owsim

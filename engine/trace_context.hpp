#pragma once
// The extended intersect context (DESIGN.md "Batching"): Embree hands it to every callback, and
// through it the callbacks reach the double-precision rays and the per-pulse candidate buffers of
// the chunk being traced. Ray ids index `rays` and `candidates`; `cylinder_hits` is per chunk.
#include <embree3/rtcore.h>

#include <span>

#include "geometry/cylinder.hpp"
#include "sensor/pulse_candidates.hpp"

namespace owsim {

class EmbreeScene;

// The last cylinder hit the user-geometry callback accepted for a ray, in double precision. No
// member initialisers: the tracer sets prim_id to RTC_INVALID_GEOMETRY_ID for each ray it traces,
// and hit is read only where prim_id names a cylinder (a block's array of records, made for every
// block, was 14 KB of stores before its first ray).
struct CylinderRecord {
  unsigned prim_id;
  CylinderHit hit;
};

struct TraceContext {
  RTCIntersectContext rtc;  // first member: Embree sees only this part
  const EmbreeScene* scene = nullptr;
  std::span<const PulseRay> rays;           // by ray id
  std::span<PulseCandidates> candidates;    // by ray id
  std::span<CylinderRecord> cylinder_hits;  // by ray id − chunk_begin
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

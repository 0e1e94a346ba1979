#pragma once
// The smallest scenario the loader accepts: an origin and a 100 m waypoint leg, with its
// trajectory block last so that tests append keys to it (or sections after it) by line number.
namespace owsim::test {

inline constexpr const char* kMinimalScenario = R"(name: m
origin: {lat: 48.6881, lon: 10.8447, h: 450}
trajectory:
  waypoints:
    speed_mps: 40
    points: [{e: 0, n: 0, u: 100}, {e: 100, n: 0, u: 100}]
)";

}  // namespace owsim::test

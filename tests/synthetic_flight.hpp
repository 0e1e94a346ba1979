#pragma once
// Synthetic flights for the output tests (test_run_checkpoint, test_frame_encoding): frames of
// the scan's own pulses with returns of every class drawn from a generator seeded by the frame,
// a small scene with wires, a pole and a tree, and reading a folder's files back.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "geometry/scene.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/mounting.hpp"
#include "sensor/pulse_candidates.hpp"
#include "sensor/receiver.hpp"
#include "sensor/scan_pattern.hpp"

namespace owsim::test {

namespace fs = std::filesystem;

// A file's bytes.
inline std::string content(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Every regular file under `root` (hidden ones too), by path relative to it, with its bytes.
inline std::map<std::string, std::string> files_under(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) {
      files[fs::relative(entry.path(), root).string()] = content(entry.path());
    }
  }
  return files;
}

// A frame of synthetic returns: the scan's own pulses, rays fanning out from a moving sensor, and
// returns of every class drawn from a generator seeded by the frame, so frame k is the same
// whenever it is made (as the simulator's are).
struct SyntheticFrame {
  FrameSweep sweep;
  std::vector<Pulse> pulses;
  std::vector<PulseRay> rays;
  std::vector<PulseReturns> returns;
  Pose start;
  std::int64_t frame = 0;

  [[nodiscard]] FrameView view() const { return {frame, sweep, pulses, rays, returns}; }
};

inline SyntheticFrame synthetic_frame(const ScanParams& scan, std::int64_t frame) {
  SyntheticFrame f;
  f.frame = frame;
  f.sweep = frame_sweep(scan, 42, frame);
  const auto n = static_cast<std::size_t>(scan.pulses_per_frame());
  f.pulses.resize(n);
  f.rays.resize(n);
  f.returns.resize(n);
  const Eigen::Vector3d origin(-300.0 + 13.0 * static_cast<double>(frame), 5.0, 100.0);
  std::mt19937_64 rng(static_cast<std::uint64_t>(frame) + 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t k = 0; k < n; ++k) {
    const Pulse pulse = pulse_of_frame(scan, f.sweep, static_cast<int>(k));
    f.pulses[k] = pulse;
    const double beta = pulse.beta_deg * 0.0174533;
    const double alpha = pulse.reference ? 0.0 : pulse.alpha_deg * 0.0174533;
    f.rays[k] = {origin, Eigen::Vector3d(std::sin(beta), std::cos(beta), alpha - 0.3).normalized()};
    PulseReturns& returns = f.returns[k];
    const double draw = unit(rng);
    returns.count = pulse.reference ? 0 : draw < 0.4 ? 1 : draw < 0.45 ? 2 : 0;
    for (int r = 0; r < returns.count; ++r) {
      Return& ret = returns.returns[r];
      const auto object = static_cast<std::uint32_t>(rng() % 5);  // 0, 1 wires, 2 pole, 3 tree
      ret.object_index = object;
      ret.surface = static_cast<std::uint8_t>(object < 2 ? 0 : object - 1);
      ret.true_range_m = 40.0 + 800.0 * unit(rng) + 100.0 * r;
      ret.range_m = ret.true_range_m + 0.4 * (unit(rng) - 0.5);
      ret.counter = static_cast<std::uint16_t>(ret.range_m / 0.6);
      ret.energy_rel = 0.2 * unit(rng);
      ret.incidence_deg = 90.0 * unit(rng);
    }
    if (returns.count > 0) returns.counter1 = returns.returns[0].counter;
    if (returns.count > 1) returns.counter2 = returns.returns[1].counter;
  }
  f.start.time_s = f.pulses.front().time_s;
  f.start.position_enu_m = origin;
  f.start.attitude = {1.0, -4.0, 90.0 + 0.5 * static_cast<double>(frame)};
  return f;
}

inline Scene small_scene() {
  Scene scene;
  scene.terrain.kind = TerrainKind::flat;
  for (int n = 1; n <= 2; ++n) {
    Conductor& wire = scene.conductors.emplace_back();
    wire.id = "span/" + std::to_string(n);
    wire.points_enu_m = {{-500.0, 4.0 * n, 30.0}, {0.0, 4.0 * n, 22.0}, {500.0, 4.0 * n, 30.0}};
  }
  scene.cylinders.push_back({"p1", SurfaceClass::pole, {50.0, 50.0, 0.0}, 0.3, 12.0, 0.3});
  scene.cylinders.push_back({"t1", SurfaceClass::tree, {-100.0, 80.0, 0.0}, 3.0, 15.0, 0.2});
  return scene;
}

}  // namespace owsim::test

#pragma once
// The scenario side of decoding or merging a recording (SENSOR-SPEC §4, §5, §9; DESIGN.md: io may
// use the engine for decode and merge): the trajectory the recording was flown on (the
// scenario's, or a navigation file named on the command line), the scenario's objects as an
// Embree scene over the region the recording's pulses can reach, and the central ray of every
// decoded pulse.
//
// Rays are built as the frame simulator builds them — the pose at the pulse's own time,
// sensor_placement, ray_direction_enu(α, β) (sensor/mounting.hpp) — so a pulse carrying the
// simulator's time, α and β gets the simulator's ray bit for bit. Set up once (may allocate, may
// throw); the ray builder is allocation-free once the caller's vectors have grown.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/embree_device.hpp"
#include "engine/embree_scene.hpp"
#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/recording/recording_decoder.hpp"
#include "io/scenario/scenario.hpp"
#include "sensor/pulse_candidates.hpp"
#include "sensor/trajectory.hpp"

namespace owsim {

// What the decode and merge commands may change in the scenario they are given.
struct RecordingScenarioOverrides {
  // A recorded navigation file instead of the scenario's trajectory source (`--trajectory`):
  // format "hellsim", "csv" or "sbet"; nullopt → csv for a .csv file, else hellsim (as the
  // scenario loader decides). The scenario's tick_s, heading, smoothing and irs_noise still apply.
  std::optional<std::filesystem::path> trajectory;
  std::optional<std::string> trajectory_format;
  std::optional<std::uint64_t> seed;  // `--seed`
  bool no_noise = false;              // `--no-noise`: range noise σ = 0, receiver noise off
};

// Loads the scenario (io/scenario/scenario_loader.hpp) and applies the overrides. Throws
// owsim::Error.
[[nodiscard]] Scenario load_recording_scenario(const std::filesystem::path& scenario_path,
                                               const RecordingScenarioOverrides& overrides);

// Checks the recording's word format — `format` ("d64" or "hellas") when given, else the file's
// extension (.d64, .hellas), else the scenario's — against the scenario's sensor.model (the mount
// and the scan depend on it). Throws owsim::Error naming the recording when they disagree.
void check_recording_format(const std::filesystem::path& recording,
                            const std::optional<std::string>& format, const Scenario& scenario);

class RecordingScene {
 public:
  // Loads the trajectory and builds the scene. Throws owsim::Error naming the recording when its
  // pulses fall outside the trajectory's time span (the time-tag wrap may be the wrong one: see
  // RecordingDecoderOptions::start_hint_s).
  RecordingScene(const Scenario& scenario, const RecordingLayout& layout);
  RecordingScene(const RecordingScene&) = delete;
  RecordingScene& operator=(const RecordingScene&) = delete;

  [[nodiscard]] const LocalFrame& local_frame() const { return local_frame_; }
  [[nodiscard]] const Trajectory& trajectory() const { return trajectory_; }
  [[nodiscard]] const Scene& scene() const { return scene_; }
  [[nodiscard]] const EmbreeScene& embree_scene() const { return *embree_scene_; }
  // The `object` table of points.csv, by object index: conductors, cylinders, then "terrain".
  [[nodiscard]] std::vector<std::string> object_ids() const;

 private:
  LocalFrame local_frame_;
  Trajectory trajectory_;
  Scene scene_;
  EmbreeDevice device_;
  std::unique_ptr<EmbreeScene> embree_scene_;
};

// The central ray of every pulse (local ENU), in parallel over the pulses; active[i] = 0 for the
// reference fiber (its ray is left default). Resizes `rays` and `active` to pulses.size().
void pulse_rays(std::span<const Pulse> pulses, const PoseSource& poses, const Mount& mount,
                SensorModel model, std::vector<PulseRay>& rays, std::vector<std::uint8_t>& active);

}  // namespace owsim

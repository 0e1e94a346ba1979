#pragma once
// A recording turned into points (INTERFACE.md `owsim decode`; source ch. 2, 10): what a replay
// tool shows a person. Every decoded return (counter < timeout) is placed at counter·Δ along its
// pulse's ray (io/recording/recording_decoder_scene.hpp) and written to points.csv, points.las and
// points.ply exactly as `owsim run` writes them (io/points/frame_points.hpp, the same writers).
//
// Range: counter·Δ, within Δ/2 = 0.30 m of the true range (plus the noise). Direction: the
// decoded α and β — MilOWS β from the encoder is within ±0.0018° of the simulated mirror β, a
// lateral error of at most 3.2e-5 rad × range (4 cm at the 1238 m timeout); HELLAS from the NI
// mark within 0.0009° (2 cm).
//
// Labels: a word holds no class. When the scenario has objects, each decoded ray is traced
// against them and a return takes the class, object, energy and incidence of the scene's
// candidate nearest in range (wires in front of the solid hit, and the solid hit, detected or
// not) if it lies within Δ + 3σ of counter·Δ (σ the scenario's range noise); a return that
// matches nothing stays `unknown` (points.csv class `unknown`, LAS class 0, PLY class 255).
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>

#include "io/recording/recording_decoder.hpp"
#include "io/recording/recording_decoder_scene.hpp"
#include "io/scenario/scenario.hpp"
#include "sensor/receiver.hpp"

namespace owsim {

struct DecodePointsOptions {
  std::filesystem::path directory;  // points.csv, points.las, points.ply (created if need be)
  bool csv = true;                  // which of the three point files to write
  bool las = true;
  bool ply = true;
  bool label_from_scene = true;  // classes from the scenario's objects
  // Told after every frame how many frames and pulses are done (progress); may be empty.
  std::function<void(std::uint64_t frames, std::uint64_t pulses)> on_frame;
};

struct DecodeReport {
  std::uint64_t frames = 0;
  std::uint64_t pulses = 0;
  std::uint64_t points = 0;
  std::uint64_t second_returns = 0;
  std::uint64_t labelled_points = 0;  // points the scene gave a class
  std::uint64_t time_tag_mismatches = 0;
  // Frames by where their mirror β came from (index: MirrorBetaSource).
  std::array<std::uint64_t, 4> frames_by_beta_source{};
};

// The returns one recorded pulse holds: counter 1, then counter 2, each one below the timeout a
// return at counter·Δ, in that order (count 0..2; counter1/counter2 copied as they are).
[[nodiscard]] PulseReturns recorded_returns(std::uint16_t counter1, std::uint16_t counter2,
                                            const RangeCounterParams& counter);

// The candidate nearest in range to range_m, if within tolerance_m of it.
[[nodiscard]] std::optional<Candidate> nearest_candidate(std::span<const Candidate> candidates,
                                                         double range_m, double tolerance_m);

// Δ + 3σ: how far a recorded return may lie from the scene candidate it is labelled with.
[[nodiscard]] double label_tolerance_m(const ReceiverParams& receiver);

// Decodes every remaining frame of `decoder` and writes the three point files; they appear under
// their final names only when complete (io/files/atomic_output_file.hpp).
DecodeReport decode_recording_points(RecordingDecoder& decoder, const RecordingScene& scene,
                                     const Scenario& scenario, const DecodePointsOptions& options);

}  // namespace owsim

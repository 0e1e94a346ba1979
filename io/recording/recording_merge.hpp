#pragma once
// Synthetic objects merged into a real recording (SENSOR-SPEC §9; source ch. 2, 8, 10;
// INTERFACE.md `owsim merge`): for every pulse of the recording, its ray is rebuilt
// (io/recording/recording_decoder.hpp, io/recording/recording_decoder_scene.hpp), traced against
// the scenario's objects, and the receiver (sensor/receiver.hpp, the scenario's threshold, noise
// keyed by (seed, frame, pulse) as in a simulation) gives the synthetic returns. The word keeps
// every bit but its counters, and those change only where the synthetic scene is seen:
//   - a synthetic return nearer than the recorded first return (or a pulse that had none): the
//     synthetic count goes to counter 1 and the recorded first return moves to counter 2 (MilOWS;
//     HELLAS has one counter, which takes the nearest);
//   - a synthetic pole, tree or ground hit nearer than a recorded return hides it (SENSOR-SPEC §7
//     pinned occlusion: the central ray stops at the nearest solid, detected or not) — the
//     recorded return is removed, as a simulation of both scenes together would.
// When a word changes, its counters are chosen as the receiver chooses (§7 pinned return
// selection) from the synthetic returns and the recorded ones still visible: the nearest, then
// the next at least min_return_separation_m beyond it (for a synthetic/recorded pair judged on
// the counters; pairs from one source are already separated). A synthetic object behind the
// recorded first return is not written: the recording's first echo may come from a solid.
// Recorded returns carry no energy, so with `sensor.returns: strongest` the merge still picks by
// range as above (and so differs from a simulation of both scenes under that rule).
// With noise off this equals simulating both scenes together, word for word, when the rays are
// rebuilt exactly (below), no synthetic object lies behind a recorded wire echo, and no
// synthetic/recorded pair of returns lies within a counter of the separation (tests/test_merge).
//
// Exact rays. On an owsim recording whose time tags lie on the scenario's pulse grid
// (RecordingTiming::scenario_grid), each frame's sweep is rebuilt as the simulator draws it —
// frame_sweep(seed, frame, look-into-turn shift at the frame's start) — and used when it
// reproduces the recording (MilOWS: every encoder word; HELLAS: MovDir, the NI mark, the header
// code): then the pulses have the simulator's α and β to the last bit. Otherwise β is the
// measured one (encoder or NI, within ±0.0018°).
//
// The merged file has the recording's format, frame structure and every other bit (the HELLAS
// header word included); a recording cut inside a word is refused by the decoder. It is written
// through an AtomicOutputFile: nothing appears under its name until it is complete.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>

#include "io/recording/recording_decoder.hpp"
#include "io/recording/recording_decoder_scene.hpp"
#include "io/scenario/scenario.hpp"
#include "sensor/receiver.hpp"

namespace owsim {

// What merging did to one pulse. When the counters come out as recorded (changed = false) the
// counts are all 0.
struct MergedCounters {
  std::uint16_t counter1 = 0;
  std::uint16_t counter2 = 0;
  bool changed = false;
  int synthetic_written = 0;  // synthetic returns now in the word
  int recorded_moved = 0;     // recorded first return moved to counter 2
  int recorded_hidden = 0;    // recorded returns behind a synthetic solid
  int recorded_dropped = 0;   // recorded returns pushed out by nearer synthetic ones
};

// The counters of one pulse after merging  (SENSOR-SPEC §9, §7 pinned return selection)
// recorded1/recorded2: the word's counters (recorded2 ignored without a second field);
// synthetic: select_returns over the synthetic candidates; synthetic_solid_counter: the
// noise-free counter of the synthetic central ray's solid hit, if any. Counters at or above the
// timeout are no return.
[[nodiscard]] MergedCounters merge_pulse_counters(
    std::uint16_t recorded1, std::uint16_t recorded2, bool second_field,
    const PulseReturns& synthetic, std::optional<std::uint16_t> synthetic_solid_counter,
    const ReceiverParams& receiver);

struct MergeOptions {
  std::filesystem::path out;  // the merged recording; must not be the recording itself
  // Told after every frame how many frames and pulses are done (progress); may be empty.
  std::function<void(std::uint64_t frames, std::uint64_t pulses)> on_frame;
};

struct MergeReport {
  std::uint64_t frames = 0;
  std::uint64_t pulses = 0;
  std::uint64_t words_changed = 0;
  std::uint64_t synthetic_returns = 0;      // synthetic counts written
  std::uint64_t recorded_moved = 0;         // recorded first returns moved to counter 2
  std::uint64_t recorded_hidden = 0;        // recorded returns hidden by a synthetic solid
  std::uint64_t recorded_dropped = 0;       // recorded returns pushed out of the word
  std::uint64_t frames_sweep_rebuilt = 0;   // α, β exactly as the simulator's
  std::uint64_t frames_sweep_measured = 0;  // β from the encoder / NI mark
  std::uint64_t time_tag_mismatches = 0;
};

// Merges the scenario's objects (scene) into every remaining frame of `decoder` and writes the
// merged recording. Throws owsim::Error on a write failure or when options.out is the recording.
MergeReport merge_recording(RecordingDecoder& decoder, const RecordingScene& scene,
                            const Scenario& scenario, const MergeOptions& options);

}  // namespace owsim

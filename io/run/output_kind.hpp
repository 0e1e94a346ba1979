#pragma once
// The output files of `owsim run` (INTERFACE.md "`owsim run` outputs") and their names.
#include <set>
#include <string>
#include <string_view>

#include "sensor/scan_params.hpp"

namespace owsim {

// The point files are three outputs: points.csv, points.las, points.ply.
// truth: truth.csv, the objects each frame could see (io/run/truth_csv.hpp).
// mcap: flight.mcap and metadata.yaml for Foxglove and ROS 2 (io/run/flight_mcap.hpp); written
// only when asked for by name.
// detections: detections.csv, the reference obstacle detector's warnings (DETECTION-SPEC), made
// from the word file the run wrote (io/detections/recording_detections.hpp), so asking for it
// writes the words too; only when asked for by name.
enum class OutputKind { d64, csv, las, ply, trajectory, summary, truth, quicklook, mcap, detections };

// "d64,summary" → {d64, summary}; `points` is csv, las and ply together; `detections` brings d64
// with it; the word file is flight.hellas for a HELLAS scenario. Throws owsim::Error naming the unknown item.
[[nodiscard]] std::set<OutputKind> parse_output_list(std::string_view list);
// The list parse_output_list reads back: the outputs in a fixed order, "d64,points,…" (`points`
// for all three point files, else those chosen).
[[nodiscard]] std::string output_list(const std::set<OutputKind>& outputs);
// The default outputs: every one but mcap and detections.
[[nodiscard]] std::set<OutputKind> all_outputs();
// Whether any point file is among `outputs`.
[[nodiscard]] bool wants_points(const std::set<OutputKind>& outputs);

// flight.d64 (MilOWS) or flight.hellas (HELLAS).
[[nodiscard]] std::string_view word_file_name(const ScanParams& scan);

}  // namespace owsim

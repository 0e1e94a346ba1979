#pragma once
// Everything `owsim run` writes (INTERFACE.md "owsim run outputs"), fed one frame at a time in
// frame order: the sensor words (flight.d64 or flight.hellas), points.csv / points.las /
// points.ply, trajectory.csv, summary.json and quicklook/. Each file is written under a temporary
// name and appears under its final name only when finish() completes it, so an interrupted run
// leaves nothing half-written.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "geometry/geodetic_frame.hpp"
#include "geometry/scene.hpp"
#include "io/flight_summary.hpp"
#include "io/point_record.hpp"
#include "sensor/frame_view.hpp"
#include "sensor/mounting.hpp"
#include "sensor/scan_params.hpp"

namespace owsim {

enum class OutputKind { d64, points, trajectory, summary, quicklook };

// "d64,summary" → {d64, summary}; the word file is flight.hellas for a HELLAS scenario. Throws
// owsim::Error naming the unknown item.
[[nodiscard]] std::set<OutputKind> parse_output_list(std::string_view list);
[[nodiscard]] std::set<OutputKind> all_outputs();

struct FlightOutputOptions {
  std::filesystem::path directory;
  std::set<OutputKind> outputs = all_outputs();
  int quicklook_every_nth_frame = 10;
  Eigen::AlignedBox2d map_region;  // the quick-look map's extent (east, north)
};

class WordSink;
class TrajectoryCsvWriter;
class Quicklook;

class FlightOutputs {
 public:
  // Creates the directory and opens every requested output (as temporaries).
  FlightOutputs(const FlightOutputOptions& options, const Scene& scene, const ScanParams& scan,
                const LocalFrame& local_frame);
  ~FlightOutputs();
  FlightOutputs(const FlightOutputs&) = delete;
  FlightOutputs& operator=(const FlightOutputs&) = delete;

  // One frame, in order; `frame_start` is the aircraft's pose at the frame's first pulse.
  void add_frame(const FrameView& frame, const Pose& frame_start);

  // Completes every file and writes summary.json with `run_facts` merged into the totals.
  void finish(const nlohmann::json& run_facts);

  [[nodiscard]] const FlightSummary& summary() const { return summary_; }

 private:
  [[nodiscard]] bool wants(OutputKind kind) const { return options_.outputs.contains(kind); }

  FlightOutputOptions options_;
  ScanParams scan_;
  const LocalFrame* local_frame_;
  FlightSummary summary_;
  std::unique_ptr<WordSink> words_;
  std::vector<std::unique_ptr<PointSink>> point_sinks_;
  std::unique_ptr<TrajectoryCsvWriter> trajectory_;
  std::unique_ptr<Quicklook> quicklook_;
  std::vector<PointRecord> points_;  // reused per frame
};

}  // namespace owsim

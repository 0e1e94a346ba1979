#pragma once
// The studio's one run at a time (docs/studio.md "Fly"): the scenario's YAML flown through the
// facade (Simulation::from_yaml … run, what `owsim run` does) on a thread of its own into a new
// folder that replaces the output folder whole once the flight completes
// (folder_replacement.hpp), then that folder's report page (`owsim view`). Progress is read
// while it runs; a cancel stops it after the frame in hand, and a cancelled or failed flight
// leaves the output folder as the previous flight left it. The output folder must be new, empty
// or a flight's (its summary.json), and must not hold the scenario.
#include <atomic>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

namespace owsim::studio {

// Fly replaces the output folder `out` whole, so it must hold nothing else: not the scenario's
// folder or one above it, and new, empty or a flight's (its summary.json). Throws owsim::Error
// with one line saying why not.
void check_output_folder(const std::filesystem::path& out,
                         const std::filesystem::path& scenario_file);

class FlightJob {
 public:
  FlightJob() = default;
  FlightJob(const FlightJob&) = delete;
  FlightJob& operator=(const FlightJob&) = delete;
  ~FlightJob();  // cancels a run in progress and waits for it

  // Starts flying `yaml` (named `scenario_file`: anchors its relative paths) into `out`; false
  // (nothing started) while another run is in progress.
  bool start(std::string yaml, std::filesystem::path scenario_file, std::filesystem::path out);
  // Asks a run in progress to stop; it ends as "cancelled".
  void cancel();
  // Waits for the run in progress, if any, to end.
  void wait();
  // {"state": idle|building|flying|report|done|failed|cancelled, "frames_done", "frames_total",
  //  "error" (failed), "out" (the folder)}
  [[nodiscard]] nlohmann::json status() const;

 private:
  void fly(const std::string& yaml, const std::filesystem::path& scenario_file,
           const std::filesystem::path& out);
  void set_state(const char* state, std::string error = {});

  mutable std::mutex mutex_;
  std::thread thread_;
  std::atomic<bool> cancel_{false};
  std::atomic<bool> running_{false};
  std::atomic<std::int64_t> frames_done_{0};
  std::atomic<std::int64_t> frames_total_{0};
  std::string state_ = "idle";  // guarded by mutex_
  std::string error_;           // guarded by mutex_
  std::filesystem::path out_;   // guarded by mutex_
};

}  // namespace owsim::studio

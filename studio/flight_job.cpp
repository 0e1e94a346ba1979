#include "studio/flight_job.hpp"

#include <exception>
#include <utility>

#include "geometry/error.hpp"
#include "io/files/confined_path.hpp"
#include "owsim/flight_report.hpp"
#include "owsim/simulation.hpp"
#include "studio/folder_replacement.hpp"

namespace owsim::studio {
namespace {

// Thrown from the progress callback to stop a run (the run removes its outputs).
struct Cancelled {};

}  // namespace

void check_output_folder(const std::filesystem::path& out,
                         const std::filesystem::path& scenario_file) {
  const auto refuse = [&](const std::string& what) {
    return Error(out.string() + ": " + what +
                 "; Fly replaces its output folder whole: choose another --out");
  };
  if (inside_tree(out, std::filesystem::weakly_canonical(scenario_file).parent_path())) {
    throw refuse("holds the scenario");
  }
  std::error_code error;
  if (!std::filesystem::exists(std::filesystem::symlink_status(out, error))) return;
  if (!std::filesystem::is_directory(std::filesystem::symlink_status(out, error))) {
    throw refuse("not a folder");
  }
  if (!std::filesystem::is_empty(out, error) &&
      !std::filesystem::is_regular_file(out / "summary.json", error)) {
    throw refuse("holds files that are not a flight's (no summary.json)");
  }
}

FlightJob::~FlightJob() {
  cancel();
  wait();
}

bool FlightJob::start(std::string yaml, std::filesystem::path scenario_file,
                      std::filesystem::path out) {
  if (running_.exchange(true)) return false;
  wait();  // the thread of the run before, already finished
  cancel_ = false;
  frames_done_ = 0;
  frames_total_ = 0;
  {
    const std::lock_guard lock(mutex_);
    state_ = "building";
    error_.clear();
    out_ = out;
  }
  thread_ = std::thread([this, yaml = std::move(yaml), scenario_file = std::move(scenario_file),
                         out = std::move(out)] {
    fly(yaml, scenario_file, out);
    running_ = false;
  });
  return true;
}

void FlightJob::fly(const std::string& yaml, const std::filesystem::path& scenario_file,
                    const std::filesystem::path& out) {
  try {
    const Simulation simulation = Simulation::from_yaml(yaml, scenario_file);
    frames_total_ = simulation.frame_count();
    const std::filesystem::path folder = std::filesystem::weakly_canonical(out);
    check_output_folder(folder, scenario_file);
    FolderReplacement replacement(folder);
    set_state("flying");
    RunOptions options;
    options.out = replacement.path();
    options.progress = [this](const RunProgress& progress) {
      frames_done_ = progress.frames_done;
      if (cancel_) throw Cancelled{};
    };
    (void)simulation.run(options);
    replacement.commit();
    // The page names its folder: written where the flight now is.
    set_state("report");
    (void)write_flight_report(folder);
    set_state("done");
  } catch (const Cancelled&) {
    set_state("cancelled");
  } catch (const std::exception& error) {
    // A cancel may come back wrapped by the layers between the callback and here.
    if (cancel_) {
      set_state("cancelled");
    } else {
      set_state("failed", error.what());
    }
  }
}

void FlightJob::cancel() { cancel_ = true; }

void FlightJob::wait() {
  if (thread_.joinable()) thread_.join();
}

void FlightJob::set_state(const char* state, std::string error) {
  const std::lock_guard lock(mutex_);
  state_ = state;
  error_ = std::move(error);
}

nlohmann::json FlightJob::status() const {
  const std::lock_guard lock(mutex_);
  nlohmann::json status = {{"state", state_},
                           {"frames_done", frames_done_.load()},
                           {"frames_total", frames_total_.load()},
                           {"out", out_.string()}};
  if (!error_.empty()) status["error"] = error_;
  return status;
}

}  // namespace owsim::studio

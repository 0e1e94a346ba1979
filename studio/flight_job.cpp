#include "studio/flight_job.hpp"

#include <exception>
#include <utility>

#include "geometry/error.hpp"
#include "owsim/flight_report.hpp"
#include "owsim/simulation.hpp"

namespace owsim::studio {
namespace {

// Thrown from the progress callback to stop a run (the run removes its outputs).
struct Cancelled {};

}  // namespace

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
    set_state("flying");
    RunOptions options;
    options.out = out;
    options.progress = [this](const RunProgress& progress) {
      frames_done_ = progress.frames_done;
      if (cancel_) throw Cancelled{};
    };
    (void)simulation.run(options);
    set_state("report");
    (void)write_flight_report(out);
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

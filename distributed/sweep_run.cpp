#include "distributed/sweep_run.hpp"

#include <array>
#include <chrono>
#include <nlohmann/json.hpp>
#include <system_error>

#include "distributed/member_dispenser.hpp"
#include "distributed/sweep_members.hpp"
#include "geometry/error.hpp"
#include "geometry/number_text.hpp"
#include "io/files/atomic_output_file.hpp"
#include "io/files/input_file.hpp"
#include "io/files/json_text.hpp"
#include "io/files/output_open.hpp"
#include "io/run/run_checkpoint.hpp"
#include "io/sweep/sweep_table.hpp"
#include "owsim/simulation.hpp"
#include "owsim/version.hpp"

namespace owsim {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::string_view kSweepStateFileName = ".owsim-sweep.json";

nlohmann::json sweep_state(const SweepSpec& spec) {
  return {{"owsim_version", version_string},
          {"sweep_file", ContentHash::hex_of(spec.text)},
          {"base_scenario", ContentHash::hex_of(spec.base_text)}};
}

// Process 0: the output folder made ready; whether complete members may be skipped.
bool prepare_folder(const SweepSpec& spec, const SweepRunOptions& options) {
  std::error_code error;
  std::filesystem::create_directories(options.out, error);
  if (error) {
    throw file_error(options.out.string(), "cannot create the output folder: " + error.message());
  }
  const std::filesystem::path state_path = options.out / kSweepStateFileName;
  const nlohmann::json state = sweep_state(spec);
  bool skip_complete = false;
  if (options.resume) {
    if (std::filesystem::exists(state_path)) {
      nlohmann::json before;
      try {
        before = nlohmann::json::parse(read_input_file(state_path, "sweep state", 1 << 20));
      } catch (const nlohmann::json::exception& e) {
        throw input_error(state_path.string(), std::string("damaged sweep state: ") + e.what());
      }
      require_same_run(state_path, before, state);
      skip_complete = true;
    } else if (options.notice) {
      options.notice("no sweep state " + state_path.string() + ": running every member");
    }
  }
  AtomicOutputFile file(state_path);
  file.write(json_text(state, 2) + "\n");
  file.commit();
  return skip_complete;
}

std::set<OutputKind> member_outputs(const SweepSpec& spec) {
  std::set<OutputKind> outputs;
  try {
    outputs = parse_output_list(spec.outputs);
  } catch (const Error& e) {
    throw input_error(spec.file.string(), std::string("outputs: ") + e.what());
  }
  outputs.insert(OutputKind::summary);  // sweep.csv is made from it
  return outputs;
}

}  // namespace

SweepReport run_sweep(Communicator& comm, const SweepSpec& spec, const SweepRunOptions& options) {
  const bool root = comm.rank() == 0;
  const std::set<OutputKind> outputs = member_outputs(spec);
  SimulationOptions simulation_options;
  simulation_options.threads =
      options.threads > 0 ? options.threads : default_threads_per_process(comm);
  check_every_member(comm, spec, simulation_options);  // before anything is written
  std::string error;
  std::string skip_complete = "0";
  if (root) {
    try {
      skip_complete = prepare_folder(spec, options) ? "1" : "0";
    } catch (const Error& e) {
      error = e.what();
    }
  }
  throw_if_any_failed(comm, error);
  comm.broadcast(skip_complete, 0);

  SweepReport report;
  report.members = spec.count;
  report.processes = comm.size();
  report.threads = simulation_options.threads;
  std::array<std::uint64_t, 3> totals{};  // ran, skipped, pulses
  const auto start = Clock::now();
  {
    MemberDispenser dispenser(comm, spec.count);
    while (const std::optional<std::int64_t> member = dispenser.next()) {
      const std::filesystem::path directory = member_directory(spec, options.out, *member);
      const std::string name = member_folder_name(spec, *member);
      make_output_subfolder(directory);  // a link planted at a member's name is not followed
      if (skip_complete == "1" && std::filesystem::exists(directory / "summary.json")) {
        ++totals[1];
        if (options.notice) options.notice("member " + name + " complete before: skipped");
        continue;
      }
      const Simulation simulation = member_simulation(spec, *member, simulation_options);
      RunOptions run;
      run.out = directory;
      run.outputs = outputs;
      // flight.mcap is not continued from a checkpoint (io/run/flight_mcap.hpp): an unfinished
      // member that writes it starts over, which gives the same bytes.
      run.resume = options.resume && !outputs.contains(OutputKind::mcap);
      const RunReport member_report = simulation.run(run);
      ++totals[0];
      totals[2] += static_cast<std::uint64_t>(member_report.frames - member_report.first_frame) *
                   static_cast<std::uint64_t>(simulation.pulses_per_frame());
      if (options.notice) {
        options.notice("member " + name + " done: " + std::to_string(member_report.frames) +
                       " frames in " + number_text(member_report.wall_s, 3) + " s");
      }
    }
  }
  comm.sum(totals);
  if (root) {
    try {
      write_sweep_table(spec, options.out);
    } catch (const Error& e) {
      error = e.what();
    }
  }
  throw_if_any_failed(comm, error);
  report.ran = static_cast<std::int64_t>(totals[0]);
  report.skipped = static_cast<std::int64_t>(totals[1]);
  report.pulses = totals[2];
  report.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  report.pulses_per_s = report.wall_s > 0 ? static_cast<double>(report.pulses) / report.wall_s : 0;
  return report;
}

}  // namespace owsim

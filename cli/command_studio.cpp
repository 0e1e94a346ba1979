// owsim studio [SCENARIO.yaml | TRAJECTORY] [--port N] [--no-browser] [--out DIR] — place objects
// along a flight in the browser, fly it, look at it (INTERFACE.md "Studio", docs/studio.md).
#include <fcntl.h>
#include <fmt/core.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "cli/commands.hpp"
#include "geometry/error.hpp"
#include "studio/new_scenario.hpp"
#include "studio/studio_server.hpp"

extern char** environ;

namespace owsim::cli {
namespace {

struct StudioCommandOptions {
  std::filesystem::path input;
  std::filesystem::path out;
  int port = 0;
  bool no_browser = false;
};

bool is_scenario_file(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  return extension == ".yaml" || extension == ".yml";
}

// xdg-open ADDRESS, without a shell; a machine without a desktop just has no browser to open.
void open_browser(const std::string& address) {
  pid_t child = 0;
  char program[] = "xdg-open";
  std::string argument = address;
  char* argv[] = {program, argument.data(), nullptr};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  if (posix_spawnp(&child, program, &actions, nullptr, argv, environ) == 0) {
    std::thread([child] { waitpid(child, nullptr, 0); }).detach();
  }
  posix_spawn_file_actions_destroy(&actions);
}

void run_studio(const StudioCommandOptions& options) {
  studio::StudioOptions studio;
  studio.port = options.port;
  if (options.input.empty()) {
    // No input: a new planned flight in the current folder (studio.yaml, opened when it exists).
    studio.scenario_file = "studio.yaml";
    if (!std::filesystem::exists(studio.scenario_file)) {
      studio.initial_yaml = studio::new_planned_scenario_yaml("studio");
    }
  } else if (is_scenario_file(options.input)) {
    if (!std::filesystem::is_regular_file(options.input)) {
      throw FileError(options.input.string() + ": no such scenario file");
    }
    studio.scenario_file = options.input;
  } else {
    // A new scenario beside the trajectory, named after it.
    const std::filesystem::path trajectory = options.input;
    studio.scenario_file = trajectory.parent_path() / (trajectory.stem().string() + ".yaml");
    if (std::filesystem::exists(studio.scenario_file)) {
      throw Error(studio.scenario_file.string() + ": exists already: open it with owsim studio " +
                  studio.scenario_file.string());
    }
    studio.initial_yaml = studio::new_scenario_yaml(trajectory, trajectory.filename().string());
  }
  const std::filesystem::path folder =
      std::filesystem::absolute(studio.scenario_file).parent_path();
  studio.out = options.out.empty() ? folder / "out" / studio.scenario_file.stem() : options.out;

  // SIGINT and SIGTERM go to one thread that stops the server; the others never see them.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  studio::StudioServer server(std::move(studio));
  std::fprintf(stdout, "%s\n", server.address().c_str());
  std::fflush(stdout);
  fmt::print(stderr, "owsim studio: serving {} on 127.0.0.1:{} (Ctrl-C stops it)\n",
             folder.string(), server.port());
  if (!options.no_browser) open_browser(server.address());
  std::thread stopper([&server, signals] {
    int signal = 0;
    sigwait(&signals, &signal);
    server.stop();
  });
  server.serve();
  // Served until a signal: the stopper has stopped the server. (Served until an error: wake it.)
  pthread_kill(stopper.native_handle(), SIGTERM);
  stopper.join();
}

}  // namespace

void add_studio_command(CLI::App& app, CommandResult& /*result*/) {
  auto options = std::make_shared<StudioCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "studio", "place objects along a flight in the browser, fly it and look at it");
  command->add_option("INPUT", options->input,
                      "a scenario (.yaml) to open, or a recorded trajectory (SBET, CSV, HellSim, "
                      "ArduPilot .log) to start a new scenario beside it; none: studio.yaml in the "
                      "current folder, a new planned flight when it does not exist");
  command->add_option("--port", options->port, "the port on 127.0.0.1 (default: a free one)")
      ->check(CLI::Range(0, 65535));
  command->add_option("--out", options->out,
                      "the output folder of Fly, replaced whole by each flight that completes "
                      "(default: out/<scenario> beside the scenario)");
  command->add_flag("--no-browser", options->no_browser, "print the address, open no browser");
  command->callback([options] { run_studio(*options); });
}

}  // namespace owsim::cli

// owsim — the command-line tool. Library code throws owsim::Error; only here does an error become
// one line on stderr and a non-zero exit status.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "distributed/communicator.hpp"
#include "geometry/error.hpp"
#include "owsim/version.hpp"

int main(int argc, char** argv) {
  // Named, not taken from argv[0]: the help text (and the man pages made from it) says `owsim`.
  CLI::App app{"owsim — MilOWS/HELLAS obstacle-warning LiDAR simulator", "owsim"};
  app.set_version_flag("--version", std::string("owsim ") + owsim::version_string);
  app.require_subcommand(1);
  // One line per error, as for every other error owsim reports.
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("owsim: ") + e.what() + " (see --help)\n";
  });
  owsim::cli::CommandResult result;
  owsim::cli::add_pattern_command(app, result);
  owsim::cli::add_run_command(app, result);
  owsim::cli::add_info_command(app, result);
  owsim::cli::add_bench_command(app, result);
  owsim::cli::add_decode_command(app, result);
  owsim::cli::add_merge_command(app, result);
  owsim::cli::add_sweep_command(app, result);
  owsim::cli::add_view_command(app, result);
  owsim::cli::add_pd_command(app, result);
  owsim::cli::add_score_command(app, result);
  owsim::cli::add_detect_command(app, result);
  owsim::cli::add_roc_command(app, result);
  owsim::cli::add_studio_command(app, result);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const owsim::ReportedElsewhere&) {
    return 1;  // process 0 of the MPI job said why
  } catch (const owsim::Error& e) {
    // One write: under mpirun a line written in pieces interleaves with the launcher's own.
    std::cerr << std::string("owsim: ") + e.what() + "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << std::string("owsim: internal error: ") + e.what() + "\n";
    return 2;
  }
  return result.exit_status;
}

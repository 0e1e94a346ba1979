#pragma once
// Each `owsim` subcommand registers itself on the CLI11 app; main() only dispatches.
#include <CLI/CLI.hpp>

namespace owsim::cli {

// What a command asks main() to exit with once it has run (0 unless it says otherwise).
struct CommandResult {
  int exit_status = 0;
};

void add_pattern_command(CLI::App& app, CommandResult& result);
void add_info_command(CLI::App& app, CommandResult& result);
void add_run_command(CLI::App& app, CommandResult& result);
void add_bench_command(CLI::App& app, CommandResult& result);
void add_decode_command(CLI::App& app, CommandResult& result);
void add_merge_command(CLI::App& app, CommandResult& result);
void add_sweep_command(CLI::App& app, CommandResult& result);
void add_view_command(CLI::App& app, CommandResult& result);
void add_pd_command(CLI::App& app, CommandResult& result);
void add_score_command(CLI::App& app, CommandResult& result);
void add_roc_command(CLI::App& app, CommandResult& result);
void add_studio_command(CLI::App& app, CommandResult& result);
void add_detect_command(CLI::App& app, CommandResult& result);

}  // namespace owsim::cli

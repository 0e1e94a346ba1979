#include "cli/commands.hpp"
namespace owsim::cli {
void add_pattern_command(CLI::App& app, CommandResult&) { app.add_subcommand("pattern", "one frame's pulse table as CSV"); }
}

#include "cli/commands.hpp"
namespace owsim::cli {
void add_info_command(CLI::App& app, CommandResult&) { app.add_subcommand("info", "what a recording holds, checked"); }
}

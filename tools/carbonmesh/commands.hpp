#pragma once
// Each subcommand registers itself on the app and returns the action to run after parsing.
#include <CLI/CLI.hpp>
#include <functional>

namespace carbonmesh::cli {

using Action = std::function<int()>;

// Registers a subcommand; `action` is set to its run function when it is selected.
void add_stats_command(CLI::App& app, Action& action);
void add_shape_command(CLI::App& app, Action& action);
void add_analyze_command(CLI::App& app, Action& action);
void add_build_command(CLI::App& app, Action& action);
void add_remesh_command(CLI::App& app, Action& action);
void add_simulate_command(CLI::App& app, Action& action);
// `help [TOPIC]`: a command's options with defaults and units, all commands, or a topic page.
void add_help_command(CLI::App& app, Action& action);

}  // namespace carbonmesh::cli

// commands.h: each subcommand of `vgeo` registers itself on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>

namespace vgeo {

void addBuildCommand(CLI::App& app, int& exitCode);
void addCheckCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);

}  // namespace vgeo

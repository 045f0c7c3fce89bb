// check_command.cpp: `vgeo check FILE.vgeo`, the invariant checker's command line.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "../reference/cut.h"
#include "commands.h"

namespace vgeo {

void addCheckCommand(CLI::App& app, int& exitCode) {
  auto* cmd =
      app.add_subcommand("check", "Load a .vgeo and verify the invariants of docs/design.md on random LOD cuts");
  auto path = std::make_shared<std::string>();
  auto options = std::make_shared<CheckOptions>();
  cmd->add_option("file", *path, ".vgeo file")->required();
  cmd->add_option("--cuts", options->cuts, "Random (camera, tau) cuts per geometry")
      ->capture_default_str()
      ->check(CLI::Range(0u, 1u << 20));
  cmd->add_option("--seed", options->seed, "Seed of the random cuts")->capture_default_str();
  cmd->callback([path, options, &exitCode] {
    VgeoData data = readVgeo(*path);
    CheckResult result = checkVgeo(data, *options);
    if (!result.ok) {
      std::fprintf(stderr, "%s: %s\n", path->c_str(), result.firstViolation.c_str());
      exitCode = 1;
      return;
    }
    std::printf("%s: %s\n", path->c_str(), result.summary.c_str());
    exitCode = 0;
  });
}

}  // namespace vgeo

// main.cpp: the `vgeo` executable: `vgeo build`, `vgeo check`, `vgeo render`, `vgeo bench` (later `view`).
// Every error ends here as one line on stderr and a non-zero exit.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{"vgeo: a virtual-geometry builder and renderer"};
  app.require_subcommand(1);
  int exitCode = 1;
  vgeo::addBuildCommand(app, exitCode);
  vgeo::addCheckCommand(app, exitCode);
  vgeo::addRenderCommand(app, exitCode);
  vgeo::addBenchCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "vgeo: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return exitCode;
}

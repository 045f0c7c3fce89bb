// main.cpp: the `vgeo` executable: `vgeo build`, `vgeo check`, `vgeo render`, `vgeo bench`.
// Every error ends here as one line on stderr and an exit code of options.h's ExitCode: the cause
// decides the code, so scripts can tell a bad command line from a bad file from a machine limit.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include "../common/atomic_file.h"
#include "../common/input_error.h"
#include "commands.h"
#include "options.h"
#include "vgeo_commit.h"

namespace {

// Large blocks on 2 MB pages. The build fills and gathers from arrays of tens to hundreds of
// megabytes (positions, graphs, sorted edges, the hash set of edges): on 4 KB pages each gather
// misses the TLB and each 4 KB first touched is a page fault. Where the kernel hands transparent huge
// pages only to memory that asks for them ("madvise", Debian's default), glibc asks for them when its
// hugetlb tunable is set, and it reads tunables once, at start: so the process starts itself again
// with the tunable added. A hugetlb tunable already set, to any value, is left as it is.
void restartWithHugePages(char** argv) {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return;
  std::ifstream policy("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(policy, line) || line.find("[madvise]") == std::string::npos) return;
  const std::string before = tunables ? tunables : "";
  const std::string with = before.empty() ? "glibc.malloc.hugetlb=1" : before + ":glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", with.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not restarted: go on as started.
  if (tunables)
    setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
}

}  // namespace

int main(int argc, char** argv) {
  restartWithHugePages(argv);
  CLI::App app{"vgeo: a virtual-geometry builder and renderer"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("vgeo " VGEO_VERSION " (commit " VGEO_COMMIT ")"));
  app.footer(
      "Exit codes: 0 done; 1 a bad or unreadable input file, an output that could not be written, or a failed check; "
      "2 a bad command line; 3 validation messages (--validate); 4 the GPU cut differs from the CPU's (--compare-cpu); "
      "5 no usable device, out of memory, or a frame past its memory limit.");
  // CLI11's own errors as one line too, like every other error.
  app.failure_message(
      [](const CLI::App*, const CLI::Error& e) { return std::string("vgeo: ") + e.what() + " (see --help)\n"; });
  int exitCode = vgeo::kExitBadFile;
  vgeo::addBuildCommand(app, exitCode);
  vgeo::addCheckCommand(app, exitCode);
  vgeo::addRenderCommand(app, exitCode);
  vgeo::addViewCommand(app, exitCode);
  vgeo::addBenchCommand(app, exitCode);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" of code 0; every other parse error is a usage error.
    const int code = app.exit(e);
    return code == 0 ? vgeo::kExitOk : vgeo::kExitUsage;
  } catch (const vgeo::UsageError& e) {
    std::fprintf(stderr, "vgeo: %s\n", e.what());
    return vgeo::kExitUsage;
  } catch (const vgeo::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return vgeo::kExitBadFile;
  } catch (const vgeo::OutputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return vgeo::kExitBadFile;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "vgeo: out of memory\n");
    return vgeo::kExitResources;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vgeo: %s\n", e.what());
    return vgeo::kExitResources;
  }
  return exitCode;
}

// options.h: what every subcommand checks on its command line before any work, and the exit codes.
// A bad value or output path is a usage error, reported as "vgeo: --option: cause" with exit code 2,
// never as a fault of the input file and never after minutes of work.
#pragma once

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "../renderer/camera.h"

namespace vgeo {

// Exit codes of `vgeo` (README, "Exit codes").
enum ExitCode : int {
  kExitOk = 0,
  kExitBadFile = 1,     // an input file is bad or unreadable, an output could not be written, check found a violation
  kExitUsage = 2,       // a bad command line: unknown option, bad value, unusable output path
  kExitValidation = 3,  // --validate: the validation layer reported something
  kExitCutDiffers = 4,  // --compare-cpu: the GPU's draw list differs from the CPU reference cut
  kExitResources = 5,   // no usable Vulkan device, out of memory, a frame past its memory limit
};

struct UsageError : std::runtime_error {
  UsageError(const std::string& option, const std::string& cause) : std::runtime_error(option + ": " + cause) {}
};

// A finite number strictly between lo and hi (a CLI11 check).
inline CLI::Validator finiteBetween(double lo, double hi, bool closedLow = false) {
  return CLI::Validator(
      [lo, hi, closedLow](std::string& text) -> std::string {
        double v = 0.0;
        try {
          size_t used = 0;
          v = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (...) {
          return "'" + text + "' is not a number";
        }
        // Finite as the float it is stored in, too (--tau 1e39 became inf).
        if (!std::isfinite(v) || !std::isfinite(float(v)) || v > hi || v == hi || v < lo || (v == lo && !closedLow))
          return "'" + text + "' is out of range: needs a finite number " + (closedLow ? ">= " : "> ") +
                 CLI::detail::to_string(lo) + (std::isinf(hi) ? std::string() : " and < " + CLI::detail::to_string(hi));
        return std::string();
      },
      std::string("NUMBER in ") + (closedLow ? "[" : "(") + CLI::detail::to_string(lo) + ", " +
          CLI::detail::to_string(hi) + ")");
}

// "ex,ey,ez,tx,ty,tz": six finite numbers, eye apart from target.
inline Camera parseCameraOption(const std::string& option, const std::string& text, float fovYDegrees) {
  std::vector<double> v;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find(',', start);
    if (end == std::string::npos) end = text.size();
    std::string item = text.substr(start, end - start);
    try {
      size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (...) {
      throw UsageError(option,
                       "'" + item + "' is not a number (expected eye_x,eye_y,eye_z,target_x,target_y,target_z)");
    }
    start = end + 1;
  }
  if (v.size() != 6)
    throw UsageError(
        option, "expected six numbers eye_x,eye_y,eye_z,target_x,target_y,target_z, got " + std::to_string(v.size()));
  for (double x : v)
    if (!std::isfinite(x) || std::abs(x) > 1e30)
      throw UsageError(option, "every number must be finite (got " + text + ")");
  Camera c;
  c.eye = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
  c.target = glm::vec3(float(v[3]), float(v[4]), float(v[5]));
  c.fovYDegrees = fovYDegrees;
  if (!(glm::length(c.target - c.eye) > 0.0f)) throw UsageError(option, "the eye and the target are the same point");
  return c;
}

// "x,y,z", a direction: three finite numbers, not all zero.
inline glm::vec3 parseDirectionOption(const std::string& option, const std::string& text) {
  glm::vec3 d;
  char end = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &d.x, &d.y, &d.z, &end) != 3 || !std::isfinite(d.x) ||
      !std::isfinite(d.y) || !std::isfinite(d.z) || glm::length(d) == 0.0f)
    throw UsageError(option, "expected a direction x,y,z of three finite numbers, not all zero (got '" + text + "')");
  return d;
}

// An output path that can be written: its folder exists, it is new or a regular file (not a folder,
// link or device, which the atomic rename would replace), it is none of the inputs, and it ends in
// `extension` (case-insensitive) when one is given.
inline void checkOutputPath(const std::string& option, const std::string& path, const std::vector<std::string>& inputs,
                            const std::string& extension = "") {
  namespace fs = std::filesystem;
  if (path.empty()) throw UsageError(option, "empty path");
  if (!extension.empty()) {
    std::string ext = fs::path(path).extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    if (ext != extension) throw UsageError(option, path + ": the output is written as " + extension + "; name it so");
  }
  std::error_code ec;
  fs::path folder = fs::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (!fs::is_directory(folder, ec))
    throw UsageError(option, path + ": the folder " + folder.string() + " does not exist");
  if (::access(folder.c_str(), W_OK) != 0)
    throw UsageError(option, path + ": the folder " + folder.string() + " is not writable");
  const fs::file_status status = fs::symlink_status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw UsageError(option, path + (fs::is_directory(status)
                                         ? " is a folder"
                                         : " is not a regular file (a link or a device): it would be replaced"));
  // The same file whether or not it exists yet: an existing one by identity (links, hard links), a new one
  // by its folder's identity and its name (`-o new.vgeo --stats new.vgeo`, or ./new.vgeo).
  auto same = [&](const fs::path& a, const fs::path& b) {
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
    if (fs::exists(a, ec) != fs::exists(b, ec)) return false;
    const fs::path fa = a.parent_path().empty() ? "." : a.parent_path(),
                   fb = b.parent_path().empty() ? "." : b.parent_path();
    return a.filename() == b.filename() && fs::equivalent(fa, fb, ec);
  };
  for (const std::string& other : inputs)
    if (!other.empty() && same(path, other))
      throw UsageError(option, path + " is an input or another output of this command; it would be overwritten");
}

}  // namespace vgeo

// input_error.h: the one error type for bad input files: one line, "FILE: cause".
#pragma once

#include <stdexcept>
#include <string>

namespace vgeo {

struct InputError : std::runtime_error {
  InputError(const std::string& file, const std::string& cause) : std::runtime_error(file + ": " + cause) {}
};

}  // namespace vgeo

// atomic_file.h: output files that are either whole or absent (atomic_file.cpp).
#pragma once

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace vgeo {

// A failed write of an output file: one line, "FILE: cause".
struct OutputError : std::runtime_error {
  OutputError(const std::string& file, const std::string& cause) : std::runtime_error(file + ": " + cause) {}
};

// Writes go to a temporary file beside `path`; commit() flushes it to disk and renames it over `path`.
// Every write is checked (a full disk, a file size limit), so a failure throws OutputError at commit
// and removes the temporary file; so does destruction without commit. Nothing half-written is left.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(const void* data, size_t size);
  // Overwrites bytes already written, at `offset`; later writes still append.
  void writeAt(uint64_t offset, const void* data, size_t size);
  // Starts writing what was written since the last call to disk, without waiting for it: commit()'s
  // flush then overlaps the writes that follow instead of starting when they end.
  void startWriteback();
  void commit();

 private:
  std::string path_, temp_;
  std::FILE* file_ = nullptr;
  int error_ = 0;      // errno of the first failed write
  uint64_t sent_ = 0;  // bytes startWriteback() has sent on
};

// The whole of `bytes` to `path`, atomically.
void writeFileAtomically(const std::string& path, const std::string& bytes);

}  // namespace vgeo

// atomic_file.h: output files that are either whole or absent (atomic_file.cpp).
#pragma once

#include <atomic>
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
  // The temporary file, open for reading too: what writeAt wrote can be read back with pread.
  int descriptor() const { return ::fileno(file_); }
  // Starts sending the bytes at [offset, offset + size) to disk, without waiting for them: commit()'s
  // flush then overlaps the work that follows instead of starting when it ends.
  void startWriteback(uint64_t offset, uint64_t size);
  // Throws the OutputError that commit() would for a write that failed so far, removing the file.
  void throwIfFailed();
  void commit();

 private:
  std::string path_, temp_;
  std::FILE* file_ = nullptr;
  std::atomic<int> error_{0};  // errno of the first failed write (writeAt may run on several threads)
};

// The whole of `bytes` to `path`, atomically.
void writeFileAtomically(const std::string& path, const std::string& bytes);

}  // namespace vgeo

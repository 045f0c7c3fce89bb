// atomic_file.cpp: write to a temporary file beside the target, check every write, fsync, rename.
// The rename is atomic within a file system, so a reader sees the old file or the whole new one; the
// temporary file lives in the target's folder to stay on its file system.
#include "atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace vgeo {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  temp_ = path_ + ".tmp." + std::to_string(::getpid());
  file_ = std::fopen(temp_.c_str(), "wb");
  if (!file_) throw OutputError(path_, std::string("cannot write: ") + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(temp_.c_str());
  }
}

void AtomicFile::write(const void* data, size_t size) {
  if (error_ || size == 0) return;
  if (std::fwrite(data, 1, size, file_) != size) error_ = errno ? errno : EIO;
}

void AtomicFile::commit() {
  if (!error_ && std::fflush(file_) != 0) error_ = errno;
  if (!error_ && ::fsync(::fileno(file_)) != 0 && errno != EINVAL) error_ = errno;
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (!error_ && closed != 0) error_ = errno;
  if (error_) {
    std::remove(temp_.c_str());
    throw OutputError(path_, std::string("write failed: ") + std::strerror(error_));
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int e = errno;
    std::remove(temp_.c_str());
    throw OutputError(path_, std::string("cannot move the finished file into place: ") + std::strerror(e));
  }
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
  AtomicFile out(path);
  out.write(bytes.data(), bytes.size());
  out.commit();
}

}  // namespace vgeo

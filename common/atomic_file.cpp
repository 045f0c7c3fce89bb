// atomic_file.cpp: write to a temporary file beside the target, check every write, fsync, rename.
// The rename is atomic within a file system, so a reader sees the old file or the whole new one; the
// temporary file lives in the target's folder to stay on its file system. SIGINT and SIGTERM remove it
// before the process ends.
#include "atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>

namespace vgeo {
namespace {

// The temporary file being written, for the SIGINT/SIGTERM handler (one at a time: outputs are written
// one after another). A SIGKILL cannot be caught and may leave one behind.
char gTempPath[4096];
volatile sig_atomic_t gTempActive = 0;

void removeTempAndDie(int signal) {
  if (gTempActive) ::unlink(gTempPath);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void track(const std::string& temp) {
  static bool installed = false;
  if (!installed) {
    std::signal(SIGINT, removeTempAndDie);
    std::signal(SIGTERM, removeTempAndDie);
    // Past a file-size limit (ulimit -f) a write fails with EFBIG and the temporary file is removed;
    // SIGXFSZ's default would end the process and leave it.
    std::signal(SIGXFSZ, SIG_IGN);
    installed = true;
  }
  gTempActive = 0;
  std::snprintf(gTempPath, sizeof gTempPath, "%s", temp.c_str());
  gTempActive = temp.size() < sizeof gTempPath ? 1 : 0;
}

void untrack() { gTempActive = 0; }

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  // A new file of a name nobody can guess, never through a link: O_EXCL | O_NOFOLLOW, so that a link
  // planted at the temporary name (to a file outside the folder) fails the open instead of being
  // followed and overwritten; then another name is tried.
  std::random_device random;
  int fd = -1, error = 0;
  for (int attempt = 0; attempt < 16 && fd < 0; attempt++) {
    char suffix[16];
    std::snprintf(suffix, sizeof suffix, "%08x", unsigned(random()));
    temp_ = path_ + ".tmp." + std::to_string(::getpid()) + "." + suffix;
    track(temp_);
    fd = ::open(temp_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    error = errno;
    if (fd < 0) untrack();
    if (fd < 0 && error != EEXIST) break;
  }
  if (fd >= 0) file_ = ::fdopen(fd, "w+b");  // readable: see descriptor()
  if (!file_) {
    if (fd >= 0) {
      error = errno;
      ::close(fd);
      ::unlink(temp_.c_str());
      untrack();
    }
    throw OutputError(path_, std::string("cannot write: ") + std::strerror(error));
  }
}

AtomicFile::~AtomicFile() {
  if (file_) {
    std::fclose(file_);
    std::remove(temp_.c_str());
  }
  untrack();
}

void AtomicFile::write(const void* data, size_t size) {
  if (error_ || size == 0) return;
  if (std::fwrite(data, 1, size, file_) != size) error_ = errno ? errno : EIO;
}

void AtomicFile::writeAt(uint64_t offset, const void* data, size_t size) {
  if (error_ || size == 0) return;
  if (std::fflush(file_) != 0) {
    error_ = errno ? errno : EIO;
    return;
  }
  const uint8_t* p = static_cast<const uint8_t*>(data);
  while (size > 0) {
    const ssize_t n = ::pwrite(::fileno(file_), p, size, off_t(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error_ = n < 0 ? errno : EIO;
      return;
    }
    p += n, size -= size_t(n), offset += uint64_t(n);
  }
}

void AtomicFile::startWriteback(uint64_t offset, uint64_t size) {
  // Only a hint: where the system cannot, fsync in commit() writes it all the same.
  if (!error_ && size > 0) ::sync_file_range(::fileno(file_), off_t(offset), off_t(size), SYNC_FILE_RANGE_WRITE);
}

void AtomicFile::throwIfFailed() {
  if (!error_) return;
  if (file_) std::fclose(file_);
  file_ = nullptr;
  std::remove(temp_.c_str());
  untrack();
  throw OutputError(path_, std::string("write failed: ") + std::strerror(error_));
}

void AtomicFile::commit() {
  if (!error_ && std::fflush(file_) != 0) error_ = errno;
  if (!error_ && ::fsync(::fileno(file_)) != 0 && errno != EINVAL) error_ = errno;
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (!error_ && closed != 0) error_ = errno;
  throwIfFailed();
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int e = errno;
    std::remove(temp_.c_str());
    untrack();
    throw OutputError(path_, std::string("cannot move the finished file into place: ") + std::strerror(e));
  }
  untrack();
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
  AtomicFile out(path);
  out.write(bytes.data(), bytes.size());
  out.commit();
}

}  // namespace vgeo

// load.cpp: picks the reader for a mesh file by its extension, and reads whole files.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "../common/parallel.h"
#include "text_reader.h"

namespace vgeo {

FillLaterVector<char> readWholeFile(const std::string& path, int threads) {
  // O_NONBLOCK: opening a FIFO waits for a writer otherwise; it is refused below like any non-file.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  // Only regular files: a device (a link to /dev/zero) or a FIFO never ends or never starts.
  struct stat status = {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) throw InputError(path, "not a regular file");
  // A regular file is read at its size, in pieces side by side: each thread first touches the pages
  // it reads into (zeroing a fresh gigabyte on one thread takes half a second).
  if (status.st_size > 0) {
    const size_t size = size_t(status.st_size);
    constexpr size_t kPiece = size_t(2) << 20;  // small enough that a file of tens of MB uses every thread
    FillLaterVector<char> data(size);
    int error = 0;
    bool shorter = false;
    parallelFor((size + kPiece - 1) / kPiece, threads, [&](size_t k) {
      for (size_t at = k * kPiece, end = std::min(size, at + kPiece); at < end;) {
        const ssize_t n = ::pread(fd, data.data() + at, end - at, off_t(at));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) __atomic_store_n(&error, errno, __ATOMIC_RELAXED);
        if (n == 0) __atomic_store_n(&shorter, true, __ATOMIC_RELAXED);
        if (n <= 0) return;
        at += size_t(n);
      }
    });
    if (error) throw InputError(path, std::string("read error: ") + std::strerror(error));
    char next = 0;
    if (!shorter && ::pread(fd, &next, 1, off_t(size)) == 0) return data;
    ::lseek(fd, 0, SEEK_SET);  // it changed while read: read it as a stream
  }
  // A file that reports no size (procfs) or changed while read: as a stream, up to what a mesh file may be.
  constexpr size_t kMaxStreamed = size_t(16) << 30;
  FillLaterVector<char> data;
  std::vector<char> buffer(size_t(1) << 16);
  for (;;) {
    const ssize_t n = ::read(fd, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (data.size() > kMaxStreamed) throw InputError(path, "grows past 16 GiB while it is read");
    if (n < 0) throw InputError(path, std::string("read error: ") + std::strerror(errno));
    if (n == 0) return data;
    data.insert(data.end(), buffer.begin(), buffer.begin() + n);
  }
}

SourceScene singleMeshScene(PolygonMesh mesh) {
  SourceScene scene;
  scene.meshes.push_back(std::move(mesh));
  scene.meshNames.push_back("mesh");
  scene.instances.push_back({});
  return scene;
}

std::vector<std::string_view> linePieces(std::string_view text, int threads, int minPieceLog2) {
  const size_t count =
      std::max<size_t>(1, std::min<size_t>(size_t(std::max(threads, 1)) * 4, text.size() >> minPieceLog2));
  std::vector<size_t> bounds{0};
  for (size_t k = 1; k < count; k++) {
    const size_t at = text.find('\n', std::max(bounds.back(), text.size() * k / count));
    if (at == std::string_view::npos) break;
    if (at + 1 > bounds.back() && at + 1 < text.size()) bounds.push_back(at + 1);
  }
  bounds.push_back(text.size());
  std::vector<std::string_view> pieces;
  for (size_t k = 0; k + 1 < bounds.size(); k++) pieces.push_back(text.substr(bounds[k], bounds[k + 1] - bounds[k]));
  return pieces;
}

SourceScene loadMeshFile(const std::string& path, int threads) {
  std::string ext = path.substr(path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".obj") return loadObj(path, threads);
  if (ext == ".off") return loadOff(path, threads);
  if (ext == ".ply") return loadPly(path);
  if (ext == ".gltf" || ext == ".glb") return loadGltf(path);
  throw InputError(path, "unknown mesh format '" + ext + "' (expected .obj, .off, .ply, .gltf or .glb)");
}

}  // namespace vgeo

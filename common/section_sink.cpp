// section_sink.cpp: a .vgeo's sections kept in memory or spooled to disk (section_sink.h).
#include "section_sink.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "atomic_file.h"
#include "parallel.h"
#include "vgeo_head.h"

namespace vgeo {
namespace {

constexpr size_t kSpoolBuffer = size_t(1) << 20;  // bytes a section collects before a write
constexpr size_t kCopyChunk = size_t(4) << 20;    // bytes read back at a time by commit() to copy
constexpr size_t kSumChunk = size_t(1) << 20;     // and by each thread to checksum

// A temporary file in `folder` that no name leads to: O_TMPFILE where the file system has it, else a
// named file unlinked at once.
int anonymousFile(const std::string& folder, const std::string& path) {
  int fd = -1;
#ifdef O_TMPFILE
  fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (fd >= 0) return fd;
#endif
  std::string name = folder + "/.vgeo-section-XXXXXX";
  fd = ::mkstemp(name.data());
  if (fd < 0) throw OutputError(path, std::string("cannot write a temporary file beside it: ") + std::strerror(errno));
  ::unlink(name.c_str());
  return fd;
}

// The first `bytes` of spool `fd` read back a buffer's size at a time, each piece handed to
// use(data, size); returns 0, or the errno of a failed read (EIO where the spool is shorter).
template <class Use>
int readBack(int fd, uint64_t bytes, std::vector<uint8_t>& buffer, Use&& use) {
  for (uint64_t at = 0; at < bytes;) {
    const ssize_t n = ::pread(fd, buffer.data(), size_t(std::min<uint64_t>(buffer.size(), bytes - at)), off_t(at));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return n < 0 ? errno : EIO;
    use(buffer.data(), size_t(n));
    at += uint64_t(n);
  }
  return 0;
}

}  // namespace

uint32_t sectionElementSize(Section s) {
#define VGEO_SECTION_SIZE(id, member, type, values, name) uint32_t(sizeof(type) * values),
  static const uint32_t sizes[] = {0, VGEO_SECTIONS(VGEO_SECTION_SIZE)};
#undef VGEO_SECTION_SIZE
  return sizes[uint32_t(s)];
}

VgeoDataSink::VgeoDataSink(VgeoData& data) : data_(data) {
#define VGEO_SECTION_COUNT(id, member, type, values, name) \
  counts_[uint32_t(Section::id) - 1] = data.member.size() / values;
  VGEO_SECTIONS(VGEO_SECTION_COUNT)
#undef VGEO_SECTION_COUNT
}

void VgeoDataSink::write(Section s, const void* data, uint64_t count) {
  switch (s) {
#define VGEO_SECTION_APPEND(id, member, type, values, name)                   \
  case Section::id: {                                                         \
    const type* p = static_cast<const type*>(data);                           \
    data_.member.insert(data_.member.end(), p, p + size_t(count) * (values)); \
    break;                                                                    \
  }
    VGEO_SECTIONS(VGEO_SECTION_APPEND)
#undef VGEO_SECTION_APPEND
    default:
      break;
  }
}

VgeoFileSink::VgeoFileSink(std::string path) : path_(std::move(path)), spools_(uint32_t(Section::Count_) - 1) {
  const size_t slash = path_.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path_.substr(0, slash);
  for (Spool& spool : spools_) spool.fd = anonymousFile(folder, path_);
}

VgeoFileSink::~VgeoFileSink() {
  for (Spool& spool : spools_)
    if (spool.fd >= 0) ::close(spool.fd);
}

void VgeoFileSink::flush(Spool& spool) {
  const uint8_t* p = spool.buffer.data();
  size_t left = spool.buffer.size();
  while (left > 0) {
    const ssize_t n = ::write(spool.fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw OutputError(path_, std::string("write failed: ") + std::strerror(n < 0 ? errno : EIO));
    p += n, left -= size_t(n);
  }
  spool.buffer.clear();
}

void VgeoFileSink::write(Section s, const void* data, uint64_t count) {
  Spool& spool = spools_[uint32_t(s) - 1];
  const uint8_t* p = static_cast<const uint8_t*>(data);
  size_t bytes = size_t(count) * sectionElementSize(s);
  if (spool.buffer.capacity() < kSpoolBuffer) spool.buffer.reserve(kSpoolBuffer);
  while (bytes > 0) {
    const size_t take = std::min(bytes, kSpoolBuffer - spool.buffer.size());
    spool.buffer.insert(spool.buffer.end(), p, p + take);
    p += take, bytes -= take;
    if (spool.buffer.size() == kSpoolBuffer) flush(spool);
  }
}

void VgeoFileSink::commit(int threads) {
  std::vector<VgeoEntry> entries(spools_.size());
  for (uint32_t i = 0; i < entries.size(); i++) {
    flush(spools_[i]);
    std::vector<uint8_t>().swap(spools_[i].buffer);
    entries[i] = {i + 1, sectionElementSize(Section(i + 1)), 0, counts_[i], 0};
  }
  const uint64_t fileSize = placeVgeoSections(entries);
  // The sections are copied in on one thread (the system takes writes to one file one at a time),
  // each chunk sent on to the disk once written, while the others take their checksums, a section a
  // thread (each reading its spool back). The header and table, which hold the checksums, go first
  // into the file but are written last.
  auto failed = [&](int error) {
    return OutputError(path_, std::string("cannot read back a section: ") + std::strerror(error));
  };
  AtomicFile out(path_);
  int readError = 0;
  std::vector<uint8_t> summed(entries.size(), 0);  // a spool the copy may close once its sum is taken
  auto sum = [&] {
    parallelFor(entries.size(), threads, [&](size_t i) {
      const uint64_t bytes = entries[i].count * entries[i].elementSize;
      std::vector<uint8_t> chunk(size_t(std::min<uint64_t>(kSumChunk, bytes)));
      VgeoChecksum sum(bytes);
      if (const int error = readBack(spools_[i].fd, bytes, chunk, [&](const uint8_t* p, size_t n) { sum.add(p, n); }))
        __atomic_store_n(&readError, error, __ATOMIC_RELAXED);
      entries[i].checksum = sum.finish();
      __atomic_store_n(&summed[i], uint8_t(1), __ATOMIC_RELEASE);
    });
  };
  auto copy = [&] {
    std::vector<uint8_t> chunk(kCopyChunk, 0);
    uint64_t written = kVgeoHeaderSize + kVgeoEntrySize * entries.size();
    out.write(chunk.data(), size_t(written));
    for (uint32_t i = 0; i < entries.size(); i++) {
      static const uint8_t zeros[16] = {};
      if (entries[i].offset > written) out.write(zeros, size_t(entries[i].offset - written));
      const uint64_t bytes = entries[i].count * entries[i].elementSize;
      if (const int error = readBack(spools_[i].fd, bytes, chunk, [&](const uint8_t* p, size_t n) {
            out.write(p, n);
            out.startWriteback();
          }))
        throw failed(error);
      written = entries[i].offset + bytes;
      if (__atomic_load_n(&summed[i], __ATOMIC_ACQUIRE)) {
        ::close(spools_[i].fd);  // its disk space back before the next section is copied
        spools_[i].fd = -1;
      }
    }
  };
  withThreads(threads, [&] { parallelInvoke(threads > 1, copy, sum); });
  if (readError) throw failed(readError);
  const std::vector<uint8_t> head = vgeoHead(entries, fileSize);
  out.writeAt(0, head.data(), head.size());
  out.commit();
}

}  // namespace vgeo

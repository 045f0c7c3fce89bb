// section_sink.cpp: a .vgeo's sections kept in memory or written to disk as they come (section_sink.h).
#include "section_sink.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>

#include "atomic_file.h"
#include "parallel.h"
#include "vgeo_head.h"

namespace vgeo {
namespace {

constexpr size_t kSpoolBuffer = size_t(1) << 20;  // bytes a section collects before a write
constexpr size_t kCopyChunk = size_t(4) << 20;    // bytes read back at a time to copy a spool into place
constexpr size_t kSumChunk = size_t(1) << 20;     // and by each thread to checksum the file's sections
constexpr size_t kBuffersInFlight = 8;            // full buffers the writers may lag behind: bounds the memory
// Writer threads of a sink of `threads`: none on one (each write done at once), one on up to seven (a
// thread summing and writing keeps up with a few builders), then one more for each four threads, to
// four (a section is one thread's at a time; most bytes are in four or five sections).
int writerThreads(int threads) { return threads <= 1 ? 0 : std::clamp(threads / 4, 1, 4); }

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

// The `bytes` at `offset` of file `fd` (a spool, or the output) read back a buffer's size at a time,
// each piece handed to use(data, size); returns 0, or the errno of a failed read (EIO where the file is
// shorter). Several threads may read one file at once.
template <class Use>
int readBack(int fd, uint64_t offset, uint64_t bytes, std::vector<uint8_t>& buffer, Use&& use) {
  for (uint64_t at = 0; at < bytes;) {
    const ssize_t n =
        ::pread(fd, buffer.data(), size_t(std::min<uint64_t>(buffer.size(), bytes - at)), off_t(offset + at));
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

void SectionSink::expectTotal(Section s, uint64_t total) {
  const uint32_t i = uint32_t(s) - 1;
  if (total < counts_[i] || (totals_[i] != kUnknown && totals_[i] != total))
    throw std::logic_error("a .vgeo section's expected total is below its count or changed");
  if (totals_[i] == total) return;
  totals_[i] = total;
  expected(s);
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

void VgeoDataSink::expected(Section s) {
  switch (s) {
#define VGEO_SECTION_RESERVE(id, member, type, values, name)                     \
  case Section::id:                                                              \
    data_.member.reserve(size_t(totals_[uint32_t(Section::id) - 1]) * (values)); \
    break;
    VGEO_SECTIONS(VGEO_SECTION_RESERVE)
#undef VGEO_SECTION_RESERVE
    default:
      break;
  }
}

// Each write: the bytes added to their section's checksum (where it is taken as written), written at
// their offset and sent on to the disk. Threaded, the buffers go to the writer threads and the caller
// gets an empty one back (a recycled one, or a new one while fewer than kBuffersInFlight are out; else
// it waits for one); otherwise each write is done at once. A spool's copy into place is a job like the
// others. A free thread takes the oldest job of a section no other thread is writing, so that a
// section's bytes reach its checksum in order while other sections are summed and written beside it.
class VgeoFileSink::Writer {
 public:
  Writer(AtomicFile& out, int threads) : out_(out) {
    for (int i = 0; i < threads; i++) threads_.emplace_back([this] { run(); });
  }
  ~Writer() { finish(); }
  // Takes the bytes of `buffer` (of section `section`), leaving it empty.
  void write(uint32_t section, std::vector<uint8_t>& buffer, uint64_t offset, VgeoChecksum* sum) {
    if (threads_.empty()) {
      perform(buffer, offset, sum);
      buffer.clear();
      return;
    }
    std::vector<uint8_t> next;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return !free_.empty() || buffers_ < kBuffersInFlight; });
      if (!free_.empty()) {
        next = std::move(free_.back());
        free_.pop_back();
      } else {
        buffers_++;
      }
      jobs_.push_back({section, std::move(buffer), offset, sum});
    }
    changed_.notify_all();
    if (next.capacity() < kSpoolBuffer) next.reserve(kSpoolBuffer);
    buffer = std::move(next);
  }
  // Copies the first `bytes` of spool `fd` to `offset` (summed into `sum` where given) and closes it.
  void copy(uint32_t section, int fd, uint64_t bytes, uint64_t offset, VgeoChecksum* sum) {
    if (threads_.empty()) {
      performCopy(fd, bytes, offset, sum);
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      jobs_.push_back({section, {}, offset, sum, fd, bytes});
    }
    changed_.notify_all();
  }
  // The errno of the first spool that could not be read back, or 0; read once every job is done.
  int readError() const { return readError_; }
  // Waits for every write given so far.
  void finish() {
    if (threads_.empty()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    for (std::thread& t : threads_) t.join();
    threads_.clear();
  }

 private:
  struct Job {
    uint32_t section;
    std::vector<uint8_t> bytes;
    uint64_t offset;
    VgeoChecksum* sum;
    int spool = -1;  // a copy's spool, whose first spoolBytes are the bytes instead
    uint64_t spoolBytes = 0;
  };
  void perform(const std::vector<uint8_t>& bytes, uint64_t offset, VgeoChecksum* sum) {
    if (sum) sum->add(bytes.data(), bytes.size());
    out_.writeAt(offset, bytes.data(), bytes.size());
    out_.startWriteback(offset, bytes.size());
  }
  void performCopy(int fd, uint64_t bytes, uint64_t offset, VgeoChecksum* sum) {
    std::vector<uint8_t> chunk(size_t(std::min<uint64_t>(kCopyChunk, bytes)));
    uint64_t at = offset;
    const int error = readBack(fd, 0, bytes, chunk, [&](const uint8_t* p, size_t n) {
      if (sum) sum->add(p, n);
      out_.writeAt(at, p, n);
      at += n;
    });
    if (error) {
      int none = 0;
      __atomic_compare_exchange_n(&readError_, &none, error, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED);
    }
    out_.startWriteback(offset, bytes);
    ::close(fd);  // its disk space back
  }
  // The oldest job whose section no thread is writing, or jobs_.end().
  std::deque<Job>::iterator takeable() {
    return std::find_if(jobs_.begin(), jobs_.end(), [&](const Job& j) { return !(writing_ >> j.section & 1u); });
  }
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      auto job = jobs_.end();
      changed_.wait(lock, [&] { return (job = takeable()) != jobs_.end() || (stop_ && jobs_.empty()); });
      if (job == jobs_.end()) return;  // stopped, every job taken
      Job taken = std::move(*job);
      jobs_.erase(job);
      writing_ |= uint64_t(1) << taken.section;
      lock.unlock();
      if (taken.spool >= 0)
        performCopy(taken.spool, taken.spoolBytes, taken.offset, taken.sum);
      else
        perform(taken.bytes, taken.offset, taken.sum);
      taken.bytes.clear();
      lock.lock();
      writing_ &= ~(uint64_t(1) << taken.section);
      if (taken.spool < 0) free_.push_back(std::move(taken.bytes));
      changed_.notify_all();
    }
  }
  AtomicFile& out_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  std::vector<std::vector<uint8_t>> free_;
  size_t buffers_ = 0;    // made for the threads so far
  uint64_t writing_ = 0;  // a bit a section being written by a thread now
  static_assert(uint32_t(Section::Count_) - 1 <= 64, "a bit a section");
  bool stop_ = false;
  int readError_ = 0;  // written by the threads, read after finish()
  std::vector<std::thread> threads_;
};

VgeoFileSink::VgeoFileSink(std::string path, int threads)
    : path_(std::move(path)), threads_(std::max(threads, 1)), spools_(kSections) {
  const size_t slash = path_.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path_.substr(0, slash);
  for (Spool& spool : spools_) spool.fd = anonymousFile(folder, path_);
}

VgeoFileSink::~VgeoFileSink() {
  writer_.reset();  // before the file it writes to
  for (Spool& spool : spools_)
    if (spool.fd >= 0) ::close(spool.fd);
}

void VgeoFileSink::flush(uint32_t section) {
  Spool& spool = spools_[section];
  if (spool.buffer.empty()) return;
  const size_t bytes = spool.buffer.size();
  if (section < placed_) {
    if (spool.sent == 0 && totals_[section] != kUnknown && !spool.sum)
      spool.sum.emplace(totals_[section] * sectionElementSize(Section(section + 1)));
    writer_->write(section, spool.buffer, spool.offset + spool.sent, spool.sum ? &*spool.sum : nullptr);
  } else {
    const uint8_t* p = spool.buffer.data();
    size_t left = bytes;
    while (left > 0) {
      const ssize_t n = ::write(spool.fd, p, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw OutputError(path_, std::string("write failed: ") + std::strerror(n < 0 ? errno : EIO));
      p += n, left -= size_t(n);
    }
    spool.buffer.clear();
  }
  spool.sent += bytes;
}

void VgeoFileSink::write(Section s, const void* data, uint64_t count) {
  const uint32_t section = uint32_t(s) - 1;
  Spool& spool = spools_[section];
  const uint8_t* p = static_cast<const uint8_t*>(data);
  size_t bytes = size_t(count) * sectionElementSize(s);
  if (spool.buffer.capacity() < kSpoolBuffer) spool.buffer.reserve(kSpoolBuffer);
  while (bytes > 0) {
    const size_t take = std::min(bytes, kSpoolBuffer - spool.buffer.size());
    spool.buffer.insert(spool.buffer.end(), p, p + take);
    p += take, bytes -= take;
    if (spool.buffer.size() == kSpoolBuffer) flush(section);
  }
}

void VgeoFileSink::expected(Section) { place(); }

// Places the sections that follow the last placed one while the total of each section before them is
// known, in file order, each 16-byte aligned after the header and table (placeVgeoSections); what a
// section's spool holds is copied into place (and summed, where its total is known) by the writer,
// which then closes the spool: the caller goes on meanwhile.
void VgeoFileSink::place() {
  while (placed_ < kSections) {
    uint64_t end = vgeoTableEnd(kSections);  // of the last placed section
    if (placed_ > 0) {
      const uint32_t last = placed_ - 1;
      if (totals_[last] == kUnknown) return;  // it may still grow
      end = spools_[last].offset + totals_[last] * sectionElementSize(Section(last + 1));
    }
    if (!out_) {
      out_ = std::make_unique<AtomicFile>(path_);
      writer_ = std::make_unique<Writer>(*out_, writerThreads(threads_));
    }
    Spool& spool = spools_[placed_];
    spool.offset = vgeoSectionStart(end);
    static const uint8_t zeros[16] = {};
    out_->writeAt(end, zeros, size_t(spool.offset - end));
    if (totals_[placed_] != kUnknown) spool.sum.emplace(totals_[placed_] * sectionElementSize(Section(placed_ + 1)));
    writer_->copy(placed_, spool.fd, spool.sent, spool.offset, spool.sum ? &*spool.sum : nullptr);
    spool.fd = -1;
    placed_++;
  }
}

void VgeoFileSink::commit() {
  // Every total is now the count; what is not placed yet is copied into place.
  for (uint32_t i = 0; i < kSections; i++)
    if (totals_[i] == kUnknown) totals_[i] = counts_[i];
  place();
  std::vector<VgeoEntry> entries(kSections);
  for (uint32_t i = 0; i < kSections; i++) {
    if (counts_[i] != totals_[i]) throw std::logic_error("a .vgeo section ended short of its expected total");
    flush(i);
    entries[i] = {i + 1, sectionElementSize(Section(i + 1)), 0, counts_[i], 0};
  }
  writer_->finish();
  if (const int error = writer_->readError())
    throw OutputError(path_, std::string("cannot read back a section: ") + std::strerror(error));
  for (Spool& spool : spools_) std::vector<uint8_t>().swap(spool.buffer);
  const uint64_t fileSize = placeVgeoSections(entries);
  for (uint32_t i = 0; i < kSections; i++)
    if (entries[i].offset != spools_[i].offset) throw std::logic_error("a .vgeo section was placed out of order");
  out_->throwIfFailed();  // a full disk, say: its cause, not the read back it cut short
  // The checksums not taken as written, a section a thread, read back while the disk takes what was
  // sent to it; the header and table, which hold them, go first into the file but are written last.
  int readError = 0;
  withThreads(threads_, [&] {
    parallelFor(entries.size(), threads_, [&](size_t i) {
      if (spools_[i].sum) {
        entries[i].checksum = spools_[i].sum->finish();
        return;
      }
      const uint64_t bytes = entries[i].count * entries[i].elementSize;
      std::vector<uint8_t> chunk(size_t(std::min<uint64_t>(kSumChunk, bytes)));
      VgeoChecksum sum(bytes);
      if (const int error = readBack(out_->descriptor(), entries[i].offset, bytes, chunk,
                                     [&](const uint8_t* p, size_t n) { sum.add(p, n); }))
        __atomic_store_n(&readError, error, __ATOMIC_RELAXED);
      entries[i].checksum = sum.finish();
    });
  });
  if (readError) throw OutputError(path_, std::string("cannot read back a section: ") + std::strerror(readError));
  const std::vector<uint8_t> head = vgeoHead(entries, fileSize);
  out_->writeAt(0, head.data(), head.size());
  out_->commit();
}

}  // namespace vgeo

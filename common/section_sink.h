// section_sink.h: where the builder's layout puts a .vgeo's arrays as it makes them (section_sink.cpp):
// a VgeoData in memory, or the file itself, each section written to disk as it comes, so that a large
// build never holds its whole file (it was as large as the rest of the build's memory together).
#pragma once

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "atomic_file.h"
#include "vgeo_file.h"
#include "vgeo_head.h"

namespace vgeo {

// The bytes of one element of section s: its type's size times its values (VGEO_SECTIONS).
uint32_t sectionElementSize(Section s);

class SectionSink {
 public:
  SectionSink() { std::fill(totals_, totals_ + kSections, kUnknown); }
  virtual ~SectionSink() = default;
  // Appends `count` elements of section s; throws std::logic_error where that passes the total
  // expectTotal gave the section.
  void append(Section s, const void* data, uint64_t count) {
    uint64_t& n = counts_[uint32_t(s) - 1];
    if (count > totals_[uint32_t(s) - 1] - n) throw std::logic_error("a .vgeo section grew past its expected total");
    if (count) write(s, data, count);
    n += count;
  }
  // Appends a whole array; its bytes are a whole number of the section's elements.
  template <class T, class Allocator>
  void append(Section s, const std::vector<T, Allocator>& v) {
    append(s, v.data(), v.size() * sizeof(T) / sectionElementSize(s));
  }
  // Elements appended to section s so far (the index the next one gets).
  uint64_t count(Section s) const { return counts_[uint32_t(s) - 1]; }
  // Section s ends with exactly `total` elements (at least its count so far): a file sink that knows
  // every section before s in the file writes s straight to its place from then on (VgeoFileSink).
  void expectTotal(Section s, uint64_t total);

 protected:
  static constexpr uint32_t kSections = uint32_t(Section::Count_) - 1;
  static constexpr uint64_t kUnknown = UINT64_MAX;
  virtual void write(Section s, const void* data, uint64_t count) = 0;
  virtual void expected(Section) {}  // totals_ has one more section's total
  uint64_t counts_[kSections] = {};
  uint64_t totals_[kSections];  // kUnknown until expected
};

// Appends to the arrays of a VgeoData.
class VgeoDataSink : public SectionSink {
 public:
  explicit VgeoDataSink(VgeoData& data);

 private:
  void write(Section s, const void* data, uint64_t count) override;
  void expected(Section s) override;
  VgeoData& data_;
};

// The .vgeo file `path`, written atomically (atomic_file.h). A section goes straight to its place in
// the file once the totals of every section before it are known (expectTotal): each full buffer is
// added to the section's checksum, written and sent on to the disk, on writer threads of their own
// when the sink has `threads` > 1 (the appending thread then only fills buffers), each section's
// buffers in order. Until then a section goes to a temporary file of its own in path's folder,
// unlinked at once so that the system removes it however the process ends, and is copied into place
// when its place is known (at the latest, at commit). Write failures throw OutputError("path: cause").
class VgeoFileSink : public SectionSink {
 public:
  explicit VgeoFileSink(std::string path, int threads = 1);
  ~VgeoFileSink() override;
  VgeoFileSink(const VgeoFileSink&) = delete;
  VgeoFileSink& operator=(const VgeoFileSink&) = delete;
  // Places what is left, takes the checksums not taken as written (reading those sections back), writes
  // the header and table, and moves the file into place.
  void commit();

 private:
  struct Spool {
    int fd = -1;                      // the temporary file, until the section is placed
    uint64_t offset = 0;              // where the section starts in the file, once placed
    uint64_t sent = 0;                // bytes written out of the buffer so far
    std::vector<uint8_t> buffer;      // written out when full
    std::optional<VgeoChecksum> sum;  // taken as written, where its total was known at its first byte
  };
  class Writer;  // the writes into the file, each section's in order, on threads of their own or at once
  void write(Section s, const void* data, uint64_t count) override;
  void expected(Section s) override;
  void flush(uint32_t section);
  void place();
  std::string path_;
  int threads_;
  std::vector<Spool> spools_;
  std::unique_ptr<AtomicFile> out_;  // from the first section placed on
  std::unique_ptr<Writer> writer_;   // with out_
  uint32_t placed_ = 0;              // sections placed, in file order
};

}  // namespace vgeo

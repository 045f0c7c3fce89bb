// section_sink.h: where the builder's layout puts a .vgeo's arrays as it makes them (section_sink.cpp):
// a VgeoData in memory, or the file itself, each section spooled to disk as it comes, so that a large
// build never holds its whole file (it was as large as the rest of the build's memory together).
#pragma once

#include <string>
#include <vector>

#include "vgeo_file.h"

namespace vgeo {

// The bytes of one element of section s: its type's size times its values (VGEO_SECTIONS).
uint32_t sectionElementSize(Section s);

class SectionSink {
 public:
  virtual ~SectionSink() = default;
  // Appends `count` elements of section s.
  void append(Section s, const void* data, uint64_t count) {
    if (count) write(s, data, count);
    counts_[uint32_t(s) - 1] += count;
  }
  // Appends a whole array; its bytes are a whole number of the section's elements.
  template <class T>
  void append(Section s, const std::vector<T>& v) {
    append(s, v.data(), v.size() * sizeof(T) / sectionElementSize(s));
  }
  // Elements appended to section s so far (the index the next one gets).
  uint64_t count(Section s) const { return counts_[uint32_t(s) - 1]; }

 protected:
  virtual void write(Section s, const void* data, uint64_t count) = 0;
  uint64_t counts_[uint32_t(Section::Count_) - 1] = {};
};

// Appends to the arrays of a VgeoData.
class VgeoDataSink : public SectionSink {
 public:
  explicit VgeoDataSink(VgeoData& data);

 private:
  void write(Section s, const void* data, uint64_t count) override;
  VgeoData& data_;
};

// The .vgeo file `path`. Each section is written to a temporary file of its own in path's folder,
// unlinked at once, so that the system removes it however the process ends; commit() then writes the
// file atomically (atomic_file.h) from them. Write failures throw OutputError("path: cause").
class VgeoFileSink : public SectionSink {
 public:
  explicit VgeoFileSink(std::string path);
  ~VgeoFileSink() override;
  VgeoFileSink(const VgeoFileSink&) = delete;
  VgeoFileSink& operator=(const VgeoFileSink&) = delete;
  // Writes the file from the spools, reading them back on up to `threads` threads.
  void commit(int threads = 1);

 private:
  struct Spool {
    int fd = -1;
    std::vector<uint8_t> buffer;  // written out when full
  };
  void write(Section s, const void* data, uint64_t count) override;
  void flush(Spool& spool);
  std::string path_;
  std::vector<Spool> spools_;
};

}  // namespace vgeo

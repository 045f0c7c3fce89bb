// vgeo_head.h: the .vgeo header, section table and checksum, shared by the writers of vgeo_file.cpp and
// section_sink.cpp (the layout itself is documented in vgeo_file.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vgeo {

constexpr char kVgeoMagic[8] = {'V', 'G', 'E', 'O', 'F', 'I', 'L', 'E'};
constexpr size_t kVgeoHeaderSize = 32, kVgeoEntrySize = 32;

struct VgeoEntry {
  uint32_t id, elementSize;
  uint64_t offset, count, checksum;
};

// Multiply-xor over 64-bit words: each step is a bijection of the word, so any change to one word
// changes the sum; the length is mixed in first so that truncation to a word boundary is caught too.
// Fed in pieces whose sizes are multiples of 8 but for the last, it gives what one call would.
class VgeoChecksum {
 public:
  explicit VgeoChecksum(uint64_t length) : h_(0x9e3779b97f4a7c15ull ^ length) {}
  void add(const uint8_t* p, size_t n);
  uint64_t finish();

 private:
  uint64_t h_;
  uint8_t tail_[8] = {};
  size_t tailSize_ = 0;
};
uint64_t vgeoChecksum(const uint8_t* p, size_t n);

// The sections' placement: the first follows the header and a table of `sections` entries, each starts
// at the first 16-byte boundary after the end of the one before.
inline uint64_t vgeoTableEnd(size_t sections) { return kVgeoHeaderSize + uint64_t(kVgeoEntrySize) * sections; }
inline uint64_t vgeoSectionStart(uint64_t previousEnd) { return (previousEnd + 15) / 16 * 16; }
// Where each of `count` sections of these element sizes and counts starts, as above; returns the file's
// size.
uint64_t placeVgeoSections(std::vector<VgeoEntry>& entries);
// The header and section table for `entries` (checksums filled in) in a file of `fileSize` bytes.
std::vector<uint8_t> vgeoHead(const std::vector<VgeoEntry>& entries, uint64_t fileSize);

}  // namespace vgeo

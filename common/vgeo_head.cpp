// vgeo_head.cpp: the .vgeo header, section table and checksum (vgeo_head.h).
#include "vgeo_head.h"

#include <algorithm>
#include <cstring>

#include "vgeo_file.h"

namespace vgeo {
namespace {

constexpr uint64_t kPrime = 0x100000001b3ull;

template <class T>
void put(std::vector<uint8_t>& out, const T& v) {
  const uint8_t* b = reinterpret_cast<const uint8_t*>(&v);
  out.insert(out.end(), b, b + sizeof(T));
}

}  // namespace

void VgeoChecksum::add(const uint8_t* p, size_t n) {
  auto word = [&](uint64_t w) {
    h_ = (h_ ^ w) * kPrime;
    h_ ^= h_ >> 31;
  };
  if (tailSize_ > 0) {
    const size_t take = std::min(n, 8 - tailSize_);
    std::memcpy(tail_ + tailSize_, p, take);
    tailSize_ += take, p += take, n -= take;
    if (tailSize_ < 8) return;
    uint64_t w;
    std::memcpy(&w, tail_, 8);
    word(w);
    tailSize_ = 0;
  }
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    word(w);
  }
  if (n > i) std::memcpy(tail_, p + i, n - i);  // never with a null p (an empty section)
  tailSize_ = n - i;
}

uint64_t VgeoChecksum::finish() {
  uint64_t tail = 0;
  std::memcpy(&tail, tail_, tailSize_);
  uint64_t h = (h_ ^ tail) * kPrime;
  return h ^ (h >> 29);
}

uint64_t vgeoChecksum(const uint8_t* p, size_t n) {
  VgeoChecksum sum(n);
  if (n) sum.add(p, n);
  return sum.finish();
}

uint64_t placeVgeoSections(std::vector<VgeoEntry>& entries) {
  uint64_t position = vgeoTableEnd(entries.size());
  for (VgeoEntry& e : entries) {
    position = vgeoSectionStart(position);
    e.offset = position;
    position += e.count * e.elementSize;
  }
  return position;
}

std::vector<uint8_t> vgeoHead(const std::vector<VgeoEntry>& entries, uint64_t fileSize) {
  std::vector<uint8_t> head(kVgeoMagic, kVgeoMagic + 8);
  head.reserve(vgeoTableEnd(entries.size()));
  put(head, kVgeoVersion);
  put(head, uint32_t(entries.size()));
  put(head, fileSize);
  put(head, uint64_t(0));
  for (const VgeoEntry& e : entries) {
    put(head, e.id);
    put(head, e.elementSize);
    put(head, e.offset);
    put(head, e.count);
    put(head, e.checksum);
  }
  const uint64_t tableSum = vgeoChecksum(head.data(), head.size());
  std::memcpy(head.data() + 24, &tableSum, 8);
  return head;
}

}  // namespace vgeo

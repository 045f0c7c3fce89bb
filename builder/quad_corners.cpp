// quad_corners.cpp: the corners of a quad mesh grouped by vertex (a counting sort, linear time and 4 bytes
// a corner), so that walks around vertices and across edges (limit.cpp, patch.cpp) find "the corner of a
// whose next vertex is b" by scanning a's few corners instead of sorting a table of every directed edge
// (which cost a 5-million-face build a second and 160 MB). The sort runs on the build's threads for a
// large mesh: one thread's pass over a 5-million-face cage was most of what the patches and limit
// stages took on 16.
#include <algorithm>

#include "../common/bucket_sort.h"
#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {

void cornersByVertex(std::span<const uint32_t> faceVertices, size_t vertexCount, int threads,
                     FillLaterVector<uint32_t>& start, FillLaterVector<uint32_t>& corners) {
  // A patch tree's local meshes (a few dozen faces, thousands of times) count on their thread, where
  // the parallel sort's fixed costs would outweigh the work.
  constexpr size_t kSmallMesh = 4096;  // corners
  if (threads > 1 && faceVertices.size() > kSmallMesh) {
    FillLaterVector<size_t> starts;
    const int vertexBits = bitsFor(std::max<size_t>(vertexCount, 1));
    corners = bucketSorted<uint32_t>(
        faceVertices.size(), vertexBits, vertexBits, threads,
        [&](size_t c, auto&& emit) { emit(faceVertices[c], uint32_t(c)); }, std::less<uint32_t>(), &starts);
    start.resize(vertexCount + 1);
    parallelForRanges(start.size(), threads, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; v++) start[v] = uint32_t(starts[v]);
    });
    return;
  }
  start.assign(vertexCount + 1, 0);
  for (uint32_t v : faceVertices) start[v + 1]++;
  for (size_t v = 0; v < vertexCount; v++) start[v + 1] += start[v];
  corners.resize(faceVertices.size());
  FillLaterVector<uint32_t> next(start.begin(), start.end() - 1);
  for (size_t c = 0; c < faceVertices.size(); c++) corners[next[faceVertices[c]]++] = uint32_t(c);
}

bool allQuads(const PolygonMesh& mesh, int threads) {
  // Every face a quad exactly when face f starts at corner 4 f, for every f and the end.
  std::vector<uint8_t> rangeQuads(parallelRangeCount(mesh.faceStart.size()), 1);
  parallelForRanges(mesh.faceStart.size(), threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++)
      if (mesh.faceStart[f] != 4 * f) {
        rangeQuads[begin / kParallelRange] = 0;
        return;
      }
  });
  return std::find(rangeQuads.begin(), rangeQuads.end(), 0) == rangeQuads.end();
}

QuadCorners::QuadCorners(const PolygonMesh& mesh, int threads) : vertices_(mesh.faceVertices) {
  cornersByVertex(vertices_, mesh.positions.size(), threads, offsets_, corners_);
  // The corners' next vertices beside them: a scan for withNext reads a few neighbouring words instead
  // of one face elsewhere in memory a corner (the walks of patch.cpp and limit.cpp are mostly these).
  nextOf_.resize(corners_.size());
  parallelForRanges(corners_.size(), threads, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; i++) nextOf_[i] = at(corners_[i], 1);
  });
}

uint32_t QuadCorners::withNext(uint32_t a, uint32_t b) const {
  for (uint32_t i = offsets_[a]; i < offsets_[a + 1]; i++)
    if (nextOf_[i] == b) return corners_[i];
  return UINT32_MAX;
}

uint32_t QuadCorners::withPrev(uint32_t a, uint32_t b) const {
  for (uint32_t i = offsets_[a]; i < offsets_[a + 1]; i++)
    if (at(corners_[i], 3) == b) return corners_[i];
  return UINT32_MAX;
}

namespace {

// Numbers for the keys met, in the order first met: open addressing in a table kept under half full.
class FirstSeen {
 public:
  // Key's number; a new key gets the next one and sets `added`.
  uint32_t number(uint32_t key, bool& added) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    const size_t mask = slots_.size() - 1;
    for (size_t i = hash(key) & mask;; i = (i + 1) & mask) {
      if (slots_[i] == kEmpty) {
        slots_[i] = uint64_t(key) << 32 | count_;
        added = true;
        return count_++;
      }
      if (uint32_t(slots_[i] >> 32) == key) {
        added = false;
        return uint32_t(slots_[i]);
      }
    }
  }
  // Passes over a number.
  void skip() { count_++; }

 private:
  static constexpr uint64_t kEmpty = UINT64_MAX;  // no key is UINT32_MAX with number UINT32_MAX
  static size_t hash(uint32_t key) { return size_t(key * 0x9E3779B1u) >> 7; }
  void grow() {
    std::vector<uint64_t> old(std::max<size_t>(64, 2 * slots_.size()), kEmpty);
    old.swap(slots_);
    const size_t mask = slots_.size() - 1;
    for (uint64_t slot : old)
      if (slot != kEmpty) {
        size_t i = hash(uint32_t(slot >> 32)) & mask;
        while (slots_[i] != kEmpty) i = (i + 1) & mask;
        slots_[i] = slot;
      }
  }
  std::vector<uint64_t> slots_;
  uint32_t count_ = 0;
};

}  // namespace

PolygonMesh facesAround(const PolygonMesh& mesh, const std::vector<glm::vec3>& positions, const QuadCorners& q,
                        const uint32_t* vertices, uint32_t count, uint32_t firstFace) {
  std::vector<uint32_t> faces;
  FirstSeen faceSeen, vertexSeen;
  bool added = false;
  if (firstFace != UINT32_MAX) faces.push_back(firstFace), faceSeen.number(firstFace, added);
  for (uint32_t k = 0; k < count; k++)
    for (uint32_t i = q.offsets()[vertices[k]]; i < q.offsets()[vertices[k] + 1]; i++)
      if (faceSeen.number(q.corners()[i] / 4, added), added) faces.push_back(q.corners()[i] / 4);
  PolygonMesh out;
  out.faceStart.reserve(faces.size() + 1);
  out.faceVertices.reserve(4 * faces.size());
  out.positions.reserve(4 * faces.size());
  for (uint32_t k = 0; k < count; k++) {  // local vertex k is vertices[k], even where one repeats
    if (vertexSeen.number(vertices[k], added), !added) vertexSeen.skip();
    out.positions.push_back(positions[vertices[k]]);
  }
  for (uint32_t f : faces) {
    uint32_t local[4];
    for (uint32_t k = 0; k < 4; k++) {
      const uint32_t v = mesh.face(f)[k];
      local[k] = vertexSeen.number(v, added);
      if (added) out.positions.push_back(positions[v]);
    }
    out.addFace(local, 4);
  }
  return out;
}

}  // namespace vgeo

// vgeo_file.cpp: writing, reading and checking .vgeo files (layout in vgeo_file.h).
#include "vgeo_file.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "atomic_file.h"
#include "input_error.h"
#include "vgeo_head.h"

namespace vgeo {
namespace {

template <class T>
T get(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

struct SectionView {
  const void* data;
  uint32_t elementSize;
  uint64_t count;
};

std::vector<SectionView> views(const VgeoData& d) {
#define VGEO_SECTION_VIEW(id, member, type, values, name) \
  {d.member.data(), uint32_t(sizeof(type) * values), d.member.size() / values},
  return {VGEO_SECTIONS(VGEO_SECTION_VIEW)};
#undef VGEO_SECTION_VIEW
}

}  // namespace

const char* sectionName(Section s) {
#define VGEO_SECTION_NAME(id, member, type, values, name) name,
  static const char* names[] = {"?", VGEO_SECTIONS(VGEO_SECTION_NAME)};
#undef VGEO_SECTION_NAME
  uint32_t i = uint32_t(s);
  return i < uint32_t(Section::Count_) ? names[i] : "?";
}

namespace {

// Emits the file's bytes in order through sink(pointer, size): header and table, then each section at its
// 16-byte aligned offset. Checksums are taken from the data in place, so writing a file needs no copy
// of it (a copy was the largest allocation of a big build).
template <class Sink>
void emitVgeo(const VgeoData& data, Sink&& sink) {
  auto sections = views(data);
  std::vector<VgeoEntry> entries(sections.size());
  for (uint32_t i = 0; i < entries.size(); i++) {
    entries[i] = {i + 1, sections[i].elementSize, 0, sections[i].count, 0};
    entries[i].checksum = vgeoChecksum(static_cast<const uint8_t*>(sections[i].data),
                                       size_t(sections[i].count) * sections[i].elementSize);
  }
  const uint64_t fileSize = placeVgeoSections(entries);
  std::vector<uint8_t> head = vgeoHead(entries, fileSize);
  sink(head.data(), head.size());
  uint64_t written = head.size();
  static const uint8_t zeros[16] = {};
  for (uint32_t i = 0; i < entries.size(); i++) {
    if (entries[i].offset > written) sink(zeros, size_t(entries[i].offset - written));
    size_t bytes = size_t(sections[i].count) * sections[i].elementSize;
    if (bytes) sink(static_cast<const uint8_t*>(sections[i].data), bytes);
    written = entries[i].offset + bytes;
  }
}

}  // namespace

std::vector<uint8_t> serializeVgeo(const VgeoData& data) {
  std::vector<uint8_t> out;
  emitVgeo(data, [&](const uint8_t* p, size_t n) { out.insert(out.end(), p, p + n); });
  return out;
}

namespace {

// Throws InputError(file, cause): the one way a check below reports.
struct Fail {
  const std::string& file;
  [[noreturn]] void operator()(const std::string& cause) const { throw InputError(file, cause); }
};

// [offset, offset + n) lies within [0, size), without overflow.
bool within(uint64_t offset, uint64_t n, uint64_t size) { return offset <= size && n <= size - offset; }

// The header, the section table and each known section's bytes (checksums, sizes, bounds).
VgeoData readSections(const uint8_t* bytes, size_t size, const Fail& fail) {
  if (size < kVgeoHeaderSize) fail("truncated: " + std::to_string(size) + " bytes is smaller than a .vgeo header");
  if (std::memcmp(bytes, kVgeoMagic, 8) != 0) fail("not a .vgeo file (bad magic)");
  uint32_t version = get<uint32_t>(bytes + 8);
  if (version != kVgeoVersion)
    fail("unsupported .vgeo version " + std::to_string(version) + " (this build reads version " +
         std::to_string(kVgeoVersion) + "); rebuild the file with this vgeo");
  uint32_t count = get<uint32_t>(bytes + 12);
  uint64_t fileSize = get<uint64_t>(bytes + 16);
  if (fileSize != size)
    fail("truncated or padded: the header says " + std::to_string(fileSize) + " bytes, the file has " +
         std::to_string(size));
  if (count > 64 || kVgeoHeaderSize + uint64_t(count) * kVgeoEntrySize > size)
    fail("corrupt section table (" + std::to_string(count) + " sections)");
  std::vector<uint8_t> head(bytes, bytes + kVgeoHeaderSize + count * kVgeoEntrySize);
  uint64_t stored = get<uint64_t>(bytes + 24);
  std::memset(head.data() + 24, 0, 8);
  if (vgeoChecksum(head.data(), head.size()) != stored) fail("corrupt header or section table (checksum mismatch)");

  VgeoData data;
  auto sections = views(data);  // element sizes only
  std::vector<bool> seen(sections.size(), false);
  for (uint32_t i = 0; i < count; i++) {
    const uint8_t* p = bytes + kVgeoHeaderSize + i * kVgeoEntrySize;
    VgeoEntry e{get<uint32_t>(p), get<uint32_t>(p + 4), get<uint64_t>(p + 8), get<uint64_t>(p + 16),
                get<uint64_t>(p + 24)};
    if (e.id == 0 || e.id >= uint32_t(Section::Count_)) continue;  // unknown sections of later minor versions
    const char* sname = sectionName(Section(e.id));
    if (seen[e.id - 1]) fail(std::string("section '") + sname + "' appears twice");
    seen[e.id - 1] = true;
    if (e.elementSize != sections[e.id - 1].elementSize)
      fail(std::string("section '") + sname + "' has element size " + std::to_string(e.elementSize));
    if (e.offset % 16 || e.offset > size || e.count > (size - e.offset) / e.elementSize)
      fail(std::string("section '") + sname + "' lies outside the file");
    const uint8_t* src = bytes + e.offset;
    size_t n = size_t(e.count * e.elementSize);
    if (vgeoChecksum(src, n) != e.checksum) fail(std::string("section '") + sname + "' is corrupt (checksum mismatch)");
    auto copy = [&](auto& vec, size_t elements) {
      vec.resize(elements);
      if (n) std::memcpy(vec.data(), src, n);
    };
    switch (Section(e.id)) {
#define VGEO_SECTION_COPY(id, member, type, values, name) \
  case Section::id:                                       \
    copy(data.member, size_t(e.count) * values);          \
    break;
      VGEO_SECTIONS(VGEO_SECTION_COPY)
#undef VGEO_SECTION_COPY
      default:
        break;
    }
  }
  for (size_t i = 0; i < seen.size(); i++)
    if (!seen[i]) fail(std::string("section '") + sectionName(Section(i + 1)) + "' is missing");
  return data;
}

// References: everything the renderer will follow must stay inside its array.
void checkReferences(const VgeoData& data, const Fail& fail) {
  const uint64_t vertices = data.vertexCount();
  if (data.normals.size() != vertices) fail("normals and positions differ in count");
  if (data.clusterCones.size() != data.clusters.size()) fail("cluster cones and clusters differ in count");
  for (const auto& c : data.clusterCones)
    for (int k = 0; k < 4; k++)
      if (!std::isfinite(c.cone[k]) || !std::isfinite(c.sphere[k])) fail("a cluster cone is not finite");
  for (size_t v = 0; v < data.positions.size(); v++)
    if (!std::isfinite(data.positions[v])) fail("vertex " + std::to_string(v / 3) + " has a non-finite position");
  for (size_t i = 0; i < data.geometries.size(); i++) {
    const auto& g = data.geometries[i];
    std::string what = "geometry " + std::to_string(i);
    if (!within(g.clusterOffset, g.clusterCount, data.clusters.size()) ||
        !within(g.groupOffset, g.groupCount, data.groups.size()) ||
        !within(g.nodeOffset, g.nodeCount, data.nodes.size()) || g.nodeCount == 0 ||
        !within(g.vertexOffset, g.vertexCount, vertices) ||
        !within(g.cageFaceOffset, g.cageFaceCount, data.cageFaces.size()))
      fail(what + " refers outside the file's arrays");
  }
  if (data.instances.empty()) fail("no instances: nothing to draw");
  for (size_t i = 0; i < data.instances.size(); i++) {
    const auto& inst = data.instances[i];
    if (inst.geometry >= data.geometries.size()) fail("instance " + std::to_string(i) + " uses a missing geometry");
    const std::string problem = instanceProblem(inst, data.geometries[inst.geometry]);
    if (!problem.empty()) fail("instance " + std::to_string(i) + " " + problem);
  }
  for (size_t i = 0; i < data.clusters.size(); i++) {
    const auto& c = data.clusters[i];
    std::string what = "cluster " + std::to_string(i);
    uint32_t vc = shaderio::clusterVertexCount(c.counts), tc = shaderio::clusterTriangleCount(c.counts);
    if (vc > VGEO_MAX_CLUSTER_VERTICES || tc > VGEO_MAX_CLUSTER_TRIANGLES)
      fail(what + " is larger than a cluster may be");
    if (!within(c.vertexOffset, vc, data.clusterVertices.size()) ||
        !within(c.triangleOffset, tc, data.clusterTriangles.size()) ||
        !within(c.cageFaceOffset, shaderio::clusterCageFaceCount(c.counts), data.cageFaces.size()))
      fail(what + " refers outside the file's arrays");
    if (c.group >= data.groups.size() || (c.producer != VGEO_NO_GROUP && c.producer >= data.groups.size()))
      fail(what + " refers to a missing group");
    for (uint32_t k = 0; k < vc; k++)
      if (data.clusterVertices[c.vertexOffset + k] >= vertices) fail(what + " uses a vertex out of range");
    for (uint32_t t = 0; t < tc; t++) {
      uint32_t tri = data.clusterTriangles[c.triangleOffset + t];
      if ((tri & 0xff) >= vc || ((tri >> 8) & 0xff) >= vc || ((tri >> 16) & 0xff) >= vc || (tri >> 24))
        fail(what + " has a triangle with a local index out of range");
    }
    if (!std::isfinite(c.selfError) || std::isnan(c.parentError)) fail(what + " has a non-finite error");
  }
  for (size_t i = 0; i < data.groups.size(); i++)
    if (!within(data.groups[i].clusterOffset, data.groups[i].clusterCount, data.clusters.size()))
      fail("group " + std::to_string(i) + " refers outside the cluster array");
    else if (data.groups[i].clusterCount > VGEO_MAX_GROUP_CLUSTERS)
      fail("group " + std::to_string(i) + " has more than " + std::to_string(VGEO_MAX_GROUP_CLUSTERS) + " clusters");
}

// The values the renderer's tests rely on: spheres finite with a radius >= 0, errors >= 0 (not NaN; a
// parent's may be +inf), no empty group, every BVH node with children, every cage face's triangles inside
// its leaf cluster (the GPU reads them by firstTriangle), and every geometry with clusters.
void checkValues(const VgeoData& data, const Fail& fail) {
  auto sphere = [](const glm::vec4& s) {
    return std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z) && std::isfinite(s.w) && s.w >= 0.0f;
  };
  auto error = [](float e) { return e >= 0.0f; };  // false for NaN
  for (size_t i = 0; i < data.geometries.size(); i++) {
    if (!sphere(data.geometries[i].boundsSphere)) fail("geometry " + std::to_string(i) + " has a bad bounding sphere");
    if (data.geometries[i].clusterCount == 0) fail("geometry " + std::to_string(i) + " has no clusters");
  }
  for (size_t i = 0; i < data.clusters.size(); i++) {
    const auto& c = data.clusters[i];
    const std::string what = "cluster " + std::to_string(i);
    if (!sphere(c.selfSphere) || !sphere(c.parentSphere)) fail(what + " has a bad bounding sphere");
    if (!error(c.selfError) || !error(c.parentError)) fail(what + " has a negative or NaN error");
    const uint32_t triangles = shaderio::clusterTriangleCount(c.counts);
    for (uint32_t k = 0; k < shaderio::clusterCageFaceCount(c.counts); k++) {
      const auto& f = data.cageFaces[c.cageFaceOffset + k];
      if (f.leafCluster != i || f.vertexCount < 3 || f.firstTriangle > triangles ||
          f.vertexCount - 2 > triangles - f.firstTriangle)
        fail(what + ": cage face " + std::to_string(c.cageFaceOffset + k) + " names triangles outside the cluster");
    }
  }
  for (size_t i = 0; i < data.groups.size(); i++) {
    const auto& g = data.groups[i];
    if (!sphere(g.sphere) || !error(g.error) || g.clusterCount == 0)
      fail("group " + std::to_string(i) + " has a bad sphere or error, or no clusters");
  }
  for (size_t i = 0; i < data.nodes.size(); i++) {
    const auto& n = data.nodes[i];
    if (!sphere(n.sphere) || !error(n.maxError) || (n.childCountAndFlags & ~VGEO_NODE_LEAF_BIT) == 0)
      fail("BVH node " + std::to_string(i) + " has a bad sphere or error, or no children");
  }
}

// Nodes: children in range, and every node reached once from its geometry's root (no cycles), no
// deeper than kMaxBvhDepth (the walks that follow may then keep their stacks small).
void checkBvh(const VgeoData& data, const Fail& fail) {
  std::vector<uint8_t> reached(data.nodes.size(), 0);
  for (const auto& g : data.geometries) {
    std::vector<std::pair<uint32_t, uint32_t>> stack{{g.nodeOffset, 1u}};
    while (!stack.empty()) {
      auto [n, depth] = stack.back();
      stack.pop_back();
      if (n < g.nodeOffset || n - g.nodeOffset >= g.nodeCount)
        fail("BVH node " + std::to_string(n) + " belongs to another geometry");
      if (reached[n]++) fail("BVH node " + std::to_string(n) + " is reached twice (the hierarchy is not a tree)");
      if (depth > kMaxBvhDepth) fail("the BVH is deeper than " + std::to_string(kMaxBvhDepth) + " levels");
      const auto& node = data.nodes[n];
      uint32_t children = node.childCountAndFlags & ~VGEO_NODE_LEAF_BIT;
      if (children > (n == g.nodeOffset ? VGEO_BVH_ROOT_WIDTH : VGEO_BVH_WIDTH))
        fail("BVH node " + std::to_string(n) + " has too many children");
      if (node.childCountAndFlags & VGEO_NODE_LEAF_BIT) {
        if (!within(node.childOffset, children, data.groups.size()) || node.childOffset < g.groupOffset ||
            node.childOffset + children > g.groupOffset + g.groupCount)
          fail("BVH node " + std::to_string(n) + " refers to groups outside its geometry");
      } else {
        if (!within(node.childOffset, children, data.nodes.size()))
          fail("BVH node " + std::to_string(n) + " refers to missing nodes");
        for (uint32_t k = 0; k < children; k++) stack.push_back({node.childOffset + k, depth + 1});
      }
    }
  }
}

// Each geometry's clusters, groups and cage faces refer only to its own vertices, groups, clusters
// and faces (a cluster naming another geometry's vertices would draw them with its instances).
void checkGeometryOwnership(const VgeoData& data, const Fail& fail) {
  for (size_t i = 0; i < data.geometries.size(); i++) {
    const auto& g = data.geometries[i];
    auto in = [](uint64_t x, uint64_t offset, uint64_t count) { return x >= offset && x - offset < count; };
    const std::string what = "geometry " + std::to_string(i);
    for (uint32_t ci = g.clusterOffset; ci < g.clusterOffset + g.clusterCount; ci++) {
      const auto& c = data.clusters[ci];
      for (uint32_t k = 0; k < shaderio::clusterVertexCount(c.counts); k++)
        if (!in(data.clusterVertices[c.vertexOffset + k], g.vertexOffset, g.vertexCount))
          fail(what + ": cluster " + std::to_string(ci) + " uses a vertex of another geometry");
      if (!in(c.group, g.groupOffset, g.groupCount) ||
          (c.producer != VGEO_NO_GROUP && !in(c.producer, g.groupOffset, g.groupCount)))
        fail(what + ": cluster " + std::to_string(ci) + " refers to a group of another geometry");
      // Coarser toward the root: the walks from a group up through its products end (no cycle).
      if (c.producer != VGEO_NO_GROUP && !(data.groups[c.producer].level < data.groups[c.group].level))
        fail(what + ": cluster " + std::to_string(ci) + " is produced by a group no finer than its own");
      const uint32_t faces = shaderio::clusterCageFaceCount(c.counts);
      if (faces && (!in(c.cageFaceOffset, g.cageFaceOffset, g.cageFaceCount) ||
                    c.cageFaceOffset + faces > g.cageFaceOffset + g.cageFaceCount))
        fail(what + ": cluster " + std::to_string(ci) + " refers to cage faces of another geometry");
    }
    for (uint32_t gi = g.groupOffset; gi < g.groupOffset + g.groupCount; gi++) {
      const auto& grp = data.groups[gi];
      if (grp.clusterCount && (!in(grp.clusterOffset, g.clusterOffset, g.clusterCount) ||
                               grp.clusterOffset + grp.clusterCount > g.clusterOffset + g.clusterCount))
        fail(what + ": group " + std::to_string(gi) + " refers to clusters of another geometry");
    }
    for (uint32_t fi = g.cageFaceOffset; fi < g.cageFaceOffset + g.cageFaceCount; fi++) {
      const auto& f = data.cageFaces[fi];
      if (!within(f.firstVertex, f.vertexCount, data.cageFaceVertices.size()) ||
          !in(f.leafCluster, g.clusterOffset, g.clusterCount))
        fail(what + ": cage face " + std::to_string(fi) + " refers outside its geometry");
      for (uint32_t k = 0; k < f.vertexCount; k++)
        if (!in(data.cageFaceVertices[f.firstVertex + k], g.vertexOffset, g.vertexCount))
          fail(what + ": cage face " + std::to_string(fi) + " uses a vertex of another geometry");
      if (fi < data.patches.size())
        for (uint32_t n : data.patches[fi].neighbours)
          if (n != VGEO_INVALID && !in(n >> 2, g.cageFaceOffset, g.cageFaceCount))
            fail(what + ": the patch of cage face " + std::to_string(fi) + " names a neighbour of another geometry");
    }
  }
}

// Cage faces and their patches: vertices, control points and neighbours in range, tree words well formed,
// chord errors finite and ordered (an edge's no larger than its face's).
void checkPatches(const VgeoData& data, const Fail& fail) {
  for (size_t i = 0; i < data.cageFaces.size(); i++) {
    const auto& f = data.cageFaces[i];
    if (!within(f.firstVertex, f.vertexCount, data.cageFaceVertices.size()) || f.leafCluster >= data.clusters.size())
      fail("cage face " + std::to_string(i) + " refers outside the file's arrays");
  }
  for (uint32_t v : data.cageFaceVertices)
    if (v >= data.vertexCount()) fail("a cage face uses a vertex out of range");
  if (data.controlPoints.size() % 3 != 0) fail("the control points are not x, y, z triples");
  for (float x : data.controlPoints)
    if (!std::isfinite(x)) fail("a control point is not finite");
  if (data.patches.size() != data.cageFaces.size()) fail("patches and cage faces differ in count");
  const size_t controlPoints = data.controlPoints.size() / 3;
  for (size_t i = 0; i < data.patches.size(); i++) {
    const shaderio::Patch& p = data.patches[i];
    std::string what = "patch " + std::to_string(i);
    const uint32_t kind = shaderio::patchKind(p.info);
    if (kind != VGEO_PATCH_NONE) {
      if (data.cageFaces[i].vertexCount != 4) fail(what + " belongs to a face that is not a quad");
      if (p.firstPoint > data.patchPoints.size()) fail(what + " refers outside the patch points");
      const uint32_t* words = data.patchPoints.data() + p.firstPoint;
      bool inRange = true;
      auto point = [&](size_t w) {
        inRange = inRange && p.pointBase < controlPoints && words[w] < controlPoints - p.pointBase;
      };
      if (!shaderio::forEachPatchPoint(p.info, words, data.patchPoints.size() - p.firstPoint, point))
        fail(what + " has malformed words (unknown kind, a node outside the patch points or a tree too deep)");
      if (!inRange) fail(what + " uses a control point out of range");
    }
    for (uint32_t n : p.neighbours)
      if (n != VGEO_INVALID && (n >> 2) >= data.patches.size()) fail(what + " names a missing neighbour");
    if (!(p.faceError >= 0.0f) || !std::isfinite(p.faceError)) fail(what + " has a bad chord error");
    for (int k = 0; k < 4; k++)
      if (!(p.edgeError[k] >= 0.0f) || !std::isfinite(p.edgeError[k]) || p.edgeError[k] > p.faceError)
        fail(what + " has a bad edge chord error");
  }
}

}  // namespace

VgeoData parseVgeo(const uint8_t* bytes, size_t size, const std::string& name) {
  const Fail fail{name};
  VgeoData data = readSections(bytes, size, fail);
  checkReferences(data, fail);
  checkBvh(data, fail);
  checkGeometryOwnership(data, fail);
  checkPatches(data, fail);
  checkValues(data, fail);
  return data;
}

std::string instanceProblem(const shaderio::Instance& inst, const shaderio::Geometry& geometry) {
  if (!(inst.maxScale > 0.0f) || !std::isfinite(inst.maxScale)) return "has a zero or non-finite scale";
  for (int r = 0; r < 4; r++)
    if (!std::isfinite(inst.row0[r]) || !std::isfinite(inst.row1[r]) || !std::isfinite(inst.row2[r]))
      return "has a non-finite transform";
  // In double: the float product may itself overflow.
  const glm::dvec4 s(geometry.boundsSphere);
  const glm::dvec4 h(s.x, s.y, s.z, 1.0);
  const glm::dvec3 c(glm::dot(glm::dvec4(inst.row0), h), glm::dot(glm::dvec4(inst.row1), h),
                     glm::dot(glm::dvec4(inst.row2), h));
  const double reach = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}) + s.w * double(inst.maxScale);
  if (!(reach <= double(kMaxWorldExtent)))
    return "reaches past +-1e15 from the origin (the renderer's float precision)";
  return "";
}

glm::vec3 VgeoData::evaluatePatch(uint32_t face, float s, float t, glm::vec3* normal) const {
  const shaderio::Patch& patch = patches[face];
  const uint32_t* corners = &cageFaceVertices[cageFaces[face].firstVertex];
  auto point = [&](uint32_t i) {
    const float* x = &controlPoints[3 * (size_t(patch.pointBase) + i)];
    return glm::vec3(x[0], x[1], x[2]);
  };
  auto corner = [&](uint32_t k) { return position(corners[k]); };
  glm::vec3 n;
  const uint32_t* words = patchPoints.data() + std::min<size_t>(patch.firstPoint, patchPoints.size());
  glm::vec3 p = shaderio::evaluatePatchWords(patch.info, words, point, corner, s, t, n);
  if (normal) *normal = n;
  return p;
}

void writeVgeo(const VgeoData& data, const std::string& path) {
  AtomicFile out(path);
  emitVgeo(data, [&](const uint8_t* p, size_t n) { out.write(p, n); });
  out.commit();
}

VgeoData readVgeo(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parseVgeo(bytes.data(), bytes.size(), path);
}

shaderio::Instance makeInstance(const glm::mat4& m, uint32_t geometry, bool geometryClosed) {
  shaderio::Instance inst{};
  glm::mat4 t = glm::transpose(m);
  inst.row0 = t[0];
  inst.row1 = t[1];
  inst.row2 = t[2];
  inst.geometry = geometry;
  // maxScale bounds how far the transform stretches any length (errors and radii grow by it): the
  // square root of a Gershgorin bound on the largest eigenvalue of M^T M, which is the largest column
  // length when the columns are orthogonal and stays an upper bound under shear.
  const glm::mat3 a(m);
  const glm::mat3 gram = glm::transpose(a) * a;
  float bound = 0.0f;
  for (int i = 0; i < 3; i++)
    bound = std::max(bound, std::abs(gram[i][0]) + std::abs(gram[i][1]) + std::abs(gram[i][2]));
  inst.maxScale = std::sqrt(bound);
  // Normal cones turn with the transform only when it is a rotation (or a mirror) times one scale:
  // orthogonal columns of equal length. A mirror keeps the outward side outward, so it may cone-cull.
  const float tolerance = 1e-5f * bound;
  bool similarity = std::abs(gram[0][0] - gram[1][1]) <= tolerance && std::abs(gram[0][0] - gram[2][2]) <= tolerance &&
                    std::abs(gram[0][1]) <= tolerance && std::abs(gram[0][2]) <= tolerance &&
                    std::abs(gram[1][2]) <= tolerance;
  inst.flags = similarity && geometryClosed ? VGEO_INSTANCE_CONE_CULL : 0u;
  return inst;
}

uint32_t encodeNormal(glm::vec3 n) {
  n /= (std::abs(n.x) + std::abs(n.y) + std::abs(n.z) + 1e-30f);
  glm::vec2 e(n.x, n.y);
  if (n.z < 0.0f)
    e = (1.0f - glm::abs(glm::vec2(n.y, n.x))) * glm::vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
  auto q = [](float f) { return uint32_t(int32_t(std::lround(glm::clamp(f, -1.0f, 1.0f) * 32767.0f)) & 0xffff); };
  return q(e.x) | q(e.y) << 16;
}

}  // namespace vgeo

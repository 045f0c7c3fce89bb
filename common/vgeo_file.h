// vgeo_file.h: the .vgeo file, the one thing the builder hands the renderer.
//
// Layout (little-endian):
//   header   : magic "VGEOFILE", u32 version, u32 sectionCount, u64 fileSize, u64 tableChecksum
//   table    : sectionCount x { u32 id, u32 elementSize, u64 offset, u64 count, u64 checksum }
//   sections : each 16-byte aligned, an array of the shaderio.h struct it names, as the GPU buffer holds it
// tableChecksum covers the header (with that field zero) and the table; each section has its own
// checksum, so an error names the damaged section. The loader checks every count, offset and index
// (vertex, cluster, group, node, face references) so that a file it accepts cannot make the renderer
// read out of bounds.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "../shaders/patch_eval.h"

namespace vgeo {

constexpr uint32_t kVgeoVersion = 6;  // 2: cluster normal cones; 3: leaves on the limit surface, control points, patches;
                                      // 4: patches for every interior face (rings), chord errors, patch points;
                                      // 5: boundary and tree patches, control points apart from vertices;
                                      // 6: the BVH root has up to VGEO_BVH_ROOT_WIDTH children (the level roots)

enum class Section : uint32_t {
  Geometries = 1,
  Instances,
  Positions,         // float x, y, z per vertex
  Normals,           // octahedral unit normals, 2 x snorm16 per vertex
  Clusters,
  ClusterVertices,   // absolute vertex index per cluster vertex
  ClusterTriangles,  // 3 x 8-bit local vertex index per triangle (bits 0-7, 8-15, 16-23)
  Groups,
  BvhNodes,
  CageFaces,
  CageFaceVertices,  // absolute vertex index per cage face corner
  ClusterCones,      // shaderio::ClusterCone per cluster (normal cone and tight sphere)
  ControlPoints,     // float x, y, z: each subdivided geometry's level-N cage, then its phantom and tree points
  Patches,           // shaderio::Patch per cage face
  PatchPoints,       // the patches' words (shaderio.h): control-point indices relative to Patch.pointBase, tree nodes
  Count_
};
const char* sectionName(Section s);

struct VgeoData {
  std::vector<shaderio::Geometry> geometries;
  std::vector<shaderio::Instance> instances;
  std::vector<float> positions;
  std::vector<uint32_t> normals;
  std::vector<shaderio::Cluster> clusters;
  std::vector<uint32_t> clusterVertices;
  std::vector<uint32_t> clusterTriangles;
  std::vector<shaderio::Group> groups;
  std::vector<shaderio::BvhNode> nodes;
  std::vector<shaderio::CageFace> cageFaces;
  std::vector<uint32_t> cageFaceVertices;
  std::vector<shaderio::ClusterCone> clusterCones;
  std::vector<float> controlPoints;  // x, y, z each
  std::vector<shaderio::Patch> patches;
  std::vector<uint32_t> patchPoints;

  size_t vertexCount() const { return positions.size() / 3; }
  // Cage face `face`'s patch at face parameters (s, t) (shaderio.h, Patch), with its unit normal, as
  // patch.tese evaluates it; a flat face (VGEO_PATCH_NONE) is bilinear between its corners' leaf vertices.
  glm::vec3 evaluatePatch(uint32_t face, float s, float t, glm::vec3* normal = nullptr) const;
  glm::vec3 position(uint32_t v) const { return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]}; }
};

// The bytes of a .vgeo file for `data`. Deterministic: equal data give equal bytes.
std::vector<uint8_t> serializeVgeo(const VgeoData& data);
// The deepest BVH a file may hold (the builder's are ~10 levels): what walks it may keep on a stack.
constexpr uint32_t kMaxBvhDepth = 64;
// Parses and checks a .vgeo image; throws InputError("name: cause") for anything wrong with it.
VgeoData parseVgeo(const uint8_t* bytes, size_t size, const std::string& name);
// Writes to a temporary file beside `path` and renames it, so no half-written file is ever left.
// Throws OutputError("path: cause") when that fails (atomic_file.h).
void writeVgeo(const VgeoData& data, const std::string& path);
VgeoData readVgeo(const std::string& path);

// An instance of `geometry` placed by `transform` (mirrors allowed), with a bound on how much it stretches
// lengths; flagged for normal-cone culling when it is a rotation, or a mirror, times one scale and the
// geometry is closed.
shaderio::Instance makeInstance(const glm::mat4& transform, uint32_t geometry, bool geometryClosed);

// Octahedral encoding of unit normals (Cigolle et al. 2014), 16 bits a component.
uint32_t encodeNormal(glm::vec3 n);
glm::vec3 decodeNormal(uint32_t packed);

}  // namespace vgeo

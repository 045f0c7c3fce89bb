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

constexpr uint32_t kVgeoVersion =
    6;  // 2: cluster normal cones; 3: leaves on the limit surface, control points, patches;
        // 4: patches for every interior face (rings), chord errors, patch points;
        // 5: boundary and tree patches, control points apart from vertices;
        // 6: the BVH root has up to VGEO_BVH_ROOT_WIDTH children (the level roots)

// The file's sections in file order, declared once: X(id, VgeoData member, value type, values an element,
// name). This table makes the Section ids, VgeoData's arrays, the writer's section views and the loader's
// copies; a new section is one line here (and its checks in parseVgeo).
//   positions        float x, y, z a vertex
//   normals          octahedral unit normal a vertex, 2 x snorm16 (encodeNormal)
//   clusterVertices  absolute vertex index a cluster vertex
//   clusterTriangles 3 x 8-bit local vertex index a triangle (bits 0-7, 8-15, 16-23)
//   cageFaceVertices absolute vertex index a cage face corner (cage faces: subdivided geometries only)
//   clusterCones     normal cone and tight sphere a cluster
//   controlPoints    float x, y, z: each subdivided geometry's level-N cage, then its phantom and tree points
//   patches          a patch a cage face; patchPoints their words (shaderio.h, Patch)
#define VGEO_SECTIONS(X)                                                   \
  X(Geometries, geometries, shaderio::Geometry, 1, "geometries")           \
  X(Instances, instances, shaderio::Instance, 1, "instances")              \
  X(Positions, positions, float, 3, "positions")                           \
  X(Normals, normals, uint32_t, 1, "normals")                              \
  X(Clusters, clusters, shaderio::Cluster, 1, "clusters")                  \
  X(ClusterVertices, clusterVertices, uint32_t, 1, "cluster vertices")     \
  X(ClusterTriangles, clusterTriangles, uint32_t, 1, "cluster triangles")  \
  X(Groups, groups, shaderio::Group, 1, "groups")                          \
  X(BvhNodes, nodes, shaderio::BvhNode, 1, "BVH nodes")                    \
  X(CageFaces, cageFaces, shaderio::CageFace, 1, "cage faces")             \
  X(CageFaceVertices, cageFaceVertices, uint32_t, 1, "cage face vertices") \
  X(ClusterCones, clusterCones, shaderio::ClusterCone, 1, "cluster cones") \
  X(ControlPoints, controlPoints, float, 3, "control points")              \
  X(Patches, patches, shaderio::Patch, 1, "patches")                       \
  X(PatchPoints, patchPoints, uint32_t, 1, "patch points")

enum class Section : uint32_t {
  None_ = 0,
#define VGEO_SECTION_ID(id, member, type, values, name) id,
  VGEO_SECTIONS(VGEO_SECTION_ID)
#undef VGEO_SECTION_ID
      Count_
};
const char* sectionName(Section s);

struct VgeoData {
  // One array a section (VGEO_SECTIONS): geometries, instances, positions, ..., patchPoints.
#define VGEO_SECTION_MEMBER(id, member, type, values, name) std::vector<type> member;
  VGEO_SECTIONS(VGEO_SECTION_MEMBER)
#undef VGEO_SECTION_MEMBER

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
// How far from the origin, in world units, an instance's bounds may reach: the shaders multiply world
// points by a view-projection in float, and products of 1e15 with a view's ~1e15 still fit a float.
constexpr float kMaxWorldExtent = 1e15f;
// Why instance `inst` of `geometry` cannot be drawn (its transform is not finite, or its world bounds
// reach past kMaxWorldExtent), or empty when it can.
std::string instanceProblem(const shaderio::Instance& inst, const shaderio::Geometry& geometry);
// Parses and checks a .vgeo image; throws InputError("name: cause") for anything wrong with it: its
// structure, every index the CPU or GPU follows, and the values the renderer relies on (finite spheres,
// errors >= 0, every BVH node with children, at least one instance). `vgeo check` adds the invariants
// of docs/design.md, which need the whole DAG walked.
VgeoData parseVgeo(const uint8_t* bytes, size_t size, const std::string& name);
// Writes to a temporary file beside `path` and renames it, so no half-written file is ever left.
// Throws OutputError("path: cause") when that fails (atomic_file.h).
void writeVgeo(const VgeoData& data, const std::string& path);
VgeoData readVgeo(const std::string& path);

// An instance of `geometry` placed by `transform` (mirrors allowed), with a bound on how much it stretches
// lengths; flagged for normal-cone culling when it is a rotation, or a mirror, times one scale and the
// geometry is closed.
shaderio::Instance makeInstance(const glm::mat4& transform, uint32_t geometry, bool geometryClosed);

// Octahedral encoding of unit normals (Cigolle et al. 2014), 16 bits a component; shaderio::decodeNormal
// (shaders/shaderio_scene.h) is its inverse on both sides.
uint32_t encodeNormal(glm::vec3 n);

}  // namespace vgeo

// builder.h: the offline builder's contracts, one function per step of docs/design.md's data flow:
//   load -> repair -> subdivide -> cluster -> (group -> simplify -> split)* -> bounds -> BVH -> .vgeo
// Every function here is deterministic: the same input and options give the same output, whatever the
// thread count. Errors in the input are thrown as InputError with one line "FILE: cause".
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "../common/fill_later.h"
#include "../common/input_error.h"
#include "../common/stage_times.h"
#include "../shaders/patch_eval.h"

namespace vgeo {

// An indexed polygon mesh: face f has the corners faceVertices[faceStart[f] .. faceStart[f+1]). Shading
// normals the input gave (glTF NORMAL, OBJ vn, PLY nx ny nz) travel with the corners, one a corner, or
// are absent (cornerNormals empty); every step that moves corners moves them alike.
struct PolygonMesh {
  std::vector<glm::vec3> positions;
  FillLaterVector<uint32_t> faceStart{0};
  FillLaterVector<uint32_t> faceVertices;
  std::vector<glm::vec3> cornerNormals;

  size_t faceCount() const { return faceStart.size() - 1; }
  uint32_t faceSize(size_t f) const { return faceStart[f + 1] - faceStart[f]; }
  const uint32_t* face(size_t f) const { return faceVertices.data() + faceStart[f]; }
  const glm::vec3* faceNormals(size_t f) const {
    return cornerNormals.empty() ? nullptr : cornerNormals.data() + faceStart[f];
  }
  void addFace(const uint32_t* corners, size_t count, const glm::vec3* normals = nullptr) {
    faceVertices.insert(faceVertices.end(), corners, corners + count);
    if (normals) cornerNormals.insert(cornerNormals.end(), normals, normals + count);
    faceStart.push_back(uint32_t(faceVertices.size()));
  }
  // Triangles when every face is fanned: sum of (corners - 2), faces of fewer than 3 corners counting 0;
  // of faces [begin, end) when given.
  size_t triangleCount(size_t begin = 0, size_t end = SIZE_MAX) const {
    size_t n = 0;
    for (size_t f = begin; f < std::min(end, faceCount()); f++) n += faceSize(f) > 2 ? faceSize(f) - 2 : 0;
    return n;
  }
  // Face f's area vector: twice its area along its normal, the cross products of its fan from the first
  // corner summed (exact for planar polygons; orientation and smooth normals weigh faces by it).
  glm::dvec3 areaVector(size_t f) const {
    const uint32_t* c = face(f);
    const glm::dvec3 a(positions[c[0]]);
    glm::dvec3 n(0.0);
    for (uint32_t k = 1; k + 1 < faceSize(f); k++)
      n += glm::cross(glm::dvec3(positions[c[k]]) - a, glm::dvec3(positions[c[k + 1]]) - a);
    return n;
  }
};

struct SourceInstance {
  glm::mat4 transform{1.0f};
  uint32_t mesh = 0;
};

// What a mesh file holds: meshes (a glTF mesh used by several nodes appears once) and their instances.
// OBJ, OFF and PLY files hold one mesh and one identity instance.
struct SourceScene {
  std::vector<PolygonMesh> meshes;
  std::vector<std::string> meshNames;
  std::vector<SourceInstance> instances;
};

// ---- load_*.cpp -------------------------------------------------------------------------------------
// Reads .obj, .off, .ply, .gltf or .glb (by extension, case-insensitive). Polygons are kept as they are.
// Checks the syntax, counts, index ranges, buffer bounds and finiteness of positions; throws InputError.
// `threads`: OBJ and OFF files are read on up to that many threads (the other formats on one).
SourceScene loadMeshFile(const std::string& path, int threads = 1);
SourceScene loadObj(const std::string& path, int threads = 1);
SourceScene loadOff(const std::string& path, int threads = 1);
SourceScene loadPly(const std::string& path);
SourceScene loadGltf(const std::string& path);
// The scene of a single-mesh format: the mesh, shown once with the identity transform.
SourceScene singleMeshScene(PolygonMesh mesh);

// ---- repair.cpp -------------------------------------------------------------------------------------
struct RepairReport {
  size_t weldedVertices = 0;     // vertices merged because they had bit-identical positions
  size_t degenerateFaces = 0;    // dropped: fewer than 3 distinct corners after welding
  size_t duplicateFaces = 0;     // dropped: same corner set as an earlier face
  size_t nonManifoldEdges = 0;   // edges with more than two faces, or two faces of one orientation
  size_t splitVertices = 0;      // vertex copies added to make every edge and vertex manifold
  size_t boundaryEdges = 0;      // edges with one face after repair (0 means closed)
  size_t unusedVertices = 0;     // dropped: referenced by no face
  size_t dissolvedVertices = 0;  // taken out of the two faces that fold through them (valence 2)
  size_t flippedFaces = 0;       // turned to agree with their component (orientFaces)
  size_t components = 0;         // of faces joined through two-face edges
  size_t nonOrientableComponents = 0;
};
// Welds bit-identical positions, drops degenerate and duplicate faces, and splits non-manifold edges and
// vertices so that every edge has at most two faces of opposite orientation and every vertex has one fan.
// Throws InputError (naming `file`) when positions are not finite or nothing is left.
RepairReport repairMesh(PolygonMesh& mesh, const std::string& file, int threads = 1);
// Whether no two of `positions` are equal (-0 as +0), found by the weld's sort. A closed geometry's
// vertices are told apart by position, and the limit surface of a cage far larger than its detail
// (2.4e9 units long and 1 wide) can round distinct vertices onto one float position.
bool positionsDistinct(const std::vector<glm::vec3>& positions, int threads);

// ---- orient.cpp -------------------------------------------------------------------------------------
struct OrientReport {
  size_t flippedFaces = 0;
  size_t components = 0;               // faces joined through edges of exactly two faces
  size_t nonOrientableComponents = 0;  // e.g. a Moebius strip: left as they are
};
// An edge of a face: its vertices, the smaller first, and the corner it starts at in its face. Twelve
// bytes, no padding: repair sorts one for every corner of the mesh.
struct CornerEdge {
  uint32_t first, second, corner;
  uint64_t key() const { return uint64_t(first) << 32 | second; }
  bool operator<(const CornerEdge& o) const {
    return first != o.first ? first < o.first : second != o.second ? second < o.second : corner < o.corner;
  }
};
// What orientation leaves for repair's split step, which would otherwise make both again: every corner's
// edge of the oriented mesh sorted by (first, second, corner), and each corner's face. Where no face
// turned and no edge has more than two faces (almost every input), also each corner's partner: the
// corner of the other face on its edge, which walks it the other way, or UINT32_MAX on a boundary.
struct OrientedEdges {
  FillLaterVector<CornerEdge> edges;
  FillLaterVector<uint32_t> cornerFace;
  FillLaterVector<uint32_t> partner;  // empty unless as above
};
// Turns faces so that every component walks each of its two-face edges once each way, keeping the
// orientation of the larger part (by area) of each component. Deterministic; positions are not moved.
OrientReport orientFaces(PolygonMesh& mesh, int threads = 1, OrientedEdges* edges = nullptr);

// ---- split_fans.cpp ---------------------------------------------------------------------------------
// Repair's split step: a vertex for each fan of wedges (split copies and non-manifold edges counted in
// `report`). `oriented`: orientFaces' sorted corner edges and corner faces, freed as soon as they are
// used (this step sets repair's peak memory). `singleEdges`: edges with one face, which are the boundary
// edges when no vertex was split. Takes the positions from `faces`.
PolygonMesh splitNonManifold(PolygonMesh& faces, OrientedEdges&& oriented, RepairReport& report, int threads,
                             size_t& singleEdges);

// ---- topology.cpp -----------------------------------------------------------------------------------
struct SurfaceTopology {
  uint64_t triangles = 0;
  uint64_t components = 0;     // triangles joined through shared edges
  uint64_t boundaryLoops = 0;  // of edges with one triangle (loops that touch count once)
  uint64_t genus = 0;          // summed over the components, from V - E + F = 2 - 2g - b each
};
// An undirected edge as one key, min << 32 | max: the builder's edge sets and sorts use it.
inline uint64_t undirectedEdge(uint32_t a, uint32_t b) { return uint64_t(std::min(a, b)) << 32 | std::max(a, b); }
// The topology of the surface of `indices` (triangles, any vertex ids).
SurfaceTopology surfaceTopology(const std::vector<uint32_t>& indices);
// The edges (min << 32 | max, ascending) that one triangle of `indices` alone has: a cluster's or a
// group's border and open boundary.
std::vector<uint64_t> edgesUsedOnce(std::span<const uint32_t> indices);
// The same for vertex ids below `vertices` (a group's local ids): bucketed by lower vertex instead of
// hashed, so that a group's thousands of edges are counted in cache.
std::vector<uint64_t> edgesUsedOnceDense(std::span<const uint32_t> indices, uint32_t vertices);

// ---- cluster.cpp (the table the normals' sums and the leaf clusters' dual graph share) --------------
// Each vertex's faces, ascending (a face once for each of its corners at the vertex): vertex v's are
// faces[start[v] .. start[v + 1]). The same on any number of threads.
struct VertexFaces {
  FillLaterVector<size_t> start;
  FillLaterVector<uint32_t> faces;
};
VertexFaces vertexFaces(std::span<const uint32_t> faceStart, std::span<const uint32_t> faceVertices, size_t vertexCount,
                        int threads);

// ---- shading_normals.cpp ----------------------------------------------------------------------------
// A vertex's corners grouped by shading normal: wedge w sits at vertex wedgeVertex[w] with normal
// wedgeNormal[w]; the wedges of vertex v are wedgeStart[v] .. wedgeStart[v + 1].
struct ShadingNormals {
  std::vector<uint32_t> cornerWedge;  // one a corner of the mesh (faceVertices); empty when oneAVertex
  FillLaterVector<uint32_t> wedgeVertex;
  FillLaterVector<glm::vec3> wedgeNormal;  // unit
  FillLaterVector<uint32_t> wedgeStart;
  bool oneAVertex = true;  // every vertex has one: wedge w is vertex w
  uint32_t wedgeOfCorner(const PolygonMesh& mesh, uint32_t corner) const {
    return oneAVertex ? mesh.faceVertices[corner] : cornerWedge[corner];
  }
  // The wedge of `vertex` whose normal is nearest `faceNormal` (a coarse triangle's corner).
  uint32_t nearestWedge(uint32_t vertex, glm::vec3 faceNormal) const;
};
// Wedges of a leaf mesh: from `vertexNormals` when given (a subdivided cage's limit normals, one a
// vertex), else from the mesh's cornerNormals when it has them, else from its faces, with a crease
// wherever two faces meet at more than creaseAngleDegrees (180: smooth everywhere). The same on any
// number of threads. Where the sums of faces' normals at each vertex run on threads, they read
// vertexFaces(mesh), made into `leafFaces` (when given) for the caller to pass on to buildDag.
ShadingNormals shadingNormals(const PolygonMesh& mesh, std::span<const glm::vec3> vertexNormals,
                              float creaseAngleDegrees, int threads, VertexFaces* leafFaces = nullptr);

// ---- subdivide.cpp ----------------------------------------------------------------------------------
// Faces of `mesh` after `levels` rounds, computed without allocating; used to reject sizes that would not
// fit 32-bit indices before any work is done.
uint64_t subdividedFaceCount(const PolygonMesh& mesh, int levels);
// One round of Catmull-Clark on a manifold mesh (repairMesh's output). Output vertex order: the old
// vertices, then one per edge, then one per face; every output face is a quad (corner, edge, face, edge).
// Boundary edges use the cubic B-spline rules (edge point = midpoint, vertex = 3/4 V + 1/8 (A + B)); a
// boundary vertex with one face is a corner and stays put. Vertices from `vertexPoints` on keep their
// positions: a local neighbourhood (facesAround) holds the rings of its first vertices only, and only
// their vertex points are read.
PolygonMesh subdivideCatmullClark(const PolygonMesh& mesh, int threads = 1, size_t vertexPoints = SIZE_MAX);

// ---- quad_corners.cpp -------------------------------------------------------------------------------
// Whether every face has four corners, on up to `threads` threads for a large mesh.
bool allQuads(const PolygonMesh& mesh, int threads = 1);
// Each vertex's corners (of any polygon mesh) in corner order, corners[start[v] .. start[v + 1]): a
// counting sort, on up to `threads` threads for a large mesh.
void cornersByVertex(std::span<const uint32_t> faceVertices, size_t vertexCount, int threads,
                     FillLaterVector<uint32_t>& start, FillLaterVector<uint32_t>& corners);

// The corners of a quad mesh (every face 4 corners; corner c is faceVertices[c]) grouped by vertex.
class QuadCorners {
 public:
  explicit QuadCorners(const PolygonMesh& mesh, int threads = 1);
  // Vertex k places after corner c in its face (k = 1: next, 2: opposite, 3: previous).
  uint32_t at(uint32_t c, uint32_t k) const { return vertices_[c - c % 4 + (c % 4 + k) % 4]; }
  // The corner of vertex a whose next (withNext) or previous (withPrev) vertex is b; UINT32_MAX if none.
  uint32_t withNext(uint32_t a, uint32_t b) const;
  uint32_t withPrev(uint32_t a, uint32_t b) const;
  // The corners of vertex v: corners()[offsets()[v] .. offsets()[v + 1]).
  const FillLaterVector<uint32_t>& corners() const { return corners_; }
  const FillLaterVector<uint32_t>& offsets() const { return offsets_; }

 private:
  const FillLaterVector<uint32_t>& vertices_;
  FillLaterVector<uint32_t> offsets_, corners_, nextOf_;  // nextOf_[i]: the next vertex of corners_[i]
};

// The faces of a quad mesh touching any of `vertices` (first `firstFace`, when given), as a mesh of their
// own with `positions` whose vertices 0 .. count - 1 are `vertices`: what one round of subdivision needs
// to get those vertices' rings right (limit.cpp, mesh_patches.cpp). Small neighbourhoods: linear scans.
PolygonMesh facesAround(const PolygonMesh& mesh, const std::vector<glm::vec3>& positions, const QuadCorners& q,
                        const uint32_t* vertices, uint32_t count, uint32_t firstFace = UINT32_MAX);

// ---- limit.cpp --------------------------------------------------------------------------------------
// Moves every vertex of a quad mesh (a Catmull-Clark cage after >= 1 round) to its limit position and
// sets `normals` to the limit normals (oriented like the faces). Returns false, changing nothing, when
// some face is not a quad. Vertices are independent: on up to `threads` threads.
// `corners`, when given, are the mesh's (a Patcher's, made for the patches first).
bool moveToLimit(PolygonMesh& mesh, FillLaterVector<glm::vec3>& normals, int threads = 1,
                 const QuadCorners* corners = nullptr);

// The dot product of v with itself: glm::length(v) squared, to the bit.
[[gnu::always_inline]] inline double squaredLength(glm::dvec3 v) { return glm::dot(v, v); }

// Squared distance from p to the triangle abc (Ericson, Real-Time Collision Detection, 5.1.5). Always
// inlined: the chord errors call it for every sample of every face, in their innermost loop, and take one
// square root of the largest (glm::length is the root of the dot product, so the result is the same).
[[gnu::always_inline]] inline double pointTriangleDistanceSquared(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b,
                                                                  glm::dvec3 c) {
  glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return squaredLength(ap);
  glm::dvec3 bp = p - b;
  double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return squaredLength(bp);
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return squaredLength(p - (a + ab * (d1 / (d1 - d3))));
  glm::dvec3 cp = p - c;
  double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return squaredLength(cp);
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return squaredLength(p - (a + ac * (d2 / (d2 - d6))));
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return squaredLength(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  double denom = 1.0 / (va + vb + vc);
  return squaredLength(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

// Distance from p to the triangle abc.
[[gnu::always_inline]] inline double pointTriangleDistance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  return std::sqrt(pointTriangleDistanceSquared(p, a, b, c));
}

// ---- patch.cpp --------------------------------------------------------------------------------------
// Which control points make the limit-surface patch of a face of a quad mesh (a cage after >= 1 round;
// shaderio.h, Patch): topology only, positions are not read.
struct FacePatch {
  uint32_t kind = VGEO_PATCH_NONE;  // VGEO_PATCH_REGULAR, VGEO_PATCH_RING or VGEO_PATCH_NONE (no rule here)
  uint32_t corner = 0;              // ring: the extraordinary corner
  uint32_t valence = 0;             // ring: its valence
  uint32_t pointCount = 0;          // 16 (regular) or 2 valence + 8 (ring)
  uint32_t points[VGEO_MAX_RING];   // control points: vertex indices of the mesh; UINT32_MAX for a phantom
  // Phantom points beyond a boundary, in the order to compute them: points[slot] = 2 points[a] - points[b].
  uint32_t phantomCount = 0;
  uint8_t phantoms[12][3];                                                    // slot, a, b
  uint32_t neighbours[4] = {UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX};  // across edge k: face << 2 | its edge
  uint32_t info() const { return kind | corner << 2 | valence << 8; }         // as shaderio.h's Patch.info
};
class Patcher {
 public:
  // Each vertex's kind is found once, on up to `threads` threads (in a large mesh).
  explicit Patcher(const PolygonMesh& mesh, int threads = 1);
  // The face's patch: regular (four corners of valence 4, interior or on a boundary) or a ring (one
  // interior extraordinary corner); VGEO_PATCH_NONE for anything else, or when some face is not a quad.
  FacePatch patch(uint32_t face) const;
  const QuadCorners& corners() const { return corners_; }
  bool quads() const { return quads_; }  // every face of the mesh a quad

 private:
  enum class VertexKind : uint8_t { Interior, Boundary, Corner, Irregular };
  VertexKind findKind(uint32_t v) const;
  bool ring(uint32_t face, uint32_t corner, FacePatch& out) const;
  const PolygonMesh& mesh_;
  QuadCorners corners_;
  std::vector<VertexKind> kinds_;
  bool quads_ = false;
};
// The patch's control-point words (pointCount of them) into `words`: a mesh vertex v as vertexWord(v), a
// phantom point (computed from `positions`) as the word appendPoint(position) returns for it.
template <class VertexWord, class AppendPoint>
void writePatchWords(const FacePatch& patch, const std::vector<glm::vec3>& positions, uint32_t* words,
                     VertexWord vertexWord, AppendPoint appendPoint) {
  glm::vec3 points[VGEO_MAX_RING];
  for (uint32_t i = 0; i < patch.pointCount; i++)
    if (patch.points[i] != UINT32_MAX) points[i] = positions[patch.points[i]];
  for (uint32_t i = 0; i < patch.phantomCount; i++)
    points[patch.phantoms[i][0]] = 2.0f * points[patch.phantoms[i][1]] - points[patch.phantoms[i][2]];
  for (uint32_t i = 0; i < patch.pointCount; i++)
    words[i] = patch.points[i] != UINT32_MAX ? vertexWord(patch.points[i]) : appendPoint(points[i]);
}

// ---- mesh_patches.cpp -------------------------------------------------------------------------------
// Every face's patch as the .vgeo stores it (shaderio.h, Patch): Patcher's where it has one, else a tree
// of the face subdivided locally (VGEO_PATCH_TREE), so every face of a quad mesh gets the limit surface;
// where an eighth of the faces or more need a tree (a sample of them says), the trees' first level comes
// from one round of the whole mesh, whose points follow the control points in `points`.
// The words and the points they add are kept in blocks of kPatchBlockFaces consecutive faces, each block
// made whole while only its own faces' trees exist: the trees of a triangle cage's first round (every
// face one) would otherwise be held beside the whole result, twice its memory.
constexpr size_t kPatchBlockFaces = 8192;
struct MeshPatches {
  FillLaterVector<uint32_t> info;                       // per face: kind | corner << 2 | valence << 8
  FillLaterVector<uint32_t> first;                      // per face: its first word; faceCount + 1 entries
  FillLaterVector<std::array<uint32_t, 4>> neighbours;  // per face: across edge k, face << 2 | its edge
  FillLaterVector<glm::vec3> points;                    // the mesh's control points, then any shared round's
  // Per block of faces: its faces' words (control-point indices and tree nodes, shaderio.h), from word
  // first[its first face] on, and the phantom and tree points they add, numbered from pointsBefore
  // (the control points and every earlier block's points).
  struct Block {
    FillLaterVector<uint32_t> words;
    FillLaterVector<glm::vec3> points;
    uint32_t pointsBefore = 0;
  };
  std::vector<Block> blocks;
  bool patched(size_t face) const { return shaderio::patchKind(info[face]) != VGEO_PATCH_NONE; }
  // Face `face`'s words.
  const uint32_t* wordsOf(uint32_t face) const {
    return blocks[face / kPatchBlockFaces].words.data() +
           (first[face] - first[face / kPatchBlockFaces * kPatchBlockFaces]);
  }
  // Face `face`'s patch at (s, t), with its unit normal; not for VGEO_PATCH_NONE faces.
  glm::vec3 evaluate(uint32_t face, float s, float t, glm::vec3* normal = nullptr) const;
  // The same positions at `count` (<= 32) parameters of one face, sharing the work they have in common.
  void evaluateAt(uint32_t face, const glm::vec2* st, int count, glm::vec3* out) const;
};
// Where the trees' first level comes from: the whole mesh's round where enough faces need a tree (Auto),
// or always each tree's own round, or always the whole mesh's (the same surface: the tests compare them).
enum class TreeRounds { Auto, Own, Shared };
MeshPatches buildPatches(const PolygonMesh& mesh, const std::vector<glm::vec3>& controlPoints, uint32_t threads,
                         TreeRounds rounds = TreeRounds::Auto);
// The same with the caller's Patcher of `mesh` (whose corners moveToLimit can take after).
MeshPatches buildPatches(const PolygonMesh& mesh, const std::vector<glm::vec3>& controlPoints, const Patcher& patcher,
                         uint32_t threads, TreeRounds rounds = TreeRounds::Auto);

// Chord errors of a face's leaf geometry against its patch, object space: edge[k] the largest distance of
// the limit curve of edge k from its segment, the same value on both faces of an edge (measured once, by
// the face of the lower index); face the largest distance of the surface from the face's two triangles, and
// at least every edge's. Zero for VGEO_PATCH_NONE faces. Plain data (PatchErrors{} is all zero), so that a
// face's entry of the list is written once, on the threads.
struct PatchErrors {
  float edge[4];
  float face;
  bool patched;  // the face has a patch (not VGEO_PATCH_NONE)
};
using PatchErrorList = FillLaterVector<PatchErrors>;
// Every face's chord errors (sampled at quarters of the parameters and scaled up 12% for what falls between).
// `limitMesh` holds the leaf vertices (limit positions).
PatchErrorList patchChordErrors(const PolygonMesh& limitMesh, const MeshPatches& patches, uint32_t threads);

// ---- partition.cpp ----------------------------------------------------------------------------------
// A graph in compressed rows: node i's neighbours are adjacency[offsets[i] .. offsets[i+1]).
struct Graph {
  FillLaterVector<uint32_t> offsets{0};
  FillLaterVector<uint32_t> adjacency;
  size_t nodeCount() const { return offsets.size() - 1; }
};
// A graph whose edges have weights: weights[e] beside adjacency[e].
struct WeightedGraph {
  std::vector<uint32_t> offsets{0}, adjacency, weights;
  size_t nodeCount() const { return offsets.size() - 1; }
};
// Groups of about `target` connected nodes with light edges between groups (group_merge.cpp):
// group[v] is node v's, numbered in order of first node; returns how many. No group holds more than
// target + target / 3 nodes; a group with no neighbour that fits may hold fewer than target. Groups
// of whole components (no edge out) are joined by the nearness of their nodes' `centroids`, and
// only those can be disconnected.
uint32_t mergeIntoGroups(const WeightedGraph& graph, const glm::vec3* centroids, uint32_t target, uint32_t* group);
// The parts as contiguous runs of a node permutation: part p is order[partStart[p] .. partStart[p+1]).
struct Partition {
  FillLaterVector<uint32_t> order;
  std::vector<uint32_t> partStart{0};
  size_t partCount() const { return partStart.size() - 1; }
};
// Splits the nodes into parts of total weight <= maxWeight by recursive bisection: a set of weight w
// becomes ceil(w / targetWeight) parts of near equal weight (so parts are nearly full), each cut growing
// one side from the set's extreme node in order of distance, so parts are compact and connected where
// the graph allows. Then pieces cut off from their part move to a neighbouring part with room (up to
// maxWeight). `fits(nodes, count)` may reject a part (then it is split in two); it must be monotonic:
// a set that fits still fits with some of its nodes taken out. Every node weight must be
// <= targetWeight <= maxWeight. Deterministic for any thread count.
Partition partitionGraph(const Graph& graph, const std::vector<uint8_t>& weights,
                         const FillLaterVector<glm::vec3>& positions, uint32_t maxWeight, uint32_t targetWeight,
                         int threads, const std::function<bool(const uint32_t*, size_t)>& fits = {});

// ---- cluster.cpp ------------------------------------------------------------------------------------
// A cluster under construction: triangles as absolute vertex index triples.
struct BuildCluster {
  std::vector<uint32_t> indices;    // 3 per triangle, <= 128 triangles, <= 256 distinct vertices
  std::vector<uint32_t> cageFaces;  // leaves: the cage faces it holds (their triangles are consecutive)
  std::vector<uint32_t> wedges;     // the wedge of each index, where the mesh has hard edges (else empty)
  // Its border: the edges (min << 32 | max, ascending) that one of its triangles alone has, as
  // edgesUsedOnce(indices) gives them, found when a simplified group is split and for the leaves
  // before the first round (its round's grouping and chord rule read them); grouping counts them
  // where they are empty.
  std::vector<uint64_t> border;
  glm::vec4 selfSphere{0.0f};
  float selfError = 0.0f;
  uint32_t producer = VGEO_NO_GROUP;  // the group that produced it
  uint32_t group = VGEO_NO_GROUP;     // the group it belongs to
  uint32_t level = 0;
};
// The triangles a cluster is cut to, leaves and simplified groups alike: nearly full, with the last
// few of VGEO_MAX_CLUSTER_TRIANGLES left as room to merge a cut-off piece back into a neighbour.
constexpr uint32_t kClusterFill = 126;
// Faces of more than kMaxLeafFaceCorners corners are replaced by triangle strips (zigzag from both ends,
// no corner in more than four triangles): they could not be patches and might not fit one cluster. Call before
// buildLeafClusters (a no-op on subdivided meshes).
constexpr uint32_t kMaxLeafFaceCorners = 66;
void triangulateLargeFaces(PolygonMesh& mesh, int threads);
// Appends the triangles of face v[0..n): a quad split along its shorter diagonal, other faces fanned.
void triangulateFace(const glm::vec3* positions, const uint32_t* v, uint32_t n, std::vector<uint32_t>& out);
// A quad's two triangles as triangulateFace makes them, into out.
void triangulateQuad(const glm::vec3* positions, const uint32_t* v, uint32_t out[6]);
// Leaf clusters from whole faces of `mesh` (a face's triangles never part): faces adjacent by an edge
// are graph neighbours, weighted by their triangle count. cageFaces lists each cluster's faces, whose
// triangles follow in that order (quads split along the shorter diagonal, other faces fanned).
// With `shading` that has hard edges, the vertex limit counts wedges and each cluster lists its corners'.
// `around`: vertexFaces(mesh) when the caller has it (taken over and freed once used), else empty.
std::vector<BuildCluster> buildLeafClusters(const PolygonMesh& mesh, int threads,
                                            const ShadingNormals* shading = nullptr, VertexFaces* around = nullptr);
struct SimplifiedGroup;
// Splits a simplified group's triangles into clusters (absolute vertex indices) by edge adjacency;
// with `shading` as above, each corner takes the wedge nearest its triangle's normal.
std::vector<BuildCluster> splitIntoClusters(const SimplifiedGroup& group, const std::vector<glm::vec3>& positions,
                                            const ShadingNormals* shading = nullptr);

// ---- local_ids.cpp ----------------------------------------------------------------------------------
// The distinct vertices of `indices` in order of first use (globals) and `indices` renumbered to
// them (local[i] indexes globals); memory in proportion to the list, not to the mesh.
void localIds(const std::vector<uint32_t>& indices, std::vector<uint32_t>& globals, std::vector<uint32_t>& local);
// The number of distinct vertices of `indices` (the size localIds would give globals), without the lists.
size_t distinctCount(const std::vector<uint32_t>& indices);

// ---- bounds.cpp -------------------------------------------------------------------------------------
// Smallest sphere enclosing the points (CGAL), rounded outward so that float tests agree.
glm::vec4 sphereOfPoints(const std::vector<glm::vec3>& positions, const uint32_t* vertices, size_t count);
// Smallest sphere enclosing the spheres (CGAL), rounded outward so that float tests agree.
glm::vec4 sphereOfSpheres(const glm::vec4* spheres, size_t count);
struct BuildCluster;
// What the file keeps of a cluster's extent: the cone of its triangle normals (shaderio.h,
// clusterFacesAway: axis the normalised mean of the unit normals, w the sine of the widest angle from
// it, -1 from 90 degrees on), the sphere of its own vertices (a leaf's is its self sphere) and their count.
struct ClusterBounds {
  glm::vec4 cone{0.0f}, sphere{0.0f};
  uint32_t vertexCount = 0;
};
// `shading` maps the cluster's wedges to their vertices (null: its ids are the vertices).
ClusterBounds clusterBounds(const BuildCluster& c, const std::vector<glm::vec3>& positions,
                            const ShadingNormals* shading);

// ---- group.cpp --------------------------------------------------------------------------------------
struct GroupPlan {
  std::vector<uint32_t> clusters;  // cluster ids, ascending
  bool isWholeComponent = false;   // no cluster outside the group shares an edge with it
};
// Partitions the `active` clusters into groups of about `targetSize` neighbours: mergeIntoGroups on
// the graph of clusters sharing an edge, edges weighted by the shared edge count, so that groups have
// short borders (the locked part of the next simplification). A level of more than kGroupingPiece * 2
// clusters is first cut into compact pieces of about kGroupingPiece (partitionGraph, by the clusters'
// centroids over `positions`), each grouped on its own, side by side. The same groups on any thread
// count. `openEdges`, when given, receives the
// edges (min << 32 | max, ascending) on the border of one cluster only: the open boundary of the
// surface, which is no group's shared border. `beside`, when given, runs on the threads beside the
// partition (it must not touch what grouping reads), after the graph is made.
constexpr uint32_t kGroupingPiece = 2048;
std::vector<GroupPlan> groupClusters(const std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& active,
                                     const std::vector<glm::vec3>& positions, uint32_t targetSize, int threads,
                                     std::vector<uint64_t>* openEdges = nullptr,
                                     const std::function<void()>& beside = {});

// ---- simplify.cpp -----------------------------------------------------------------------------------
struct SimplifiedGroup {
  std::vector<uint32_t> indices;  // the simplified triangles, as positions in `globals`
  std::vector<uint32_t> globals;  // the group's absolute vertex indices (those the simplifier removed too)
  float error = 0.0f;             // object-space error added by this simplification
  int relaxation = 0;             // 1 when it needed an error above 2% of the group's size to get there
  bool halved = false;            // reached <= 55% of the input triangles
};
// Simplifies a group's triangles to `targetTriangles` (about half) by quadric-error half-edge collapses
// with the group border (edges without a twin inside the group that another cluster has) locked,
// keeping the surface manifold (link condition, no flips). Edges of `openEdges` (absolute ids,
// min << 32 | max, ascending) are the surface's open boundary: their vertices, unless also on the
// locked border, collapse along it. A new edge between two locked vertices a, b (absolute ids) is made
// only if chordAllowed(a, b).
SimplifiedGroup simplifyGroup(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                              const std::function<bool(uint32_t, uint32_t)>& chordAllowed,
                              const std::vector<uint64_t>& openEdges, size_t targetTriangles);

// ---- dag.cpp ----------------------------------------------------------------------------------------
struct BuildOptions {
  int threads = 1;
  uint32_t groupSize = 16;
  // Chord error of each face against the limit surface (patchChordErrors); a leaf cluster's self error
  // is the largest of its faces'. Empty: leaves have error 0 (the input is the surface).
  const PatchErrorList* leafFaceErrors = nullptr;
  // The leaf mesh's wedges; clusters list them only where some vertex has two (a hard edge).
  const ShadingNormals* shading = nullptr;
  // vertexFaces of the leaf mesh when shadingNormals made it (empty otherwise): taken over by the leaf
  // clusters' dual graph and freed there.
  VertexFaces* leafFaces = nullptr;
  // Every leaf triangle is a face that repair checked, none split along a diagonal: repair left each
  // directed edge on one face at most, so no leaf triangles can fold onto each other.
  bool leavesAreRepairedFaces = false;
  std::function<void(double fraction, const char* stage)> progress;
  StageTimes* times = nullptr;  // where the DAG's steps add their seconds (leaves, grouping, ...)
};
struct BuildGroup {
  std::vector<uint32_t> members;  // cluster ids
  glm::vec4 sphere{0.0f};
  float error = 0.0f;  // +inf for root groups
  uint32_t level = 0;
};
// A mesh's LOD DAG before it is laid out into a file.
struct Dag {
  std::vector<BuildCluster> clusters;
  std::vector<BuildGroup> groups;
  std::vector<uint32_t> levelClusters;   // clusters formed in each round (round 0: the leaves)
  std::vector<uint64_t> levelTriangles;  // triangles of the active set after each round
  uint32_t relaxedGroups = 0;            // groups that needed any relaxation (see SimplifiedGroup)
  uint32_t stuckGroups = 0;              // groups that could not be halved; their clusters were retried
  uint32_t rootClusters = 0;
  SurfaceTopology roots;              // of the root clusters' triangles together
  std::vector<ClusterBounds> bounds;  // one a cluster
};
// A surface the DAG cannot be built on (it folds onto itself: two leaf triangles hold the same edge in
// the same direction, so no cut of it is watertight); buildScene reports it as an InputError.
struct SurfaceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// Builds the DAG of a repaired mesh whose faces are the leaf faces (the level-N cage). Throws
// SurfaceError when the leaf triangles fold onto themselves.
Dag buildDag(const PolygonMesh& mesh, const BuildOptions& options);

// ---- bvh.cpp ----------------------------------------------------------------------------------------
// A BVH over groups: one subtree per level under one root, VGEO_BVH_WIDTH children a node. Group ids in
// leaves are indices into `groups`; node 0 is the root.
struct Bvh {
  std::vector<shaderio::BvhNode> nodes;
  std::vector<uint32_t> groupOrder;  // groups in leaf order: leaves reference runs of this array
};
Bvh buildBvh(const std::vector<BuildGroup>& groups);

}  // namespace vgeo

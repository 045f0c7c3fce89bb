// mesh_patches.cpp: every face's limit-surface patch in the form the .vgeo stores it (shaderio.h, Patch),
// and the chord errors of the leaf triangles against it.
// - Where patch.cpp has a rule (a B-spline patch, with phantom points beyond a boundary, or Stam's ring)
//   the face's words are its control points; phantom points are appended to the control points.
// - Anywhere else the face is subdivided locally, as in feature-adaptive subdivision (Niessner, Loop,
//   Meyer & DeRose, "Feature-adaptive GPU rendering of Catmull-Clark subdivision surfaces", TOG 2012):
//   the faces sharing a vertex with it (all that its four sub-faces and their 4 x 4 neighbourhoods depend
//   on) are subdivided once with subdivide.cpp's rules; each sub-face that patch.cpp covers becomes a
//   leaf of the face's quadtree, the others are split again, down to VGEO_MAX_PATCH_DEPTH levels, where
//   the remaining quadrant (1/64 of the face, inside the finest tessellation step) is bilinear between its
//   corners' limit points. Two extraordinary corners (--subdiv 1 of a triangle mesh) take one level, an
//   extraordinary vertex on a boundary all six.
// - Where many faces need a tree, their first level is one round of the whole mesh instead, made once:
//   its points follow the control points and serve every tree that reads them (a round is local, so the
//   whole mesh's gives each sub-face the neighbourhood a face's own round would).
#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {
namespace {

// A face's quadtree: words relative to the patch's first word, point words indexing `points`, or, with
// kShared set, the mesh's shared points (MeshPatches::points) by their own index.
struct PatchTree {
  static constexpr uint32_t kShared = 0x80000000u;
  std::vector<uint32_t> words;
  std::vector<glm::vec3> points;

  uint32_t append(glm::vec3 p) {
    points.push_back(p);
    return uint32_t(points.size() - 1);
  }

  // Fills the four child words at `payload` with the sub-faces of face 0 of `local` (the faces sharing a
  // vertex with it: facesAround), at depth + 1; its sub-face at corner k is face k after one round.
  void split(const PolygonMesh& local, int depth, size_t payload) {
    const PolygonMesh sub = subdivideCatmullClark(local, 1, 4);
    const Patcher patcher(sub);
    std::vector<uint32_t> pointOf(sub.positions.size(), UINT32_MAX);  // shared by the sub-faces' patches
    addChildren(sub, patcher, 0, depth, payload, [&](uint32_t v) {
      return pointOf[v] != UINT32_MAX ? pointOf[v] : (pointOf[v] = append(sub.positions[v]));
    });
  }

  // The same from a round of the whole mesh made once (`fine`, with its Patcher), whose vertices are
  // shared points from `fineBase` on: the face's sub-face at corner k is fine face firstFace + k.
  void splitFine(const PolygonMesh& fine, const Patcher& finePatcher, uint32_t firstFace, uint32_t fineBase) {
    addChildren(fine, finePatcher, firstFace, 0, 0, [&](uint32_t v) { return kShared | (fineBase + v); });
  }

  // The child words at `payload`: child k is face firstFace + k of `sub`, a round below depth `depth`;
  // pointOf(v) is the point word of sub's vertex v, shared by the children.
  template <class PointOf>
  void addChildren(const PolygonMesh& sub, const Patcher& patcher, uint32_t firstFace, int depth, size_t payload,
                   PointOf&& pointOf) {
    PolygonMesh limit;
    for (uint32_t child = 0; child < 4; child++) {
      const uint32_t face = firstFace + child;
      words[payload + child] = uint32_t(words.size());
      const FacePatch patch = patcher.patch(face);
      if (patch.kind != VGEO_PATCH_NONE) {
        words.push_back(patch.info());
        const size_t at = words.size();
        words.resize(at + patch.pointCount);
        writePatchWords(patch, sub.positions, words.data() + at, pointOf, [&](glm::vec3 p) { return append(p); });
      } else if (depth + 1 < VGEO_MAX_PATCH_DEPTH) {
        words.push_back(VGEO_PATCH_TREE);
        const size_t at = words.size();
        words.resize(at + 4);
        split(facesAround(sub, sub.positions, patcher.corners(), sub.face(face), 4, face), depth + 1, at);
      } else {
        if (limit.faceCount() == 0) {
          FillLaterVector<glm::vec3> normals;
          limit = sub;
          moveToLimit(limit, normals);
        }
        words.push_back(VGEO_PATCH_NONE);
        for (uint32_t k = 0; k < 4; k++) {
          words.push_back(uint32_t(points.size()));
          points.push_back(limit.positions[limit.face(face)[k]]);
        }
      }
    }
  }
};

// Squared, as pointTriangleDistanceSquared: the chord errors take one square root of the largest.
double pointSegmentDistanceSquared(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b) {
  glm::dvec3 ab = b - a;
  double len2 = glm::dot(ab, ab);
  double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return squaredLength(p - (a + t * ab));
}

// The share of faces that need a tree, from up to kTreeSamples faces spread evenly (the same on any thread
// count).
constexpr size_t kTreeSamples = 1024;
// One round of the whole mesh with its Patcher costs about 1 us a face on one thread, a tree's own round
// about 9 (armadillo --subdiv 1): from one face in eight needing a tree on, the shared round costs less.
constexpr double kFineRoundTreeShare = 0.125;
constexpr size_t kSharedTreeBatchBlocks = 2;  // blocks a batch after shared-round trees (words alone held)
double treeShare(const Patcher& patcher, size_t faceCount) {
  if (faceCount == 0) return 0.0;
  const size_t stride = std::max<size_t>(1, faceCount / kTreeSamples);
  size_t sampled = 0, trees = 0;
  for (size_t f = 0; f < faceCount; f += stride, sampled++) trees += patcher.patch(uint32_t(f)).kind == VGEO_PATCH_NONE;
  return double(trees) / double(sampled);
}

// The control points copied; the per-face arrays sized, not filled.
MeshPatches sized(const PolygonMesh& mesh, const std::vector<glm::vec3>& controlPoints, uint32_t threads) {
  MeshPatches out;
  out.info.resize(mesh.faceCount());
  out.first.resize(mesh.faceCount() + 1);
  out.first[0] = 0;
  out.neighbours.resize(mesh.faceCount());
  out.points.resize(controlPoints.size());
  parallelForRanges(controlPoints.size(), int(threads), [&](size_t begin, size_t end) {
    std::copy(controlPoints.begin() + long(begin), controlPoints.begin() + long(end), out.points.begin() + long(begin));
  });
  return out;
}

// No face patched.
MeshPatches unpatched(const PolygonMesh& mesh, const std::vector<glm::vec3>& controlPoints, uint32_t threads) {
  MeshPatches out = sized(mesh, controlPoints, threads);
  parallelForRanges(mesh.faceCount(), int(threads), [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++) {
      out.info[f] = VGEO_PATCH_NONE;
      out.first[f + 1] = 0;
      out.neighbours[f] = {UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX};
    }
  });
  return out;
}

}  // namespace

MeshPatches buildPatches(const PolygonMesh& mesh, const std::vector<glm::vec3>& controlPoints, uint32_t threads,
                         TreeRounds rounds) {
  if (controlPoints.size() != mesh.positions.size()) return unpatched(mesh, controlPoints, threads);
  return buildPatches(mesh, controlPoints, Patcher(mesh, int(threads)), threads, rounds);
}

MeshPatches buildPatches(const PolygonMesh& mesh, const std::vector<glm::vec3>& controlPoints, const Patcher& patcher,
                         uint32_t threads, TreeRounds rounds) {
  // Every face a quad (the Patcher knows) and the control points the mesh's: what the Patcher and the
  // trees need.
  if (!patcher.quads() || controlPoints.size() != mesh.positions.size()) return unpatched(mesh, controlPoints, threads);
  const size_t faceCount = mesh.faceCount();
  MeshPatches out = sized(mesh, controlPoints, threads);  // every face's entries written below
  // Where many faces need trees (a triangle cage after its first round: two extraordinary corners a
  // face), their first level comes from one more round of the whole mesh, made once and shared, instead
  // of a round of each face's own neighbourhood (each vertex was subdivided about nine times over).
  // Elsewhere the trees are few and the whole round would cost far more than theirs.
  // The round's points follow the control points and serve every tree: a point of that round is
  // stored once, where each tree held its own copy of about 40.
  std::unique_ptr<const PolygonMesh> fine;
  std::unique_ptr<const Patcher> finePatcher;
  const uint32_t fineBase = uint32_t(controlPoints.size());
  // The round has a vertex, an edge and a face point for each vertex, edge (at most 4 a quad) and face:
  // the control points and all of those must fit the 31 bits a shared point word gives them.
  const bool roundFits = 2 * uint64_t(fineBase) + 5 * uint64_t(faceCount) < PatchTree::kShared;
  if (roundFits && (rounds == TreeRounds::Shared ||
                    (rounds == TreeRounds::Auto && treeShare(patcher, faceCount) >= kFineRoundTreeShare))) {
    const bool ownPositions = &controlPoints == &mesh.positions;
    PolygonMesh withPoints;  // the mesh with `controlPoints`, where they are not its own positions
    if (!ownPositions) {
      withPoints = mesh;
      withPoints.positions = controlPoints;
    }
    fine = std::make_unique<const PolygonMesh>(subdivideCatmullClark(ownPositions ? mesh : withPoints, int(threads)));
    finePatcher = std::make_unique<const Patcher>(*fine, int(threads));
    out.points.resize(fineBase + fine->positions.size());
    parallelForRanges(fine->positions.size(), int(threads), [&](size_t begin, size_t end) {
      std::copy(fine->positions.begin() + long(begin), fine->positions.begin() + long(end),
                out.points.begin() + long(fineBase + begin));
    });
  }
  // A batch of blocks at a time: sizes first (words and extra points a face), trees built on the way;
  // then each block is sized and every face writes its part and frees its tree. A batch is one block
  // after a batch that made trees of their own rounds (their points are held until written), two after
  // one whose trees read the shared round (words alone: eight raised a 16-thread build's peak by a fifth
  // for no time), else a block for every two threads: one block's two loops are too short for 16
  // threads, whose start and finish then cost as much as the work.
  const size_t mostBlocks = std::clamp<size_t>(threads / 2, 1, 8);
  std::vector<uint32_t> extraBefore(mostBlocks * kPatchBlockFaces);  // in the face's block
  std::vector<std::unique_ptr<PatchTree>> trees(mostBlocks * kPatchBlockFaces);
  // The batch's patches, found while sizing and written after: room that each face's own thread fills
  // (a vector would zero its 2 MB a block on this thread first).
  static_assert(std::is_trivially_destructible_v<FacePatch>);
  const std::unique_ptr<std::byte[]> patchRoom(new std::byte[mostBlocks * kPatchBlockFaces * sizeof(FacePatch)]);
  FacePatch* const facePatches = reinterpret_cast<FacePatch*>(patchRoom.get());
  uint32_t pointsBefore = uint32_t(out.points.size());
  size_t batchBlocks = 1;
  for (size_t batchFirst = 0; batchFirst < faceCount;) {
    const size_t batchFaces = std::min(batchBlocks * kPatchBlockFaces, faceCount - batchFirst);
    parallelFor(batchFaces, int(threads), [&](size_t i) {
      const size_t f = batchFirst + i;
      const FacePatch& patch = *new (&facePatches[i]) FacePatch(patcher.patch(uint32_t(f)));
      for (int k = 0; k < 4; k++) out.neighbours[f][size_t(k)] = patch.neighbours[k];
      if (patch.kind != VGEO_PATCH_NONE) {
        out.info[f] = patch.info();
        out.first[f + 1] = patch.pointCount;
        extraBefore[i] = patch.phantomCount;
        return;
      }
      trees[i] = std::make_unique<PatchTree>();
      trees[i]->words.resize(4);
      if (fine)  // a quad a corner, in corner order: face f's sub-face at corner k is fine face 4f + k
        trees[i]->splitFine(*fine, *finePatcher, uint32_t(4 * f), fineBase);
      else
        trees[i]->split(facesAround(mesh, controlPoints, patcher.corners(), mesh.face(f), 4, uint32_t(f)), 0, 0);
      out.info[f] = VGEO_PATCH_TREE;
      out.first[f + 1] = uint32_t(trees[i]->words.size());
      extraBefore[i] = uint32_t(trees[i]->points.size());
    });
    bool madeTrees = false;
    const size_t blocksBefore = out.blocks.size();
    std::vector<uint32_t> extraCount;
    for (size_t blockFirst = 0; blockFirst < batchFaces; blockFirst += kPatchBlockFaces) {
      const size_t blockFaces = std::min(kPatchBlockFaces, batchFaces - blockFirst);
      uint32_t extra = 0;
      for (size_t i = blockFirst; i < blockFirst + blockFaces; i++) {
        out.first[batchFirst + i + 1] += out.first[batchFirst + i];
        madeTrees = madeTrees || trees[i];
        extra += std::exchange(extraBefore[i], extra);
      }
      out.blocks.emplace_back().pointsBefore = pointsBefore;
      extraCount.push_back(extra);
      pointsBefore += extra;
    }
    // The blocks' arrays allocated on the threads: on huge pages, the first touch of an allocation (the
    // allocator's own header) zeroes its 2 MB, which on one thread held the other fifteen waiting.
    parallelFor(extraCount.size(), int(threads), [&](size_t b) {
      const size_t f0 = batchFirst + b * kPatchBlockFaces,
                   f1 = std::min(f0 + kPatchBlockFaces, batchFirst + batchFaces);
      MeshPatches::Block& block = out.blocks[blocksBefore + b];
      block.words.resize(out.first[f1] - out.first[f0]);
      block.points.resize(extraCount[b]);
    });
    parallelFor(batchFaces, int(threads), [&](size_t i) {
      const size_t f = batchFirst + i;
      MeshPatches::Block& block = out.blocks[f / kPatchBlockFaces];
      const size_t blockFirstFace = f / kPatchBlockFaces * kPatchBlockFaces;
      uint32_t* words = block.words.data() + (out.first[f] - out.first[blockFirstFace]);
      const uint32_t extraFirst = extraBefore[i];
      if (trees[i]) {
        const PatchTree& tree = *trees[i];
        std::copy(tree.words.begin(), tree.words.end(), words);
        std::copy(tree.points.begin(), tree.points.end(), block.points.begin() + extraFirst);
        const uint32_t extra = block.pointsBefore + extraFirst;
        shaderio::forEachPatchPoint(out.info[f], words, tree.words.size(), [&](size_t k) {
          words[k] = words[k] & PatchTree::kShared ? words[k] & ~PatchTree::kShared : words[k] + extra;
        });
        trees[i].reset();
        return;
      }
      uint32_t next = extraFirst;
      writePatchWords(
          facePatches[i], controlPoints, words, [](uint32_t v) { return v; },
          [&](glm::vec3 p) {
            block.points[next] = p;
            return block.pointsBefore + next++;
          });
    });
    batchFirst += batchFaces;
    batchBlocks = !madeTrees ? mostBlocks : fine ? std::min(kSharedTreeBatchBlocks, mostBlocks) : 1;
  }
  return out;
}

// A face's points are control points or its own block's; the lookup is made once for all its reads.
template <class Evaluate>
auto withFacePoints(const MeshPatches& patches, uint32_t face, Evaluate&& evaluate) {
  const MeshPatches::Block& block = patches.blocks[face / kPatchBlockFaces];
  const glm::vec3 *control = patches.points.data(), *added = block.points.data();
  const uint32_t before = block.pointsBefore;
  return evaluate([=](uint32_t i) { return i < before ? control[i] : added[i - before]; });
}

glm::vec3 MeshPatches::evaluate(uint32_t face, float s, float t, glm::vec3* normal) const {
  glm::vec3 n;
  glm::vec3 p = withFacePoints(*this, face, [&](auto point) {
    return shaderio::evaluatePatchWords(
        info[face], wordsOf(face), point, [](uint32_t) { return glm::vec3(0.0f); }, s, t, n);
  });
  if (normal) *normal = n;
  return p;
}

void MeshPatches::evaluateAt(uint32_t face, const glm::vec2* st, int count, glm::vec3* out) const {
  withFacePoints(*this, face, [&](auto point) {
    shaderio::evaluatePatchWordsAt(
        info[face], wordsOf(face), point, [](uint32_t) { return glm::vec3(0.0f); }, st, count, out);
  });
}

PatchErrorList patchChordErrors(const PolygonMesh& limitMesh, const MeshPatches& patches, uint32_t threads) {
  const size_t faceCount = limitMesh.faceCount();
  if (patches.info.size() != faceCount) return parallelFilled(faceCount, PatchErrors{}, int(threads));
  PatchErrorList own(faceCount), merged(faceCount);  // every face's entry written below
  const std::vector<glm::vec3>& x = limitMesh.positions;
  // Quarter parameters: the bulge of a bicubic between its corners peaks near the middle; 12% more
  // covers what falls between the samples (tests/test_patch.cpp checks against 16ths). An edge is
  // measured once, by the face of the lower index (or the only one, on a boundary).
  constexpr float kSlack = 1.12f;
  constexpr size_t kAheadFaces = 4;
  static const float kCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  parallelFor(faceCount, int(threads), [&](size_t f) {
    PatchErrors& e = own[f] = PatchErrors{};
    if (!patches.patched(f)) return;
    e.patched = true;
    const uint32_t* v = limitMesh.face(f);
    // A face's corners are points of three rounds' arrays (vertex, edge and face points), a miss each;
    // asked for a few faces ahead, they arrive while this face's patch is evaluated.
    if (f + kAheadFaces < faceCount)
      for (int k = 0; k < 4; k++) __builtin_prefetch(&x[limitMesh.face(f + kAheadFaces)[k]]);
    // The samples: quarters along each edge this face measures, then the 3 x 3 inner quarters.
    glm::vec2 st[21];
    int count = 0, edgeFirst[4];
    for (int k = 0; k < 4; k++) {
      const uint32_t n = patches.neighbours[f][size_t(k)];
      edgeFirst[k] = n != UINT32_MAX && (n >> 2) < f ? -1 : count;
      if (edgeFirst[k] < 0) continue;
      for (int i = 1; i < 4; i++) {
        float u = float(i) / 4.0f;
        st[count++] = {kCorner[k][0] + u * (kCorner[(k + 1) % 4][0] - kCorner[k][0]),
                       kCorner[k][1] + u * (kCorner[(k + 1) % 4][1] - kCorner[k][1])};
      }
    }
    const int inner = count;
    for (int i = 1; i < 4; i++)
      for (int j = 1; j < 4; j++) st[count++] = {float(i) / 4.0f, float(j) / 4.0f};
    glm::vec3 p[21];
    patches.evaluateAt(uint32_t(f), st, count, p);
    for (int k = 0; k < 4; k++) {
      if (edgeFirst[k] < 0) continue;
      glm::dvec3 a(x[v[k]]), b(x[v[(k + 1) % 4]]);
      double worst = 0.0;  // squared
      for (int i = 0; i < 3; i++)
        worst = std::max(worst, pointSegmentDistanceSquared(glm::dvec3(p[edgeFirst[k] + i]), a, b));
      e.edge[k] = float(std::sqrt(worst) * kSlack);
    }
    uint32_t tris[6];
    triangulateQuad(x.data(), v, tris);
    double worst = 0.0;  // squared: the root of the largest is the largest root, to the bit
    for (int i = inner; i < count; i++) {
      // The nearer triangle's distance; the second is needed only where the first is past the worst.
      glm::dvec3 q(p[i]);
      double d = pointTriangleDistanceSquared(q, x[tris[0]], x[tris[1]], x[tris[2]]);
      if (d > worst) d = std::min(d, pointTriangleDistanceSquared(q, x[tris[3]], x[tris[4]], x[tris[5]]));
      worst = std::max(worst, d);
    }
    e.face = float(std::sqrt(worst) * kSlack);
  });
  // One value an edge, the measuring face's (0 next to a flat face: the edge stays straight there); a
  // face's error covers its edges'.
  parallelFor(faceCount, int(threads), [&](size_t f) {
    PatchErrors& out = merged[f] = PatchErrors{};
    if (!own[f].patched) return;
    out.patched = true;
    out.face = own[f].face;
    for (int k = 0; k < 4; k++) {
      const uint32_t n = patches.neighbours[f][size_t(k)];
      out.edge[k] = n == UINT32_MAX        ? own[f].edge[k]
                    : !own[n >> 2].patched ? 0.0f
                    : (n >> 2) < f         ? own[n >> 2].edge[n & 3]
                                           : own[f].edge[k];
      out.face = std::max(out.face, out.edge[k]);
    }
  });
  return merged;
}

}  // namespace vgeo

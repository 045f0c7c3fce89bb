// split_fans.cpp: repair's step 5 (repair.cpp), every face corner a wedge, wedges joined across manifold
// edges (two faces walking the edge opposite ways), one output vertex for each fan. At an edge with more
// than two faces, or two of one orientation, the first face and the first later face of opposite
// orientation stay joined; the other faces' wedges there get vertices of their own. The joins are a
// union-find over every corner; where every edge is manifold (almost every input) a walk around each
// vertex first finds whether any vertex has two fans (its turns read off orientation's partners where
// it left them), and without one the faces are kept as they are.
#include <algorithm>

#include "../common/parallel.h"
#include "builder.h"
#include "union_find.h"

namespace vgeo {
namespace {

// Flags of a corner in splitNonManifold's scratch array; flagCorner adds one from any thread.
constexpr uint8_t kIsolated = 1;   // its wedge gets a vertex of its own
constexpr uint8_t kPathStart = 2;  // its own edge has one face
constexpr uint8_t kSeen = 4;       // reached by oneFanEach's walks
void flagCorner(FillLaterVector<uint8_t>& flags, uint32_t c, uint8_t flag) {
  __atomic_fetch_or(&flags[c], flag, __ATOMIC_RELAXED);
}

// Whether every used vertex's corners form one fan, where every edge has one face or two that walk it
// opposite ways. Corner c at v turns to `turn(c)`: the corner at v of the other face on the edge into
// c, or none (UINT32_MAX) where that edge is a boundary. No two corners turn to one, so a vertex's
// corners fall into paths, each from a corner flagged kPathStart, and loops; a vertex with more than
// one path, or a path and a loop, or a corner no walk reaches, has more than one fan. A loop is walked
// from the first unreached corner a thread finds at a vertex no walk has claimed; a second loop at a
// vertex is never walked, and its corners stay unreached. The union-find of splitNonManifold joins the
// same corners. Adds kSeen to `flags` (the union-find that follows a false return reads only kIsolated).
template <class Turn>
bool oneFanEach(const PolygonMesh& faces, Turn&& turn, FillLaterVector<uint8_t>& flags, int threads) {
  const size_t cornerCount = faces.faceVertices.size();
  constexpr uint8_t kPath = 1, kLoop = 2;  // what claimed a vertex first
  FillLaterVector<uint8_t> walked = parallelFilled(faces.positions.size(), uint8_t(0), threads);
  bool many = false;
  auto load = [&](size_t c) { return __atomic_load_n(&flags[c], __ATOMIC_RELAXED); };
  auto seen = [&](size_t c) { return (load(c) & kSeen) != 0; };
  // A corner is on one path or loop, walked once: only that walk writes its flags here.
  auto mark = [&](uint32_t c) { __atomic_store_n(&flags[c], uint8_t(load(c) | kSeen), __ATOMIC_RELAXED); };
  auto walk = [&](uint32_t start) {
    mark(start);
    for (uint32_t c = turn(start); c != UINT32_MAX && c != start; c = turn(c)) mark(c);
  };
  parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++)
      if (load(c) & kPathStart) {
        if (__atomic_exchange_n(&walked[faces.faceVertices[c]], kPath, __ATOMIC_RELAXED))
          __atomic_store_n(&many, true, __ATOMIC_RELAXED);
        walk(uint32_t(c));
      }
  });
  if (!many)
    parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; c++) {
        if (seen(c)) continue;
        uint8_t claimed = 0;
        if (__atomic_compare_exchange_n(&walked[faces.faceVertices[c]], &claimed, kLoop, false, __ATOMIC_RELAXED,
                                        __ATOMIC_RELAXED))
          walk(uint32_t(c));
        else if (claimed == kPath)
          __atomic_store_n(&many, true, __ATOMIC_RELAXED);
      }
    });
  if (!many)
    parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; c++)
        if (!seen(c)) {
          __atomic_store_n(&many, true, __ATOMIC_RELAXED);
          return;
        }
    });
  return !many;
}

}  // namespace

PolygonMesh splitNonManifold(PolygonMesh& faces, OrientedEdges&& oriented, RepairReport& report, int threads,
                             size_t& singleEdges) {
  const size_t cornerCount = faces.faceVertices.size();
  const FillLaterVector<CornerEdge>& edges = oriented.edges;
  const FillLaterVector<uint32_t>& cornerFace = oriented.cornerFace;
  auto nextCorner = [&](uint32_t c) {
    uint32_t f = cornerFace[c];
    return c + 1 == faces.faceStart[f + 1] ? faces.faceStart[f] : c + 1;
  };
  // From min to max in face order: the corner's vertex is the key's smaller one.
  auto forward = [&](const CornerEdge& e) { return faces.faceVertices[e.corner] == e.first; };
  auto freeEdges = [&] {
    FillLaterVector<CornerEdge>().swap(oriented.edges);
    FillLaterVector<uint32_t>().swap(oriented.cornerFace);
    FillLaterVector<uint32_t>().swap(oriented.partner);
  };
  FillLaterVector<uint8_t> flags = parallelFilled(cornerCount, uint8_t(0), threads);
  bool manyFans = false;  // found so already
  if (!oriented.partner.empty()) {
    // Every edge of one face or of two walking it opposite ways (orientFaces' partners): no edge is
    // non-manifold, the edge into corner c is its previous corner's, and the turns are read off the
    // partners rather than found again from the sorted edges.
    const FillLaterVector<uint32_t>& partner = oriented.partner;
    size_t single = 0;
    parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
      size_t n = 0;
      for (size_t c = begin; c < end; c++)
        if (partner[c] == UINT32_MAX) flags[c] = kPathStart, n++;
      __atomic_fetch_add(&single, n, __ATOMIC_RELAXED);
    });
    auto turn = [&](uint32_t c) {
      const uint32_t f = cornerFace[c];
      return partner[c == faces.faceStart[f] ? faces.faceStart[f + 1] - 1 : c - 1];
    };
    if (oneFanEach(faces, turn, flags, threads)) {
      singleEdges += single;
      freeEdges();
      return std::move(faces);
    }
    // A vertex of several fans: the union-find below, which reads only kIsolated of the flags.
    FillLaterVector<uint32_t>().swap(oriented.partner);
    manyFans = true;
  }

  // A key's corners are one run of the sorted edges. Wedges that get a vertex of their own are
  // flagged kIsolated first, then the manifold edges join theirs. The same pass finds each corner's
  // turn around its vertex for oneFanEach (complete where no edge is non-manifold).
  FillLaterVector<uint32_t> newCorner(cornerCount);  // turns; then each corner's class, then its vertex
  FillLaterVector<uint32_t>& turn = newCorner;
  auto sameKey = [&](size_t i, size_t j) { return edges[i].key() == edges[j].key(); };
  // The run's edge that joins its first (its partner), or SIZE_MAX when none does.
  auto partnerOf = [&](size_t i, size_t j) {
    for (size_t k = i + 1; k < j; k++)
      if (forward(edges[k]) != forward(edges[i])) return k;
    return SIZE_MAX;
  };
  size_t single = 0, nonManifold = 0;
  parallelForRuns(edges.size(), threads, sameKey, [&](size_t i, size_t j) {
    const uint32_t c0 = edges[i].corner;
    if (j - i == 1) {
      __atomic_fetch_add(&single, size_t(1), __ATOMIC_RELAXED);
      turn[nextCorner(c0)] = UINT32_MAX;
      flagCorner(flags, c0, kPathStart);
      return;
    }
    const size_t partner = partnerOf(i, j);
    if (j - i == 2 && partner != SIZE_MAX) {
      const uint32_t c1 = edges[partner].corner;
      turn[nextCorner(c0)] = c1;
      turn[nextCorner(c1)] = c0;
      return;
    }
    __atomic_fetch_add(&nonManifold, size_t(1), __ATOMIC_RELAXED);
    for (size_t k = i + 1; k < j; k++) {
      if (k == partner) continue;
      flagCorner(flags, edges[k].corner, kIsolated);
      flagCorner(flags, nextCorner(edges[k].corner), kIsolated);
    }
  });
  singleEdges += single;
  report.nonManifoldEdges += nonManifold;
  if (nonManifold == 0 && !manyFans &&
      oneFanEach(
          faces, [&](uint32_t c) { return turn[c]; }, flags, threads)) {
    // Every vertex one fan: the union-find below would give each corner its own vertex again.
    freeEdges();
    return std::move(faces);
  }
  // Join the wedges across manifold edges; c0 runs a->b in its face, c1 b->a in its. An isolated wedge
  // (at an endpoint of an edge where its face was detached) joins nothing: it gets a vertex of its own,
  // which opens its face's other edge at that corner into a boundary. Such an edge joins nothing at
  // either end: joined at its other end only, the two faces would meet at a vertex without an edge
  // (a bowtie the fuzzer found: a face on a three-face edge that also shared a good edge).
  UnionFind wedges(cornerCount, threads);
  parallelForRuns(edges.size(), threads, sameKey, [&](size_t i, size_t j) {
    const size_t partner = j - i > 1 ? partnerOf(i, j) : SIZE_MAX;
    if (partner == SIZE_MAX) return;
    const uint32_t c0 = edges[i].corner, c1 = edges[partner].corner;
    auto isolated = [&](uint32_t c) { return (flags[c] & kIsolated) != 0; };
    if (isolated(c0) || isolated(nextCorner(c0)) || isolated(c1) || isolated(nextCorner(c1))) return;
    wedges.unite(c0, nextCorner(c1));
    wedges.unite(nextCorner(c0), c1);
  });
  freeEdges();

  // Output vertices: the class of a vertex's first corner keeps the vertex; every other class (a fan
  // of wedges, or an isolated wedge alone) gets a copy, numbered in the order of its first corner,
  // which is its union-find root (the smaller root wins every union; isolated wedges join nothing).
  const size_t vertexCount = faces.positions.size();
  FillLaterVector<uint32_t> firstCorner = parallelFilled(vertexCount, UINT32_MAX, threads);
  parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++) {
      newCorner[c] = wedges.find(uint32_t(c));
      atomicMin(firstCorner[faces.faceVertices[c]], uint32_t(c));
    }
  });
  wedges = UnionFind(0);
  FillLaterVector<uint32_t> copyId(cornerCount);  // read only where written: the classes given a copy
  PolygonMesh out;
  out.positions = std::move(faces.positions);
  report.splitVertices += parallelNumber(
      cornerCount, threads, [&](size_t c) { return newCorner[c] == c && firstCorner[faces.faceVertices[c]] != c; },
      [&](size_t copies) { out.positions.resize(vertexCount + copies); },
      [&](size_t c, size_t n) {
        copyId[c] = uint32_t(vertexCount + n);
        out.positions[vertexCount + n] = out.positions[faces.faceVertices[c]];
      });
  parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++) {
      const uint32_t v = faces.faceVertices[c], cls = newCorner[c];
      newCorner[c] = firstCorner[v] == cls ? v : copyId[cls];
    }
  });
  out.faceStart = std::move(faces.faceStart);
  out.faceVertices = std::move(newCorner);
  out.cornerNormals = std::move(faces.cornerNormals);
  return out;
}

}  // namespace vgeo

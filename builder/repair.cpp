// repair.cpp: turns a polygon soup into a manifold mesh the later steps can trust.
// 1. Positions must be finite and within +-1e12 (else an error). 2. Bit-identical positions are welded, so that meshes
// split for texture seams (glTF) become connected. 3. Faces with fewer than 3 distinct corners are
// dropped, as are faces with the corner set of an earlier face; a vertex that two faces fold through
// (valence 2) is taken out of them. 4. Faces are turned to agree with their neighbours (orient.cpp).
// 5. Non-manifold edges and vertices are split by wedges (split_fans.cpp): every face corner is a wedge;
// the wedges of a vertex joined through manifold edges (two faces, opposite orientations) form one fan
// and share one output vertex, every other fan gets its own copy.
// One pass leaves every edge with at most two faces of opposite orientation and every vertex one fan.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>

#include "../common/bucket_sort.h"
#include "../common/first_of_equal.h"
#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {
namespace {

// Products of three coordinates (volumes, squared lengths times a length) stay inside float.
constexpr float kMaxCoordinate = 1e12f;

// The faces of `mesh` that keep(f, corners, normals) keeps, with the corners (and, where the mesh has
// them, normals) it leaves in those arrays, in face order, made on up to `threads` threads: sized in a
// first pass, filled in a second (keep runs twice a face). Where every face is kept as it was, the
// mesh itself is returned (no second pass). Takes the positions from `mesh`.
template <class Keep>
PolygonMesh keptFaces(PolygonMesh& mesh, int threads, Keep&& keep) {
  const size_t n = mesh.faceCount();
  const bool withNormals = !mesh.cornerNormals.empty();
  std::vector<uint32_t> size(n);
  bool changed = false;
  parallelForRanges(n, threads, [&](size_t begin, size_t end) {
    std::vector<uint32_t> corners;
    std::vector<glm::vec3> normals;
    bool changedHere = false;
    for (size_t f = begin; f < end; f++) {
      corners.clear(), normals.clear();
      const bool kept = keep(f, corners, normals);
      size[f] = kept ? uint32_t(corners.size()) : 0u;
      changedHere = changedHere || !kept || corners.size() != mesh.faceSize(f) ||
                    !std::equal(corners.begin(), corners.end(), mesh.face(f)) ||
                    (withNormals && !std::equal(normals.begin(), normals.end(), mesh.faceNormals(f)));
    }
    if (changedHere) __atomic_store_n(&changed, true, __ATOMIC_RELAXED);
  });
  if (!changed) return std::move(mesh);
  PolygonMesh kept;
  kept.positions = std::move(mesh.positions);
  std::vector<uint32_t> at(n);  // a kept face's first corner in `kept`
  const size_t corners = parallelNumber(
      n, threads, [&](size_t f) { return size[f]; }, [&](size_t total) { kept.faceVertices.resize(total); },
      [&](size_t f, size_t corner) { at[f] = uint32_t(corner); });
  parallelNumber(
      n, threads, [&](size_t f) { return size[f] > 0; }, [&](size_t faces) { kept.faceStart.resize(faces + 1); },
      [&](size_t f, size_t face) { kept.faceStart[face] = at[f]; });
  kept.faceStart.back() = uint32_t(corners);
  if (withNormals) kept.cornerNormals.resize(corners);
  parallelForRanges(n, threads, [&](size_t begin, size_t end) {
    std::vector<uint32_t> corners;
    std::vector<glm::vec3> normals;
    for (size_t f = begin; f < end; f++) {
      if (!size[f]) continue;
      corners.clear(), normals.clear();
      keep(f, corners, normals);
      std::copy(corners.begin(), corners.end(), kept.faceVertices.begin() + at[f]);
      if (withNormals) std::copy(normals.begin(), normals.end(), kept.cornerNormals.begin() + at[f]);
    }
  });
  return kept;
}

// A vertex with two faces that share both of its edges (valence 2, nothing between the faces there)
// folds the surface: both faces run through it, and once triangulated or subdivided they hold the same
// triangle edge twice. Such a vertex is taken out of both faces (a face left with fewer than three
// corners is dropped, counted with `degenerate`), until none is left. Returns the vertices taken out.
size_t dissolveFolds(PolygonMesh& mesh, size_t& degenerate, int threads) {
  size_t dissolved = 0;
  for (bool changed = true; changed;) {
    changed = false;
    const size_t vertexCount = mesh.positions.size();
    // Each vertex's corner count, and for a vertex of two corners the two, in order.
    const size_t cornerCount = mesh.faceVertices.size();
    FillLaterVector<uint32_t> count = parallelFilled(vertexCount, 0u, threads),
                              cornerOf = parallelFilled(2 * vertexCount, UINT32_MAX, threads);
    parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; c++) __atomic_fetch_add(&count[mesh.faceVertices[c]], 1u, __ATOMIC_RELAXED);
    });
    parallelForRanges(cornerCount, threads, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; c++) {
        const uint32_t v = mesh.faceVertices[c];
        if (count[v] != 2) continue;
        uint32_t* two = &cornerOf[2 * v];
        uint32_t empty = UINT32_MAX;
        if (!__atomic_compare_exchange_n(&two[0], &empty, uint32_t(c), false, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
          __atomic_store_n(&two[1], uint32_t(c), __ATOMIC_RELAXED);
      }
    });
    bool anyOfTwo = false;
    parallelForRanges(vertexCount, threads, [&](size_t begin, size_t end) {
      bool found = false;
      for (size_t v = begin; v < end; v++) {
        if (count[v] != 2) continue;
        found = true;
        if (cornerOf[2 * v] > cornerOf[2 * v + 1]) std::swap(cornerOf[2 * v], cornerOf[2 * v + 1]);
      }
      if (found) __atomic_store_n(&anyOfTwo, true, __ATOMIC_RELAXED);
    });
    if (!anyOfTwo) break;  // no vertex of two corners: nothing can fold
    FillLaterVector<uint32_t> cornerFace(cornerCount);
    parallelForRanges(mesh.faceCount(), threads, [&](size_t begin, size_t end) {
      for (size_t f = begin; f < end; f++)
        std::fill(cornerFace.begin() + mesh.faceStart[f], cornerFace.begin() + mesh.faceStart[f + 1], uint32_t(f));
    });
    auto around = [&](uint32_t c, int step) {
      const uint32_t f = cornerFace[c], n = mesh.faceSize(f), k = c - mesh.faceStart[f];
      return mesh.face(f)[(k + n + uint32_t(step)) % n];
    };
    std::vector<uint8_t> drop(mesh.faceVertices.size(), 0), touched(mesh.faceCount(), 0);
    for (uint32_t v = 0; v < vertexCount; v++) {
      if (count[v] != 2) continue;
      const uint32_t a = cornerOf[2 * v], b = cornerOf[2 * v + 1];
      if (cornerFace[a] == cornerFace[b] || touched[cornerFace[a]] || touched[cornerFace[b]]) continue;
      const uint32_t pa = around(a, -1), na = around(a, 1), pb = around(b, -1), nb = around(b, 1);
      if (!((pa == pb && na == nb) || (pa == nb && na == pb))) continue;
      drop[a] = drop[b] = 1;
      touched[cornerFace[a]] = touched[cornerFace[b]] = 1;  // one vertex a face a pass: neighbours stay valid
      dissolved++;
      changed = true;
    }
    if (!changed) break;
    const size_t before = mesh.faceCount();
    mesh = keptFaces(mesh, threads, [&](size_t f, std::vector<uint32_t>& corners, std::vector<glm::vec3>& normals) {
      for (uint32_t c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; c++) {
        if (drop[c]) continue;
        corners.push_back(mesh.faceVertices[c]);
        if (!mesh.cornerNormals.empty()) normals.push_back(mesh.cornerNormals[c]);
      }
      return corners.size() >= 3;
    });
    degenerate += before - mesh.faceCount();
  }
  return dissolved;
}

// Every face index in range and every used position finite and within +-kMaxCoordinate, else an
// InputError naming the file (the first bad index or vertex in order, on any thread count). Returns
// which vertices the faces use.
std::vector<uint8_t> checkPositions(const PolygonMesh& mesh, const std::string& file, int threads) {
  const size_t vertexCount = mesh.positions.size(), none = SIZE_MAX;
  size_t badCorner = none;
  parallelForRanges(mesh.faceVertices.size(), threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++)
      if (mesh.faceVertices[c] >= vertexCount) {
        atomicMin(badCorner, c);
        return;
      }
  });
  if (badCorner != none)
    throw InputError(file, "face index " + std::to_string(mesh.faceVertices[badCorner]) + " is out of range (" +
                               std::to_string(vertexCount) + " vertices)");
  std::vector<uint8_t> used(vertexCount, 0);
  parallelForRanges(mesh.faceVertices.size(), threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++) __atomic_store_n(&used[mesh.faceVertices[c]], uint8_t(1), __ATOMIC_RELAXED);
  });
  size_t nonFinite = none, far = none;
  parallelForRanges(vertexCount, threads, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; v++) {
      const glm::vec3& p = mesh.positions[v];
      if (!used[v]) continue;
      if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)))
        atomicMin(nonFinite, v);
      else if (std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxCoordinate)
        atomicMin(far, v);
    }
  });
  if (nonFinite != none) {
    const glm::vec3& p = mesh.positions[nonFinite];
    throw InputError(file, "vertex " + std::to_string(nonFinite) + " has a non-finite position (" +
                               std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")");
  }
  if (far != none) {
    const glm::vec3& p = mesh.positions[far];
    char where[256];
    std::snprintf(where, sizeof where,
                  "vertex %zu lies beyond +-1e12 (%g, %g, %g), past what the LOD build's float arithmetic holds: "
                  "scale the model down",
                  far, double(p.x), double(p.y), double(p.z));
    throw InputError(file, where);
  }
  if (mesh.faceCount() == 0) throw InputError(file, "empty mesh: no faces");
  return used;
}

// A position's bits, -0 as +0: the key of welding (bit-identical positions are one vertex).
std::array<uint32_t, 3> positionBits(const glm::vec3& p) {
  std::array<uint32_t, 3> bits;
  for (int i = 0; i < 3; i++) {
    const float f = p[i] + 0.0f;  // -0 + 0 = +0
    std::memcpy(&bits[size_t(i)], &f, 4);
  }
  return bits;
}

// Each vertex's first vertex at its position (firstOfEqual over the positions' bits).
FillLaterVector<uint32_t> firstAtPosition(const std::vector<glm::vec3>& positions, int threads) {
  return firstOfEqual(
      positions.size(), threads,
      [&](size_t v) {
        const std::array<uint32_t, 3> bits = positionBits(positions[v]);
        return hashWords(bits.data(), 3);
      },
      [&](size_t a, size_t b) { return positionBits(positions[a]) == positionBits(positions[b]); });
}

// Weld: maps each vertex to the first of those at its position.
FillLaterVector<uint32_t> weldPositions(const PolygonMesh& mesh, const std::vector<uint8_t>& used, size_t& welded,
                                        int threads) {
  FillLaterVector<uint32_t> weld = firstAtPosition(mesh.positions, threads);
  size_t joined = 0;
  parallelForRanges(weld.size(), threads, [&](size_t begin, size_t end) {
    size_t n = 0;
    for (size_t v = begin; v < end; v++) n += weld[v] != v && used[v];
    if (n) __atomic_fetch_add(&joined, n, __ATOMIC_RELAXED);
  });
  welded += joined;
  return weld;
}

// The faces over welded corners: repeated neighbours merged, faces with < 3 distinct corners dropped
// (counted in `degenerate`). Takes the positions from `mesh`.
PolygonMesh weldFaces(PolygonMesh& mesh, const FillLaterVector<uint32_t>& weld, size_t& degenerate, int threads) {
  const bool withNormals = !mesh.cornerNormals.empty();
  const size_t before = mesh.faceCount();
  PolygonMesh faces =
      keptFaces(mesh, threads, [&](size_t f, std::vector<uint32_t>& corners, std::vector<glm::vec3>& normals) {
        for (uint32_t i = 0; i < mesh.faceSize(f); i++) {
          uint32_t v = weld[mesh.face(f)[i]];
          if (!corners.empty() && corners.back() == v) continue;
          corners.push_back(v);
          if (withNormals) normals.push_back(mesh.faceNormals(f)[i]);
        }
        while (corners.size() > 1 && corners.front() == corners.back()) {
          corners.pop_back();
          if (withNormals) normals.pop_back();
        }
        if (corners.size() < 3) return false;
        if (corners.size() > 16) {  // distinct corners: sorted, or for a face of a few compared pairwise
          std::vector<uint32_t> sorted(corners);
          std::sort(sorted.begin(), sorted.end());
          return std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
        }
        for (size_t i = 0; i < corners.size(); i++)
          for (size_t j = i + 1; j < corners.size(); j++)
            if (corners[i] == corners[j]) return false;
        return true;
      });
  degenerate += before - faces.faceCount();
  return faces;
}

// Whether faces a and b of `faces` have one corner set (repair left each face's corners distinct).
bool sameCornerSet(const PolygonMesh& faces, uint32_t a, uint32_t b) {
  const uint32_t n = faces.faceSize(a);
  if (faces.faceSize(b) != n) return false;
  const uint32_t *ca = faces.face(a), *cb = faces.face(b);
  if (n <= 16) return std::all_of(ca, ca + n, [&](uint32_t v) { return std::find(cb, cb + n, v) != cb + n; });
  std::vector<uint32_t> sa(ca, ca + n), sb(cb, cb + n);
  std::sort(sa.begin(), sa.end());
  std::sort(sb.begin(), sb.end());
  return sa == sb;
}

// Duplicates: faces with the same corner set; the first one stays. Returns how many went.
size_t dropDuplicateFaces(PolygonMesh& faces, int threads) {
  size_t duplicates = 0;
  const size_t n = faces.faceCount();
  // The top half of each face's corner-set hash beside its id in one 8-byte word, the words sorted
  // as they are (comparing face ids through a hash array missed the cache on large meshes), about one
  // face a bucket. Faces of one corner set meet in one run of equal halves, the first face first;
  // only within a run are corners compared.
  auto tag = [](uint64_t word) { return word >> 32; };
  FillLaterVector<uint64_t> byHash = bucketSorted<uint64_t>(
      n, 64, std::max(kChunkedBucketBits, bitsFor(n + 1)), threads,
      [&](size_t f, auto&& emit) {
        const uint64_t h = hashOfSet(faces.face(f), faces.faceSize(f));
        emit(h, tag(h) << 32 | f);
      },
      std::less<uint64_t>());
  // Each run on its own: a face is in one run, so runs never write the same flag. A face dropped is
  // passed over, so a run of many copies of one face costs its length, not its square.
  FillLaterVector<uint8_t> drop = parallelFilled(n, uint8_t(0), threads);
  bool dropped = false;
  parallelForRuns(
      n, threads, [&](size_t i, size_t j) { return tag(byHash[i]) == tag(byHash[j]); },
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i + 1 < end; i++) {
          const uint32_t fi = uint32_t(byHash[i]);
          if (drop[fi]) continue;
          for (size_t j = i + 1; j < end; j++) {
            const uint32_t fj = uint32_t(byHash[j]);
            if (!drop[fj] && sameCornerSet(faces, fi, fj)) {
              drop[fj] = 1;
              __atomic_store_n(&dropped, true, __ATOMIC_RELAXED);
            }
          }
        }
      });
  decltype(byHash)().swap(byHash);  // before the copy below
  if (!dropped) return 0;           // nothing to copy
  PolygonMesh kept =
      keptFaces(faces, threads, [&](size_t f, std::vector<uint32_t>& corners, std::vector<glm::vec3>& normals) {
        if (drop[f]) return false;
        corners.assign(faces.face(f), faces.face(f) + faces.faceSize(f));
        if (const glm::vec3* n = faces.faceNormals(f)) normals.assign(n, n + faces.faceSize(f));
        return true;
      });
  duplicates = n - kept.faceCount();
  faces = std::move(kept);
  return duplicates;
}

// Drops the vertices no face uses, keeping order; returns how many (welded ones not counted again).
size_t dropUnusedVertices(PolygonMesh& out, size_t welded, int threads) {
  FillLaterVector<uint32_t> remap = parallelFilled(out.positions.size(), UINT32_MAX, threads);
  parallelForRanges(out.faceVertices.size(), threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++) __atomic_store_n(&remap[out.faceVertices[c]], 0u, __ATOMIC_RELAXED);
  });
  bool anyUnused = false;
  parallelForRanges(out.positions.size(), threads, [&](size_t begin, size_t end) {
    if (std::find(remap.begin() + long(begin), remap.begin() + long(end), UINT32_MAX) != remap.begin() + long(end))
      __atomic_store_n(&anyUnused, true, __ATOMIC_RELAXED);
  });
  if (!anyUnused) return 0;  // every vertex used (so none welded either): nothing to renumber
  std::vector<glm::vec3> compact;
  const size_t kept = parallelNumber(
      out.positions.size(), threads, [&](size_t v) { return remap[v] == 0; }, [&](size_t n) { compact.resize(n); },
      [&](size_t v, size_t n) {
        remap[v] = uint32_t(n);
        compact[n] = out.positions[v];
      });
  // Vertices welded into another are not referenced any more either; count only the others.
  const size_t unused = out.positions.size() - kept - welded;
  parallelForRanges(out.faceVertices.size(), threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; c++) out.faceVertices[c] = remap[out.faceVertices[c]];
  });
  out.positions = std::move(compact);
  return unused;
}

// Edges with one face.
size_t countBoundaryEdges(const PolygonMesh& out, int threads) {
  size_t boundary = 0;
  std::vector<uint64_t> keys;
  keys.reserve(out.faceVertices.size());
  for (size_t f = 0; f < out.faceCount(); f++)
    for (uint32_t i = 0; i < out.faceSize(f); i++) {
      uint32_t a = out.face(f)[i], b = out.face(f)[(i + 1) % out.faceSize(f)];
      keys.push_back(undirectedEdge(a, b));
    }
  parallelSort(keys, threads);
  for (size_t i = 0; i < keys.size();) {
    size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) j++;
    if (j - i == 1) boundary++;
    i = j;
  }
  return boundary;
}

}  // namespace

bool positionsDistinct(const std::vector<glm::vec3>& positions, int threads) {
  const FillLaterVector<uint32_t> first = firstAtPosition(positions, threads);
  bool repeated = false;
  parallelForRanges(first.size(), threads, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; v++)
      if (first[v] != v) {
        __atomic_store_n(&repeated, true, __ATOMIC_RELAXED);
        return;
      }
  });
  return !repeated;
}

RepairReport repairMesh(PolygonMesh& mesh, const std::string& file, int threads) {
  RepairReport report;
  PolygonMesh faces;
  {
    const std::vector<uint8_t> used = checkPositions(mesh, file, threads);
    const FillLaterVector<uint32_t> weld = weldPositions(mesh, used, report.weldedVertices, threads);
    faces = weldFaces(mesh, weld, report.degenerateFaces, threads);
    mesh = PolygonMesh();  // its positions moved to `faces`; its faces are not needed again
  }
  report.duplicateFaces = dropDuplicateFaces(faces, threads);
  if (faces.faceCount() == 0) throw InputError(file, "empty mesh: every face is degenerate or a duplicate");
  report.dissolvedVertices = dissolveFolds(faces, report.degenerateFaces, threads);
  if (faces.faceCount() == 0) throw InputError(file, "empty mesh: every face is degenerate or a duplicate");
  OrientedEdges edges;
  const OrientReport orient = orientFaces(faces, threads, &edges);
  report.flippedFaces = orient.flippedFaces;
  report.components = orient.components;
  report.nonOrientableComponents = orient.nonOrientableComponents;
  size_t singleEdges = 0;
  PolygonMesh out = splitNonManifold(faces, std::move(edges), report, threads, singleEdges);
  faces = PolygonMesh();
  report.unusedVertices = dropUnusedVertices(out, report.weldedVertices, threads);
  // Without a split vertex the edges are those just counted (dropping unused vertices renumbers, one
  // to one); a split opens edges into boundaries, so they are counted again.
  report.boundaryEdges = report.splitVertices == 0 ? singleEdges : countBoundaryEdges(out, threads);
  mesh = std::move(out);
  return report;
}

}  // namespace vgeo

// limit.cpp: moves the vertices of a Catmull-Clark mesh (every face a quad: a cage after >= 1 round of
// subdivide.cpp) onto the limit surface and gives them its normals, so the leaf triangles sample the true
// surface. Closed-form masks (Halstead, Kass & DeRose, "Efficient, fair interpolation using Catmull-Clark
// surfaces", SIGGRAPH 1993):
// - interior vertex v of valence n, edge neighbours e_j and face-opposite vertices f_j in rotation order:
//     limit = (n^2 v + 4 sum e_j + sum f_j) / (n (n + 5)),
//     tangents sum_j a cos(2 pi j / n) e_j + (cos(2 pi j / n) + cos(2 pi (j+1) / n)) f_j and the same with
//     sin, a = 1 + cos(2 pi / n) + cos(pi / n) sqrt(2 (9 + cos(2 pi / n))); the normal is their cross;
// - boundary vertex (the boundary is a cubic B-spline, subdivide.cpp): limit = (a + 4 v + b) / 6 over its
//   boundary neighbours, tangent b - a; across the boundary, at a regular boundary vertex (two faces), the
//   B-spline patch's derivative ((d_a + 4 c + d_b) - (a + 4 v + b)) / 6 over the interior row (c, d_a, d_b);
//   at other valences, where no closed-form mask is used, from the vertex's ring subdivided until it lies
//   in the tangent plane (crossBoundaryTangent);
// - corner (one face): stays, normal of its face's corner.
#include <algorithm>
#include <cmath>
#include <optional>

#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {
namespace {

// A tangent across the boundary at boundary vertex v of three or more faces: its ring (the faces around
// it) subdivided 16 times, rescaled by 2 about v after each round (subdivision is affine invariant, so
// this only keeps the numbers in range), then the mean of its interior edge neighbours minus v. Each
// round shrinks the ring's offset from the tangent plane against its extent in it by the ratio of the
// subdivision matrix's eigenvalues (about 1/2), so after 16 the direction is exact to rounding.
glm::dvec3 crossBoundaryTangent(const PolygonMesh& mesh, const QuadCorners& q, uint32_t v) {
  const uint32_t center = 0;
  PolygonMesh ring = facesAround(mesh, mesh.positions, q, &v, 1);
  for (int round = 0; round < 16; round++) {
    PolygonMesh sub = subdivideCatmullClark(ring);  // vertex points keep their index: v stays 0
    ring = facesAround(sub, sub.positions, QuadCorners(sub), &center, 1);
    const glm::vec3 origin = ring.positions[0];
    for (glm::vec3& p : ring.positions) p = 2.0f * (p - origin);
  }
  // Edge neighbours of v: an interior one follows v in one face and precedes it in another.
  std::vector<int> seen(ring.positions.size(), 0);
  for (size_t f = 0; f < ring.faceCount(); f++)
    for (uint32_t k = 0; k < 4; k++)
      if (ring.face(f)[k] == center) seen[ring.face(f)[(k + 1) % 4]]++, seen[ring.face(f)[(k + 3) % 4]]++;
  glm::dvec3 inner(0.0);
  for (size_t i = 0; i < seen.size(); i++)
    if (seen[i] == 2) inner += glm::dvec3(ring.positions[i]);
  return inner;  // relative to v, which sits at the origin
}

// The closed-form masks' weights for an interior vertex of valence n: a, and cos / sin (2 pi j / n) for
// j = 0 .. n, made once per valence (most vertices share a few valences; the trigonometry was most of
// a vertex's cost).
struct RingWeights {
  double a = 0.0;
  std::vector<double> cos, sin;
};
RingWeights makeRingWeights(size_t n) {
  const double pi = 3.14159265358979323846, nn = double(n);
  RingWeights w;
  w.a = 1.0 + std::cos(2.0 * pi / nn) + std::cos(pi / nn) * std::sqrt(2.0 * (9.0 + std::cos(2.0 * pi / nn)));
  for (size_t j = 0; j <= n; j++) {
    w.cos.push_back(std::cos(2.0 * pi * double(j) / nn));
    w.sin.push_back(std::sin(2.0 * pi * double(j) / nn));
  }
  return w;
}
// Every valence a ring walk can reach (moveVertex stops at 65 corners).
constexpr size_t kMostRing = 65;
const RingWeights& ringWeights(size_t n) {
  static const std::vector<RingWeights> tables = [] {
    std::vector<RingWeights> t(kMostRing + 1);
    for (size_t k = 1; k <= kMostRing; k++) t[k] = makeRingWeights(k);
    return t;
  }();
  return tables[n];
}

// Vertex v's limit position and normal (the masks above); `ring` is scratch.
void moveVertex(const PolygonMesh& mesh, const QuadCorners& q, uint32_t v, std::vector<uint32_t>& ring,
                glm::vec3& limitPoint, glm::vec3& limitNormal) {
  // Around a vertex, a corner's successor is the corner whose next vertex is this corner's previous;
  // walks start at a corner without predecessor where there is one (a boundary vertex), so they see
  // every face, else at v's first corner.
  const uint32_t cornerCount = q.offsets()[v + 1] - q.offsets()[v];
  if (cornerCount == 0) return;  // unused vertex
  // The corners around v in rotation order from `first`; true when the walk returns to it.
  auto walk = [&](uint32_t first) {
    ring.clear();
    for (uint32_t c = first; ring.size() < kMostRing;) {
      ring.push_back(c);
      c = q.withNext(v, q.at(c, 3));
      if (c == UINT32_MAX) return false;
      if (c == ring.front()) return true;
    }
    return false;
  };
  // A closed walk through all of v's corners gives each a predecessor: then none is without one, and
  // the walk from the first corner is the one wanted.
  bool closed = walk(q.corners()[q.offsets()[v]]);
  if (!closed || ring.size() != cornerCount) {
    uint32_t firstCorner = UINT32_MAX;
    for (uint32_t i = q.offsets()[v]; i < q.offsets()[v + 1]; i++) {
      const uint32_t c = q.corners()[i];
      if (firstCorner == UINT32_MAX || q.withPrev(v, q.at(c, 1)) == UINT32_MAX) firstCorner = c;
    }
    closed = walk(firstCorner);
  }
  glm::dvec3 p(mesh.positions[v]), faceNormal(0.0);
  for (uint32_t r : ring) {
    glm::dvec3 a(mesh.positions[q.at(r, 1)]), b(mesh.positions[q.at(r, 3)]);
    faceNormal += glm::cross(a - p, b - p);
  }
  glm::dvec3 t1(0.0), t2(0.0);
  const size_t n = ring.size();
  if (closed) {
    const double nn = double(n);
    const RingWeights& w = ringWeights(n);
    const double a = w.a;
    glm::dvec3 sumE(0.0), sumF(0.0);
    for (size_t j = 0; j < n; j++) {
      glm::dvec3 e(mesh.positions[q.at(ring[j], 1)]), f(mesh.positions[q.at(ring[j], 2)]);
      sumE += e;
      sumF += f;
      double c0 = w.cos[j], c1 = w.cos[j + 1], s0 = w.sin[j], s1 = w.sin[j + 1];
      t1 += a * c0 * e + (c0 + c1) * f;
      t2 += a * s0 * e + (s0 + s1) * f;
    }
    limitPoint = glm::vec3((nn * nn * p + 4.0 * sumE + sumF) / (nn * (nn + 5.0)));
  } else if (n >= 2) {
    // Boundary: ring[0]'s next and ring[n-1]'s prev are the boundary neighbours.
    glm::dvec3 a(mesh.positions[q.at(ring[0], 1)]), b(mesh.positions[q.at(ring[n - 1], 3)]);
    glm::dvec3 curve = (a + 4.0 * p + b) / 6.0;
    limitPoint = glm::vec3(curve);
    t1 = b - a;
    if (n == 2) {
      glm::dvec3 c(mesh.positions[q.at(ring[0], 3)]), da(mesh.positions[q.at(ring[0], 2)]),
          db(mesh.positions[q.at(ring[1], 2)]);
      t2 = (da + 4.0 * c + db) / 6.0 - curve;
    } else {
      t2 = crossBoundaryTangent(mesh, q, v);
    }
  }  // corner: stays, normal of its face
  glm::dvec3 normal = glm::cross(t1, t2);
  if (!(glm::length(normal) > 1e-12 * glm::dot(t1, t1) + 1e-30)) normal = faceNormal;
  if (glm::dot(normal, faceNormal) < 0.0) normal = -normal;
  double len = glm::length(normal);
  if (len > 0.0) limitNormal = glm::vec3(normal / len);
}

}  // namespace

bool moveToLimit(PolygonMesh& mesh, FillLaterVector<glm::vec3>& normals, int threads, const QuadCorners* corners) {
  const size_t vertexCount = mesh.positions.size();
  if (!allQuads(mesh, threads)) return false;
  std::optional<QuadCorners> own;
  const QuadCorners& q = corners ? *corners : own.emplace(mesh, threads);
  FillLaterVector<glm::vec3> limit(vertexCount);
  normals.resize(vertexCount);
  parallelForRanges(
      vertexCount, threads,
      [&](size_t begin, size_t end) {
        std::vector<uint32_t> ring;
        for (uint32_t v = uint32_t(begin); v < end; v++) {
          limit[v] = mesh.positions[v];
          normals[v] = glm::vec3(0.0f, 0.0f, 1.0f);
          moveVertex(mesh, q, v, ring, limit[v], normals[v]);
        }
      },
      kHeavyRange);
  parallelForRanges(vertexCount, threads, [&](size_t begin, size_t end) {
    std::copy(limit.begin() + long(begin), limit.begin() + long(end), mesh.positions.begin() + long(begin));
  });
  return true;
}

}  // namespace vgeo

// test_repair.cpp: welding, degenerate and duplicate faces, non-manifold edges and vertices.
#include <algorithm>
#include <cmath>
#include <map>

#include "../common/bucket_sort.h"
#include "test_util.h"

namespace vgeo {
namespace {

// Every edge has at most two faces, of opposite orientation; every vertex one fan (its corners joined
// through the faces on their edges).
void expectManifold(const PolygonMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> cornerOf;  // directed edge a->b: the corner at a
  std::vector<uint32_t> cornerFace(m.faceVertices.size());
  for (size_t f = 0; f < m.faceCount(); f++)
    for (uint32_t i = 0; i < m.faceSize(f); i++) {
      directed[{m.face(f)[i], m.face(f)[(i + 1) % m.faceSize(f)]}]++;
      cornerOf[{m.face(f)[i], m.face(f)[(i + 1) % m.faceSize(f)]}] = m.faceStart[f] + i;
      cornerFace[m.faceStart[f] + i] = uint32_t(f);
    }
  for (auto& [e, n] : directed)
    EXPECT_EQ(n, 1) << "directed edge " << e.first << "-" << e.second << " used " << n << " times";
  std::vector<uint32_t> parent(m.faceVertices.size());
  for (uint32_t c = 0; c < parent.size(); c++) parent[c] = c;
  auto find = [&](uint32_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  auto next = [&](uint32_t c) {
    const uint32_t f = cornerFace[c];
    return c + 1 == m.faceStart[f + 1] ? m.faceStart[f] : c + 1;
  };
  for (const auto& [edge, c] : cornerOf) {  // c at a on a->b; the face on b->a has a corner at a after it
    auto other = cornerOf.find({edge.second, edge.first});
    if (other != cornerOf.end()) parent[find(c)] = find(next(other->second));
  }
  std::map<uint32_t, uint32_t> fanOf;
  for (uint32_t c = 0; c < parent.size(); c++) {
    auto [it, added] = fanOf.emplace(m.faceVertices[c], find(c));
    EXPECT_EQ(it->second, find(c)) << "vertex " << m.faceVertices[c] << " has more than one fan";
  }
}

TEST(Repair, SplitsANonManifoldEdgeOfThreeFaces) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  const uint32_t t[3][3] = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};  // three "pages" on edge 0-1
  for (auto& f : t) m.addFace(f, 3);
  RepairReport r = repairMesh(m, "book");
  EXPECT_EQ(r.nonManifoldEdges, 1u);
  EXPECT_GE(r.splitVertices, 2u);
  EXPECT_EQ(m.faceCount(), 3u);
  expectManifold(m);
}

TEST(Repair, SplitsANonManifoldVertex) {
  // Two triangles touching at vertex 0 only (a bowtie).
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  const uint32_t t[2][3] = {{0, 1, 2}, {0, 3, 4}};
  for (auto& f : t) m.addFace(f, 3);
  RepairReport r = repairMesh(m, "bowtie");
  EXPECT_EQ(r.splitVertices, 1u);
  EXPECT_EQ(m.positions.size(), 6u);
  expectManifold(m);
}

TEST(Repair, SplitsTheApexOfTwoClosedSurfaces) {
  // Two tetrahedra sharing vertex 0 and no edge: every edge has two faces, yet vertex 0 has two fans.
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  const uint32_t t[8][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 5, 4}, {0, 4, 6}, {0, 6, 5}, {4, 5, 6}};
  for (auto& f : t) m.addFace(f, 3);
  RepairReport r = repairMesh(m, "apex");
  EXPECT_EQ(r.nonManifoldEdges, 0u);
  EXPECT_EQ(r.splitVertices, 1u);
  EXPECT_EQ(r.boundaryEdges, 0u);
  EXPECT_EQ(m.positions.size(), 8u);
  expectManifold(m);
}

TEST(Repair, DropsDegenerateAndDuplicateFacesAndWelds) {
  PolygonMesh m;
  // A quad split into triangles with its vertices duplicated (as glTF does at seams).
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const uint32_t t[5][3] = {{0, 1, 2}, {3, 4, 5}, {0, 1, 1}, {2, 0, 1}, {0, 3, 4}};
  for (auto& f : t) m.addFace(f, 3);
  RepairReport r = repairMesh(m, "seams");
  EXPECT_EQ(r.weldedVertices, 2u);
  EXPECT_EQ(r.degenerateFaces, 2u);  // {0,1,1} and {0,3,4} = {0,0,2} after welding
  EXPECT_EQ(r.duplicateFaces, 1u);   // {2,0,1} repeats {0,1,2}
  EXPECT_EQ(m.faceCount(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(r.boundaryEdges, 4u);
  expectManifold(m);
}

// A crafted file can repeat one face a million times: each copy is dropped once, the others passed
// over (a comparison of every pair of copies would run past the suite's timeout).
TEST(Repair, AMillionCopiesOfOneFaceGoAsDuplicates) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const uint32_t tetra[4][3] = {{0, 2, 1}, {0, 3, 2}, {0, 1, 3}, {1, 2, 3}};
  for (auto& f : tetra) m.addFace(f, 3);
  constexpr size_t kCopies = 1000000;
  for (size_t i = 0; i < kCopies; i++) m.addFace(tetra[0], 3);
  const RepairReport r = repairMesh(m, "copies", 2);
  EXPECT_EQ(r.duplicateFaces, kCopies);
  EXPECT_EQ(m.faceCount(), 4u);
  EXPECT_EQ(r.boundaryEdges, 0u);
  expectManifold(m);
}

TEST(Repair, TurnsFacesToAgreeWithTheirComponent) {
  // CGAL's cube of 12 triangles with every other face reversed, and a second cube apart from it with
  // one face reversed: each becomes consistent, keeping the orientation most of its area has.
  PolygonMesh m;
  for (float offset : {0.0f, 5.0f})
    for (int i = 0; i < 8; i++)
      m.positions.push_back({float(i & 1) + offset, float((i >> 1) & 1), float((i >> 2) & 1)});
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};  // outward
  size_t face = 0;
  for (uint32_t base : {0u, 8u})
    for (const auto& q : quads)
      for (int half = 0; half < 2; half++) {
        uint32_t tri[3] = {base + q[0], base + q[1 + half], base + q[2 + half]};
        const bool reverse = base == 0 ? face % 2 == 1 : face == 17;
        if (reverse) std::swap(tri[1], tri[2]);
        m.addFace(tri, 3);
        face++;
      }
  OrientReport r = orientFaces(m);
  EXPECT_EQ(r.components, 2u);
  EXPECT_EQ(r.nonOrientableComponents, 0u);
  EXPECT_EQ(r.flippedFaces, 6u + 1u);  // half of the first cube (a tie keeps the seed's side), one face of the second
  expectManifold(m);
  // Through repair, nothing is split any more.
  RepairReport repaired = repairMesh(m, "cubes");
  EXPECT_EQ(repaired.nonManifoldEdges, 0u);
  EXPECT_EQ(repaired.splitVertices, 0u);
  EXPECT_EQ(repaired.boundaryEdges, 0u);
}

TEST(Repair, AMoebiusStripIsCountedAndCutWhereItDisagrees) {
  // A strip of 8 quads whose ends meet with a half twist: no orientation agrees all round.
  PolygonMesh m;
  const int n = 8;
  for (int i = 0; i < n; i++) {
    float a = 6.2831853f * float(i) / float(n), twist = a / 2.0f;
    glm::vec3 centre(std::cos(a), std::sin(a), 0.0f), radial(std::cos(a), std::sin(a), 0.0f), up(0, 0, 1);
    glm::vec3 d = 0.3f * (std::cos(twist) * up + std::sin(twist) * radial);
    m.positions.push_back(centre + d);
    m.positions.push_back(centre - d);
  }
  for (int i = 0; i < n; i++) {
    uint32_t a0 = uint32_t(2 * i), a1 = a0 + 1;
    uint32_t b0 = uint32_t(2 * ((i + 1) % n)), b1 = b0 + 1;
    if (i == n - 1) std::swap(b0, b1);  // the half twist
    uint32_t q[4] = {a0, a1, b1, b0};
    m.addFace(q, 4);
  }
  RepairReport r = repairMesh(m, "moebius");
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.nonOrientableComponents, 1u);
  EXPECT_EQ(r.nonManifoldEdges, 1u);  // cut open at the one edge where the orientations disagree
  expectManifold(m);
}

TEST(Repair, AMessyMeshRepairsTheSameOnAnyThreadCount) {
  // Orientation's union-find and the split's passes run on many threads: a grid of 180,000 triangles
  // with a third of them turned, a fin on every 997th triangle (an edge of three faces), every 1,009th
  // face repeated, and 40 Moebius strips, repaired on 1 and 4 threads, must give the same mesh and report.
  PolygonMesh m;
  const uint32_t n = 300;
  for (uint32_t y = 0; y <= n; y++)
    for (uint32_t x = 0; x <= n; x++) m.positions.push_back({float(x), float(y), 0.1f * float((x * 7 + y * 3) % 5)});
  for (uint32_t y = 0; y < n; y++)
    for (uint32_t x = 0; x < n; x++) {
      const uint32_t a = y * (n + 1) + x, b = a + 1, c = a + n + 2, d = a + n + 1;
      uint32_t t[2][3] = {{a, b, c}, {a, c, d}};
      for (auto& tri : t) {
        const size_t f = m.faceCount();
        if ((f * 2654435761u >> 7) % 3 == 0) std::swap(tri[1], tri[2]);
        m.addFace(tri, 3);
        if (f % 1009 == 0) m.addFace(tri, 3);
        if (f % 997 == 0) {
          m.positions.push_back(m.positions[tri[0]] + glm::vec3(0.3f, 0.3f, 1.0f));
          uint32_t fin[3] = {tri[0], tri[1], uint32_t(m.positions.size() - 1)};
          m.addFace(fin, 3);
        }
      }
    }
  for (int strip = 0; strip < 40; strip++) {
    const uint32_t base = uint32_t(m.positions.size());
    for (int i = 0; i < 8; i++) {
      float a = 6.2831853f * float(i) / 8.0f, twist = a / 2.0f;
      glm::vec3 centre(400.0f + 3.0f * float(strip) + std::cos(a), std::sin(a), 0.0f);
      glm::vec3 d =
          0.3f * (std::cos(twist) * glm::vec3(0, 0, 1) + std::sin(twist) * glm::vec3(std::cos(a), std::sin(a), 0));
      m.positions.push_back(centre + d);
      m.positions.push_back(centre - d);
    }
    for (uint32_t i = 0; i < 8; i++) {
      uint32_t a0 = base + 2 * i, a1 = a0 + 1, b0 = base + 2 * ((i + 1) % 8), b1 = b0 + 1;
      if (i == 7) std::swap(b0, b1);
      uint32_t q[4] = {a0, a1, b1, b0};
      m.addFace(q, 4);
    }
  }
  PolygonMesh one = m, four = m;
  RepairReport r1 = repairMesh(one, "messy", 1), r4 = repairMesh(four, "messy", 4);
  EXPECT_EQ(r1.nonOrientableComponents, 40u);
  EXPECT_GT(r1.flippedFaces, 50000u);
  EXPECT_GT(r1.nonManifoldEdges, 180u);
  EXPECT_GT(r1.duplicateFaces, 170u);
  for (auto [a, b] : {std::pair{r1.weldedVertices, r4.weldedVertices},
                      {r1.degenerateFaces, r4.degenerateFaces},
                      {r1.duplicateFaces, r4.duplicateFaces},
                      {r1.nonManifoldEdges, r4.nonManifoldEdges},
                      {r1.splitVertices, r4.splitVertices},
                      {r1.boundaryEdges, r4.boundaryEdges},
                      {r1.unusedVertices, r4.unusedVertices},
                      {r1.flippedFaces, r4.flippedFaces},
                      {r1.components, r4.components},
                      {r1.nonOrientableComponents, r4.nonOrientableComponents}})
    EXPECT_EQ(a, b);
  EXPECT_EQ(one.faceVertices, four.faceVertices);
  EXPECT_EQ(one.faceStart, four.faceStart);
  EXPECT_TRUE(one.positions == four.positions);
  expectManifold(one);
}

TEST(Repair, PinchedSheetsSplitTheSameOnAnyThreadCount) {
  // Two grids of 20,000 triangles each, every edge with one or two faces, the second pinched onto the
  // first at 60 vertices: inner onto inner (two loops of corners at one vertex), boundary onto boundary
  // (two paths), boundary onto inner (a path and a loop). Each pinch is one split vertex.
  PolygonMesh m;
  const uint32_t n = 100, side = n + 1;
  for (int sheet = 0; sheet < 2; sheet++)
    for (uint32_t y = 0; y <= n; y++)
      for (uint32_t x = 0; x <= n; x++) m.positions.push_back({float(x), float(y), 5.0f * float(sheet)});
  std::map<uint32_t, uint32_t> pinch;  // a vertex of the second grid -> the first grid's vertex it takes
  for (uint32_t k = 0; k < 20; k++) {
    pinch[side * side + (5 + k * 4) * side + 7 + k * 4] = (3 + k * 4) * side + 9 + k * 4;  // inner onto inner
    pinch[side * side + 2 + k * 5] = 4 + k * 5;                                            // bottom onto bottom
    pinch[side * side + side * (3 + k * 5)] = (2 + k * 4) * side + 50;                     // left onto inner
  }
  for (uint32_t sheet = 0; sheet < 2; sheet++)
    for (uint32_t y = 0; y < n; y++)
      for (uint32_t x = 0; x < n; x++) {
        const uint32_t a = sheet * side * side + y * side + x, b = a + 1, c = a + side + 1, d = a + side;
        uint32_t t[2][3] = {{a, b, c}, {a, c, d}};
        for (auto& tri : t) {
          for (uint32_t& v : tri)
            if (auto p = pinch.find(v); p != pinch.end()) v = p->second;
          m.addFace(tri, 3);
        }
      }
  PolygonMesh one = m, four = m;
  RepairReport r1 = repairMesh(one, "pinched", 1), r4 = repairMesh(four, "pinched", 4);
  EXPECT_EQ(r1.nonManifoldEdges, 0u);
  EXPECT_EQ(r1.splitVertices, 60u);
  EXPECT_EQ(r1.boundaryEdges, 8u * n);
  EXPECT_EQ(r1.splitVertices, r4.splitVertices);
  EXPECT_EQ(one.faceVertices, four.faceVertices);
  EXPECT_TRUE(one.positions == four.positions);
  expectManifold(one);
  // Without the pinches nothing is split.
  PolygonMesh apart;
  apart.positions = m.positions;
  for (size_t f = 0; f < m.faceCount(); f++) {
    uint32_t tri[3];
    for (uint32_t i = 0; i < 3; i++) {
      tri[i] = m.face(f)[i];
      if (f >= 2 * n * n)  // the second grid's faces take their own vertices back
        for (const auto& [own, taken] : pinch)
          if (tri[i] == taken) tri[i] = own;
    }
    apart.addFace(tri, 3);
  }
  RepairReport r = repairMesh(apart, "apart", 4);
  EXPECT_EQ(r.splitVertices, 0u);
  EXPECT_EQ(apart.faceVertices.size(), m.faceVertices.size());
  expectManifold(apart);
}

TEST(Repair, BucketSortedIsStdSortOnAnyThreadCount) {
  // Repair's and the leaf clusters' sorts: (key, id) items from 100,000 sources, a tenth of them on one
  // key (a vertex of a huge fan), in buckets of one key each (shared counts) and by a hash's top bits
  // (counts a chunk), on 1 and 3 threads: std::sort's order, and each bucket's start where it begins.
  using Item = std::pair<uint64_t, uint32_t>;
  const size_t sources = 100000;
  auto vertexKey = [](size_t s, int k) { return s % 10 == 0 ? 7u : uint32_t((s * 2654435761u + size_t(k)) % 50000); };
  std::vector<Item> expectVertex, expectHash;
  for (size_t s = 0; s < sources; s++)
    for (int k = 0; k < 3; k++) {
      expectVertex.push_back({vertexKey(s, k), uint32_t(3 * s + size_t(k))});
      const uint32_t id = uint32_t(3 * s + size_t(k));
      expectHash.push_back({hashWords(&id, 1), id});
    }
  std::sort(expectVertex.begin(), expectVertex.end());
  std::sort(expectHash.begin(), expectHash.end());
  auto same = [](const FillLaterVector<Item>& got, const std::vector<Item>& expect) {
    return std::equal(got.begin(), got.end(), expect.begin(), expect.end());
  };
  for (int threads : {1, 3}) {
    // A bucket a key: 2^16 buckets (one range of the counts' scan), then 2^18 (four ranges).
    for (const int bits : {bitsFor(50000), 18}) {
      FillLaterVector<size_t> starts;
      const FillLaterVector<Item> byVertex = bucketSorted<Item>(
          sources, bits, bits, threads,
          [&](size_t s, auto&& emit) {
            for (int k = 0; k < 3; k++) emit(vertexKey(s, k), Item(vertexKey(s, k), uint32_t(3 * s + size_t(k))));
          },
          std::less<Item>(), &starts);
      EXPECT_TRUE(same(byVertex, expectVertex)) << threads << " threads, " << bits << " bits";
      ASSERT_EQ(starts.size(), (size_t(1) << bits) + 1);
      for (uint64_t v = 0; v < 50000; v += 97)
        for (size_t i = starts[v]; i < starts[v + 1]; i++) ASSERT_EQ(byVertex[i].first, v);
      for (size_t b = 50000; b < starts.size(); b += 4099) ASSERT_EQ(starts[b], byVertex.size());
    }
    const FillLaterVector<Item> byHash = bucketSorted<Item>(
        sources, 64, kChunkedBucketBits, threads,
        [&](size_t s, auto&& emit) {
          for (int k = 0; k < 3; k++) {
            const uint32_t id = uint32_t(3 * s + size_t(k));
            emit(hashWords(&id, 1), Item(hashWords(&id, 1), id));
          }
        },
        std::less<Item>());
    EXPECT_TRUE(same(byHash, expectHash)) << threads << " threads";
  }
}

TEST(Repair, RejectsNonFinitePositions) {
  PolygonMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, NAN, 0}};
  const uint32_t t[3] = {0, 1, 2};
  m.addFace(t, 3);
  try {
    repairMesh(m, "nan.obj");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nan.obj: vertex 2 has a non-finite position"), std::string::npos) << e.what();
  }
}

TEST(Repair, NonManifoldInputsBuildAndCheck) {
  // Two cubes sharing one edge (a non-manifold edge of four faces) through the whole pipeline.
  std::string dir = test::tempDir();
  std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "v 2 1 0\nv 2 2 0\nv 1 2 0\nv 2 1 1\nv 2 2 1\nv 1 2 1\n"
      "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
      "f 3 11 10 9\nf 7 12 13 14\nf 3 9 12 7\nf 9 10 13 12\nf 10 11 14 13\nf 11 3 7 14\n";
  std::string path = test::writeFile(dir, "two_cubes.obj", obj);
  SceneBuildStats stats;
  VgeoData data = test::build(path, 2, 2, &stats);
  EXPECT_EQ(stats.repair.nonManifoldEdges, 1u);
  CheckResult result = checkVgeo(data, {16, 3});
  EXPECT_TRUE(result.ok) << result.firstViolation;
}

}  // namespace
}  // namespace vgeo

// test_format.cpp: .vgeo round trip, and rejection (never a crash) of truncated or damaged files.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <tuple>

#include "test_util.h"

namespace vgeo {
namespace {

VgeoData smallScene() { return test::build(test::asset("horned_cube.obj"), 1); }

TEST(Format, RoundTripIsByteIdentical) {
  VgeoData data = smallScene();
  std::vector<uint8_t> bytes = serializeVgeo(data);
  VgeoData parsed = parseVgeo(bytes.data(), bytes.size(), "memory");
  EXPECT_EQ(serializeVgeo(parsed), bytes);
  std::string path = test::tempDir() + "/scene.vgeo";
  writeVgeo(data, path);
  VgeoData read = readVgeo(path);
  EXPECT_EQ(serializeVgeo(read), bytes);
  EXPECT_EQ(read.clusters.size(), data.clusters.size());
  EXPECT_EQ(read.nodes.size(), data.nodes.size());
}

TEST(Format, OnlyClosedOutwardMeshesAreFlaggedForBackFaceCulling) {
  // The renderer drops clusters and triangles that face away on closed instances; a closed mesh turned
  // inside out (every face reversed) would lose its visible side, so it is not flagged closed.
  std::ifstream in(test::asset("horned_cube.obj"));
  std::string line, reversed;
  while (std::getline(in, line)) {
    if (line.rfind("f ", 0) == 0) {
      std::vector<std::string> corners;
      std::istringstream words(line.substr(2));
      for (std::string w; words >> w;) corners.push_back(w);
      std::string face("f");
      for (auto c = corners.rbegin(); c != corners.rend(); ++c) face.append(" ").append(*c);
      line.swap(face);
    }
    reversed += line + "\n";
  }
  std::string path = test::writeFile(test::tempDir(), "inside_out.obj", reversed);
  VgeoData outward = smallScene(), inward = test::build(path, 1);
  EXPECT_TRUE(outward.geometries[0].flags & VGEO_GEOMETRY_CLOSED);
  EXPECT_TRUE(outward.instances[0].flags & VGEO_INSTANCE_CONE_CULL);
  EXPECT_FALSE(inward.geometries[0].flags & VGEO_GEOMETRY_CLOSED);
  EXPECT_FALSE(inward.instances[0].flags & VGEO_INSTANCE_CONE_CULL);
  EXPECT_EQ(inward.clusters.size(), outward.clusters.size());
}

TEST(Format, TruncatedFilesAreRejected) {
  std::vector<uint8_t> bytes = serializeVgeo(smallScene());
  for (size_t size : {size_t(0), size_t(7), size_t(31), size_t(100), bytes.size() / 2, bytes.size() - 1}) {
    try {
      parseVgeo(bytes.data(), size, "cut.vgeo");
      ADD_FAILURE() << "accepted a file cut to " << size << " bytes";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cut.vgeo: ", 0), 0u) << e.what();
    }
  }
}

TEST(Format, AFlippedByteInAnySectionIsRejectedByName) {
  VgeoData data = smallScene();
  std::vector<uint8_t> bytes = serializeVgeo(data);
  // The section table starts at byte 32: { id, elementSize, offset, count, checksum } of 32 bytes each.
  const uint32_t sections = uint32_t(Section::Count_) - 1;
  for (uint32_t s = 0; s < sections; s++) {
    uint64_t offset, count;
    uint32_t elementSize;
    std::memcpy(&elementSize, bytes.data() + 32 + 32 * s + 4, 4);
    std::memcpy(&offset, bytes.data() + 32 + 32 * s + 8, 8);
    std::memcpy(&count, bytes.data() + 32 + 32 * s + 16, 8);
    if (count == 0) continue;
    for (uint64_t at : {offset, offset + count * elementSize / 2, offset + count * elementSize - 1}) {
      std::vector<uint8_t> damaged = bytes;
      damaged[at] ^= 0x5a;
      try {
        parseVgeo(damaged.data(), damaged.size(), "bad.vgeo");
        ADD_FAILURE() << "accepted a flipped byte in section " << sectionName(Section(s + 1));
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(sectionName(Section(s + 1))), std::string::npos) << e.what();
      }
    }
  }
  // The header and the table themselves.
  for (size_t at : {size_t(8), size_t(12), size_t(20), size_t(40), size_t(32 + 32 * 3 + 9)}) {
    std::vector<uint8_t> damaged = bytes;
    damaged[at] ^= 0x01;
    EXPECT_THROW(parseVgeo(damaged.data(), damaged.size(), "bad.vgeo"), InputError) << "byte " << at;
  }
}

TEST(Format, OtherVersionsGetAClearError) {
  // Newer files, and older ones (version 2 had no control points or patches), name the version and
  // say what to do.
  for (uint32_t version : {kVgeoVersion + 1, 2u}) {
    std::vector<uint8_t> bytes = serializeVgeo(smallScene());
    std::memcpy(bytes.data() + 8, &version, 4);
    try {
      parseVgeo(bytes.data(), bytes.size(), "other.vgeo");
      FAIL();
    } catch (const InputError& e) {
      std::string what = e.what();
      EXPECT_EQ(what.rfind("other.vgeo: unsupported .vgeo version " + std::to_string(version), 0), 0u) << what;
      EXPECT_NE(what.find("rebuild the file"), std::string::npos) << what;
    }
  }
}

TEST(Format, ChecksumsAreRecomputedButReferencesStillChecked) {
  // A file whose checksums are right but whose contents lie (a cluster pointing past the vertex array)
  // is still rejected: the loader checks references, not only bytes.
  VgeoData data = smallScene();
  data.clusterVertices[0] = uint32_t(data.vertexCount() + 5);
  std::vector<uint8_t> bytes = serializeVgeo(data);
  try {
    parseVgeo(bytes.data(), bytes.size(), "lie.vgeo");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("uses a vertex out of range"), std::string::npos) << e.what();
  }
  data = smallScene();
  data.nodes[0].childOffset = 0;  // the root's children include the root: a cycle
  data.nodes[0].childCountAndFlags = 2;
  bytes = serializeVgeo(data);
  EXPECT_THROW(parseVgeo(bytes.data(), bytes.size(), "cycle.vgeo"), InputError);
  // Below the root a node holds at most VGEO_BVH_WIDTH children (the traversal's per-node bit mask).
  data = smallScene();
  const uint32_t inner = data.nodes[0].childOffset;
  ASSERT_LT(inner, data.nodes.size());
  data.nodes[inner].childCountAndFlags =
      (data.nodes[inner].childCountAndFlags & VGEO_NODE_LEAF_BIT) | (VGEO_BVH_WIDTH + 1);
  bytes = serializeVgeo(data);
  try {
    parseVgeo(bytes.data(), bytes.size(), "wide.vgeo");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has too many children"), std::string::npos) << e.what();
  }
}

TEST(Format, MalformedPatchWordsAreRejected) {
  // Trees (a triangle cage after one round: every face is one) whose words lie: a child before its
  // parent (a cycle), a point past the control points, an unknown ring valence.
  VgeoData good =
      test::build(test::writeFile(test::tempDir(), "tri.obj",
                                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"),
                  1);
  const shaderio::Patch& tree = good.patches[0];
  ASSERT_EQ(shaderio::patchKind(tree.info), VGEO_PATCH_TREE);
  auto rejected = [](const VgeoData& data, const std::string& expected) {
    std::vector<uint8_t> bytes = serializeVgeo(data);
    try {
      parseVgeo(bytes.data(), bytes.size(), "patch.vgeo");
      ADD_FAILURE() << "accepted; expected: " << expected;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  VgeoData data = good;
  data.patchPoints[tree.firstPoint + 1] = 0;  // quadrant 1's node is the root's own words
  rejected(data, "has malformed words");
  data = good;
  const uint32_t child = tree.firstPoint + good.patchPoints[tree.firstPoint];  // quadrant 0's node
  data.patchPoints[child + 1] = uint32_t(data.controlPoints.size());
  rejected(data, "uses a control point out of range");
  data = good;
  data.patchPoints[child] = VGEO_PATCH_RING | 40u << 8;
  rejected(data, "has malformed words");
  EXPECT_NO_THROW(parseVgeo(serializeVgeo(good).data(), serializeVgeo(good).size(), "good.vgeo"));
}

TEST(Format, TheFileWrittenAsItIsBuiltIsTheOneBuiltInMemory) {
  // `vgeo build` writes each section to disk as the layout makes it (VgeoFileSink): the last geometry's
  // part in place, what came before it spooled and copied into place. The same bytes as the in-memory
  // build writes, for a subdivided cage (patches, whose points are spooled before the DAG), a flat mesh,
  // and a glTF of many meshes (each section holds every geometry's part, in order), whether the sink
  // writes on threads of its own (one, or four on a sink of 16) or not; the spools leave nothing behind.
  const std::string dir = test::tempDir();
  for (const auto& [path, subdiv, sinkThreads] : std::vector<std::tuple<std::string, int, int>>{
           {test::asset("horned_cube.obj"), 2, 1},
           {test::cgalMesh("cow.off"), 0, 3},
           {test::assimpModel("2CylinderEngine-glTF-Binary/2CylinderEngine.glb"), 0, 1},
           {test::assimpModel("2CylinderEngine-glTF-Binary/2CylinderEngine.glb"), 0, 4},
           {test::asset("horned_cube.obj"), 3, 16}}) {
    SCOPED_TRACE(path + " with a sink of " + std::to_string(sinkThreads) + " threads");
    SceneBuildOptions options;
    options.subdivisionLevels = subdiv;
    options.threads = 2;
    SceneBuildStats stats;
    {
      VgeoFileSink file(dir + "/spooled.vgeo", sinkThreads);
      buildScene(path, options, stats, file);
      file.commit();
    }
    const std::vector<uint8_t> expected = serializeVgeo(test::build(path, subdiv));
    EXPECT_EQ(test::readFile(dir + "/spooled.vgeo"), std::string(expected.begin(), expected.end()));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  }
}

// One section of `data` as raw elements, for replaying a build into a sink.
struct SectionBytes {
  Section section;
  const uint8_t* bytes;
  uint64_t count;
};
std::vector<SectionBytes> sectionsOf(const VgeoData& data) {
  std::vector<SectionBytes> out;
#define VGEO_SECTION_BYTES(id, member, type, values, name) \
  out.push_back({Section::id, reinterpret_cast<const uint8_t*>(data.member.data()), data.member.size() / (values)});
  VGEO_SECTIONS(VGEO_SECTION_BYTES)
#undef VGEO_SECTION_BYTES
  return out;
}

TEST(Format, TheFileSinkWritesASectionInPlaceOnceTheTotalsBeforeItAreKnown) {
  // VgeoFileSink spools a section until the totals of every section before it in the file are known
  // (expectTotal), then copies it into place and writes the rest of it there. Whatever totals come
  // when, the file is the one serializeVgeo makes, and nothing else is left in its folder.
  const VgeoData data = test::build(test::asset("horned_cube.obj"), 2);  // every section holds something
  const std::vector<uint8_t> expected = serializeVgeo(data);
  const std::vector<SectionBytes> sections = sectionsOf(data);
  for (const SectionBytes& s : sections) ASSERT_GT(s.count, 0u) << sectionName(s.section);
  const std::string dir = test::tempDir(), path = dir + "/placed.vgeo";
  // Each section in three pieces, the sections taking turns; `expect(piece, sink)` runs before each
  // round of pieces.
  auto replay = [&](const std::function<void(int, SectionSink&)>& expect, int threads) {
    {
      VgeoFileSink sink(path, threads);
      for (int piece = 0; piece < 3; piece++) {
        expect(piece, sink);
        for (const SectionBytes& s : sections) {
          const uint64_t begin = s.count * uint64_t(piece) / 3, end = s.count * uint64_t(piece + 1) / 3;
          sink.append(s.section, s.bytes + begin * sectionElementSize(s.section), end - begin);
        }
      }
      sink.commit();
    }
    EXPECT_EQ(test::readFile(path), std::string(expected.begin(), expected.end()));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  };
  auto expectAll = [&](SectionSink& sink, bool backwards) {
    for (size_t i = 0; i < sections.size(); i++) {
      const SectionBytes& s = sections[backwards ? sections.size() - 1 - i : i];
      sink.expectTotal(s.section, s.count);
    }
  };
  {
    SCOPED_TRACE("no totals: every section spooled and copied at commit");
    replay([](int, SectionSink&) {}, 1);
  }
  {
    SCOPED_TRACE("every total first: every section written in place");
    replay([&](int piece, SectionSink& sink) { piece == 0 ? expectAll(sink, false) : void(); }, 3);
  }
  {
    SCOPED_TRACE("every total after a third of each section, last section first");
    replay([&](int piece, SectionSink& sink) { piece == 1 ? expectAll(sink, true) : void(); }, 2);
  }
  {
    SCOPED_TRACE("the same with four writer threads: copies and writes of several sections at once");
    replay([&](int piece, SectionSink& sink) { piece == 1 ? expectAll(sink, true) : void(); }, 16);
  }
  {
    SCOPED_TRACE("the totals of the first three sections only: the fourth placed, the rest spooled");
    replay(
        [&](int piece, SectionSink& sink) {
          if (piece == 1)
            for (size_t i = 0; i < 3; i++) sink.expectTotal(sections[i].section, sections[i].count);
        },
        1);
  }
  // Totals that do not hold are the caller's bug: a logic_error, and no file.
  std::filesystem::remove(path);
  {
    VgeoFileSink sink(path);
    sink.expectTotal(Section::Geometries, 1);
    EXPECT_THROW(sink.expectTotal(Section::Geometries, 2), std::logic_error);
    const SectionBytes& geometries = sections[0];
    ASSERT_EQ(geometries.section, Section::Geometries);
    sink.append(Section::Geometries, geometries.bytes, 1);
    EXPECT_THROW(sink.append(Section::Geometries, geometries.bytes, 1), std::logic_error);
    sink.expectTotal(Section::Instances, 2);
    EXPECT_THROW(sink.commit(), std::logic_error);  // no instance appended
  }
  {
    VgeoFileSink sink(path);
    sink.append(Section::Geometries, sections[0].bytes, 1);
    EXPECT_THROW(sink.expectTotal(Section::Geometries, 0), std::logic_error);
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 0);
}

TEST(Format, OutputIsTheSameForAnyThreadCount) {
  std::vector<uint8_t> one = serializeVgeo(test::build(test::cgalMesh("bunny00.off"), 0, 1));
  std::vector<uint8_t> two = serializeVgeo(test::build(test::cgalMesh("bunny00.off"), 0, 2));
  std::vector<uint8_t> three = serializeVgeo(test::build(test::cgalMesh("bunny00.off"), 0, 3));
  EXPECT_EQ(one, two);
  EXPECT_EQ(one, three);
}

TEST(Format, ASubdividedCageIsTheSameForAnyThreadCount) {
  // Subdivision, patches, limit and chord errors on threads: a cage with holes (boundary rules,
  // irregular boundary vertices) large enough that each of them splits its work (120 k quads).
  const std::string cage = test::cgalMesh("mech-holes-shark.off");
  std::vector<uint8_t> one = serializeVgeo(test::build(cage, 2, 1));
  EXPECT_EQ(one, serializeVgeo(test::build(cage, 2, 2)));
  EXPECT_EQ(one, serializeVgeo(test::build(cage, 2, 3)));
}

}  // namespace
}  // namespace vgeo

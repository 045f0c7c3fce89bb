// test_bad_input.cpp: every bad input gives one clear line naming the file and the cause, a non-zero
// exit, and no output file; inputs that are odd but valid build.
#include <filesystem>

#include "test_util.h"

namespace vgeo {
namespace {

struct BadCase {
  std::string name;
  std::string file;      // path, or a file name written from `content` into the test directory
  std::string content;   // empty: `file` is an existing path
  std::string expected;  // a part of the error line
  std::string options = "";
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, FailsWithOneClearLineAndWritesNothing) {
  const BadCase& c = GetParam();
  std::string dir = test::tempDir();
  std::string input = c.content.empty() ? c.file : test::writeFile(dir, c.file, c.content);
  std::string output = dir + "/out.vgeo";
  test::RunResult r = test::runVgeo("build '" + input + "' -o '" + output + "' -q " + c.options);
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(output)) << "an output file was written";
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "temporary file left: " << entry.path();
  // One line: the file's name, then the cause.
  ASSERT_FALSE(r.output.empty());
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.rfind(input + ": ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in: " << r.output;
}

const char* kCube =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

INSTANTIATE_TEST_SUITE_P(
    Files, BadInput,
    ::testing::Values(
        BadCase{"Missing", "/nonexistent/mesh.obj", "", "cannot open"},
        BadCase{"UnknownFormat", "mesh.xyz", "1 2 3\n", "unknown mesh format"},
        BadCase{"TruncatedOff", "t.off", "OFF\n8 6 0\n0 0 0\n1 0 0\n", "truncated"},
        BadCase{"OffIndexOutOfRange", "i.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "out of range"},
        BadCase{"OffNotOff", "n.off", "PLY\n3 1 0\n", "not an OFF file"},
        BadCase{"ObjBadVertex", "v.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "vertex needs three numbers"},
        BadCase{"ObjIndexOutOfRange", "o.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "out of range"},
        // The line is found again after reading (lines are not kept per face): comments and blank
        // lines count, and the face is the second one.
        BadCase{"ObjIndexOutOfRangeLine", "ol.obj", "v 0 0 0\nv 1 0 0\n# c\n\nv 0 1 0\nf 1 2 3\nf 1 2 9\n",
                "line 7: face index 9 is out of range (3 vertices)"},
        BadCase{"ObjNormalOutOfRangeLine", "on.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1 2 3\nf 1//1 2//1 3//2\n",
                "line 6: normal index 2 is out of range (1 normals)"},
        BadCase{"ObjNaN", "nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "non-finite position"},
        BadCase{"ObjInf", "inf.obj", "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", "non-finite position"},
        BadCase{"EmptyMesh", "e.obj", "v 0 0 0\nv 1 0 0\n", "empty mesh"},
        BadCase{"AllDegenerate", "d.obj", "v 0 0 0\nv 1 0 0\nf 1 2 2\nf 1 1 1\n", "empty mesh"},
        BadCase{
            "PlyTruncatedBinary", "b.ply",
            std::string("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n") +
                std::string(20, '\0'),
            "truncated"},
        BadCase{"PlyNoVertexXYZ", "x.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float q\nend_header\n1\n",
                "lacks x, y or z"},
        BadCase{"TooLargeForIndices", "cube.obj", kCube, "too large for the format's 32-bit indices", "--subdiv 16"},
        BadCase{"GltfIndexOutOfRange", test::assimpModel("IndexOutOfRange/IndexOutOfRange.gltf"), "", "out of range"},
        BadCase{"GltfAllIndicesOutOfRange", test::assimpModel("IndexOutOfRange/AllIndicesOutOfRange.gltf"), "",
                "out of range"},
        BadCase{"GltfMissingBin", test::assimpModel("MissingBin/BoxTextured.gltf"), "", "BoxTextured0.bin"},
        BadCase{"GltfSchemaFailure", test::assimpModel("SchemaFailures/sceneWrongType.gltf"), "", "BoxTextured0.bin"},
        BadCase{"GltfInfinites", test::assimpModel("BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb"), "",
                "non-finite position"},
        BadCase{"GltfRecursiveNodes", test::assimpModel("RecursiveNodes/RecursiveNodes.gltf"), "", "cyclic node graph"},
        BadCase{"GltfIncorrectVertexArrays", test::assimpModel("IncorrectVertexArrays/Cube.gltf"), "",
                "not a whole number of triangles"},
        BadCase{"GltfNoScene", test::assimpModel("TestNoRootNode/NoScene.gltf"), "", "no meshes"},
        BadCase{"GltfBadJson", "bad.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ { ", "parse error"},
        BadCase{"GltfTruncatedGlb", "t.glb", std::string("glTF\x02\0\0\0", 8), "truncated GLB"},
        BadCase{"GltfMeshesNotAnArray", test::assimpModel("wrongTypes/badArray.gltf"), "", "shows no triangle mesh"}),
    [](const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; });

TEST(BadInputFolder, AFolderNamedLikeAMeshIsRefused) {
  // Read as a stream, a folder once gave "out of memory" and no file name; only regular files are read.
  const std::string dir = test::tempDir(), folder = dir + "/folder.obj";
  std::filesystem::create_directories(folder);
  test::RunResult r = test::runVgeo("build '" + folder + "' -o '" + dir + "/f.vgeo' -q");
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_EQ(r.output, folder + ": not a regular file\n");
}

TEST(GoodInput, BoxBadNormalsBuilds) {
  // Bad normals do not matter to the builder (it uses positions only): a correct build.
  std::string dir = test::tempDir();
  test::RunResult r = test::runVgeo("build '" + test::assimpModel("BoxBadNormals-glTF-Binary/BoxBadNormals.glb") +
                                    "' -o " + dir + "/b.vgeo -q");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/b.vgeo"));
}

TEST(GoodInput, DegenerateAndDuplicateFacesAreDroppedAndCounted) {
  std::string dir = test::tempDir();
  std::string obj = std::string(kCube) + "f 1 2 2\nf 1 4 3 2\nf 3 2 1 4\n";
  std::string path = test::writeFile(dir, "dups.obj", obj);
  test::RunResult r = test::runVgeo("build '" + path + "' -o " + dir + "/d.vgeo -q --stats " + dir + "/s.json");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("1 degenerate and 2 duplicate faces dropped"), std::string::npos) << r.output;
}

TEST(BadVgeo, CheckRejectsAFileThatIsNotVgeo) {
  std::string dir = test::tempDir();
  std::string path = test::writeFile(dir, "x.vgeo", "this is not a vgeo file at all, but it is long enough");
  test::RunResult r = test::runVgeo("check '" + path + "'");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_EQ(r.output, path + ": not a .vgeo file (bad magic)\n");
}

// Normals named from the first face on are kept for every corner; a face without them shades flat
// (zero: its face's normal).
TEST(GoodInput, ObjCornerNormalsFromTheFirstFace) {
  const std::string dir = test::tempDir();
  const std::string path = test::writeFile(
      dir, "n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 1 0\nf 1//1 2//2 3//1\nf 2 4 3\n");
  const PolygonMesh mesh = loadObj(path).meshes[0];
  ASSERT_EQ(mesh.cornerNormals.size(), 6u);
  EXPECT_EQ(mesh.cornerNormals[0], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh.cornerNormals[1], glm::vec3(0, 1, 0));
  EXPECT_EQ(mesh.cornerNormals[2], glm::vec3(0, 0, 1));
  EXPECT_EQ(mesh.cornerNormals[3], glm::vec3(0.0f));
}

// Numbers are read in place, without cutting the token out first: a number is taken only where its
// token ends with it, so a plain index followed by anything else is a bad index, and an index of more
// than 18 digits, a sign or a slash goes the general way; numbers at a line's or the file's end count.
TEST(GoodInput, ObjNumbersReadInPlaceEndWithTheirToken) {
  const std::string dir = test::tempDir();
  const std::string path = test::writeFile(
      dir, "t.obj",
      "v +0 0 0\t\nv 1.5e0 0 0 \r\nv 0 1 0\nv 1 1 0\nf 01 2\t3 \r\nf 2 -1 3/7/\nf 0000000000000000000002 4 3\nf 2 4 3");
  const PolygonMesh mesh = loadObj(path).meshes[0];
  ASSERT_EQ(mesh.faceCount(), 4u);
  EXPECT_EQ(mesh.positions[1], glm::vec3(1.5f, 0, 0));
  const std::vector<uint32_t> corners(mesh.faceVertices.begin(), mesh.faceVertices.end());
  EXPECT_EQ(corners, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 1, 3, 2, 1, 3, 2}));
  const std::pair<const char*, const char*> bad[] = {
      {"f 1 2 3#c", "bad face index '3#c'"},
      {"f 1 2 +3", "bad face index '+3'"},
      {"f 1 2 0", "bad face index '0'"},
      {"f 1 2 3a", "bad face index '3a'"},
      {"f 1 2 99999999999999999999", "bad face index '99999999999999999999'"},
      {"f 1 2 100000000000000000", "face index too large for 32-bit indices"},
      {"v 1 2 3e", "vertex needs three numbers"},
      {"v 1 2 ++3", "vertex needs three numbers"},
      {"v 1 2 3#", "vertex needs three numbers"},
  };
  for (const auto& [line, cause] : bad) {
    const std::string badPath = test::writeFile(dir, "b.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n") + line + "\n");
    try {
      loadObj(badPath);
      ADD_FAILURE() << "no error for " << line;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), badPath + ": line 4: " + cause) << line;
    }
  }
}

// A file of more than 8 MB is read in pieces on several threads: the mesh is the one one thread reads,
// negative (relative) indices and normals looking back across the pieces' starts included, and the
// error reported is the first in the file, on its line.
TEST(ObjInPieces, TheMeshAndTheFirstErrorOfOneThread) {
  const std::string dir = test::tempDir();
  std::string text;
  for (int i = 0; text.size() < (12u << 20); i++) {
    text += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0.5\nvn 0 0 1\n";
    if (i > 0) text += "f -4//-1 -2//-1 -1//-2 -3//-1\n";
    if (i % 7 == 0) text += "# a comment\n\n";
  }
  const std::string path = test::writeFile(dir, "strip.obj", text);
  const SourceScene one = loadObj(path, 1), four = loadObj(path, 4);
  EXPECT_GT(one.meshes[0].faceCount(), 100000u);
  EXPECT_TRUE(one.meshes[0].positions == four.meshes[0].positions);
  EXPECT_TRUE(one.meshes[0].faceStart == four.meshes[0].faceStart);
  EXPECT_TRUE(one.meshes[0].faceVertices == four.meshes[0].faceVertices);
  EXPECT_TRUE(one.meshes[0].cornerNormals == four.meshes[0].cornerNormals);
  // Two bad lines, at 60% and 90% of the file: the first is reported.
  std::string bad = text;
  const size_t late = bad.find('\n', bad.size() * 9 / 10) + 1, early = bad.find('\n', bad.size() * 6 / 10) + 1;
  bad.insert(late, "v 1 2\n");
  bad.insert(early, "f 1 2 zz\n");
  const size_t line = 1 + size_t(std::count(bad.begin(), bad.begin() + long(early), '\n'));
  const std::string badPath = test::writeFile(dir, "bad.obj", bad);
  for (int threads : {1, 4}) {
    try {
      loadObj(badPath, threads);
      ADD_FAILURE() << "no error with " << threads << " threads";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), badPath + ": line " + std::to_string(line) + ": bad face index 'zz'");
    }
  }
}

// An OFF file of more than 256 KB in one element a line is read in pieces on several threads; a file
// that leaves that form anywhere, and any error, is read as one thread reads it.
TEST(OffInPieces, TheMeshAndTheErrorsOfOneThread) {
  const std::string dir = test::tempDir();
  constexpr int kSide = 320;
  std::string vertices, faces;
  for (int y = 0; y < kSide; y++)
    for (int x = 0; x < kSide; x++) {
      vertices += std::to_string(x) + " " + std::to_string(y) + " " + std::to_string((x * y) % 7) + "\n";
      if ((x + y) % 97 == 0) vertices += "# a comment\n\n";
    }
  for (int y = 0; y + 1 < kSide; y++)
    for (int x = 0; x + 1 < kSide; x++) {
      const int v = y * kSide + x;
      faces += "4 " + std::to_string(v) + " " + std::to_string(v + 1) + " " + std::to_string(v + kSide + 1) + " " +
               std::to_string(v + kSide) + ((x % 5 == 0) ? " 255 0 0\r\n" : "\n");
    }
  const std::string counts = std::to_string(kSide * kSide) + " " + std::to_string((kSide - 1) * (kSide - 1)) + " 0";
  auto same = [&](const std::string& name, const std::string& text) {
    const std::string path = test::writeFile(dir, name, text);
    const SourceScene one = loadOff(path, 1), four = loadOff(path, 4);
    EXPECT_EQ(one.meshes[0].faceCount(), size_t((kSide - 1) * (kSide - 1))) << name;
    EXPECT_TRUE(one.meshes[0].positions == four.meshes[0].positions) << name;
    EXPECT_TRUE(one.meshes[0].faceStart == four.meshes[0].faceStart) << name;
    EXPECT_TRUE(one.meshes[0].faceVertices == four.meshes[0].faceVertices) << name;
  };
  const std::string text = "OFF\n# made here\n" + counts + "\n" + vertices + faces;
  ASSERT_GT(text.size(), size_t(3) << 20);
  same("grid.off", text);
  // Two vertices on one line, a face over two lines, late in the file: the one-thread reader's meaning.
  std::string twoOnALine = text;
  const size_t late = twoOnALine.find('\n', vertices.size() * 9 / 10 + 20) + 1;
  twoOnALine.erase(twoOnALine.find('\n', late), 1);
  twoOnALine.insert(twoOnALine.find('\n', late), " ");
  same("two.off", twoOnALine + "1 2 3\n");  // a line past the last face, as many lines as one a line
  std::string split = text;
  const size_t face = split.find("\n4 ", split.size() * 9 / 10) + 1;
  split[split.find(' ', split.find(' ', face + 2) + 1)] = '\n';
  same("split.off", split);
  // Errors: a bad index at 90% of the file, and a face fewer than the counts promise.
  std::string bad = text;
  const size_t at = bad.find("\n4 ", bad.size() * 9 / 10) + 3;
  bad.replace(at, bad.find(' ', at) - at, "999999999");
  std::string truncated = text.substr(0, text.rfind('\n', text.size() - 2) + 1);
  for (const auto& [name, content] : {std::pair{"bad.off", bad}, std::pair{"truncated.off", truncated}}) {
    const std::string path = test::writeFile(dir, name, content);
    std::string one, four;
    try {
      loadOff(path, 1);
    } catch (const InputError& e) {
      one = e.what();
    }
    try {
      loadOff(path, 4);
    } catch (const InputError& e) {
      four = e.what();
    }
    EXPECT_FALSE(one.empty()) << name;
    EXPECT_EQ(one, four) << name;
  }
}

}  // namespace
}  // namespace vgeo

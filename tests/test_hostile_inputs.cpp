// test_hostile_inputs.cpp: crafted and fuzzed files (tests/inputs/, and larger ones made here) through
// the binary: each ends quickly with exit 1 and one line naming the file and the cause, or builds a
// file that passes `vgeo check`; never a crash, a hang, a read outside the input's folder or an
// allocation driven by a count the file cannot back.
#include <chrono>
#include <filesystem>

#include "gltf_writer.h"
#include "test_util.h"

namespace vgeo {
namespace {

namespace fs = std::filesystem;

std::string input(const std::string& name) { return std::string(VGEO_SOURCE_DIR) + "/tests/inputs/" + name; }

// Runs `args`; expects exit 1 within `seconds`, one line that starts with `file: ` and holds `expected`.
void expectRefused(const std::string& args, const std::string& file, const std::string& expected,
                   double seconds = 20.0) {
  SCOPED_TRACE(args);
  auto start = std::chrono::steady_clock::now();
  test::RunResult r = test::runVgeo(args);
  double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.rfind(file + ": ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << "expected '" << expected << "' in: " << r.output;
  EXPECT_LT(took, seconds);
}

void expectBuildRefused(const std::string& file, const std::string& expected, const std::string& options = "") {
  const std::string out = (fs::temp_directory_path() / "vgeo_hostile_out.vgeo").string();
  fs::remove(out);
  expectRefused("build '" + file + "' -o " + out + " -q " + options, file, expected);
  EXPECT_FALSE(fs::exists(out));
}

TEST(HostileInputs, CraftedGltfFilesAreRefused) {
  expectBuildRefused(input("gltf_accessor_offset_wrap.gltf"), "reads past the end of bufferView");
  expectBuildRefused(input("gltf_view_offset_wrap.gltf"), "reads past the end of buffer");
  expectBuildRefused(input("gltf_view_offset_wrap_far.gltf"), "reads past the end of buffer");
  expectBuildRefused(input("glb_view_offset_wrap.glb"), "reads past the end of buffer");
  expectBuildRefused(input("gltf_index_count_huge.gltf"), "reads past the end of bufferView");
  expectBuildRefused(input("gltf_diamond_64.gltf"), "the limit of instances");
  expectBuildRefused(input("gltf_diamond_20.gltf"), "the limit of instances");
  expectBuildRefused(input("gltf_etc_passwd.gltf"), "inside the glTF's folder");
  expectBuildRefused(input("gltf_uri_dir.gltf"), "inside the glTF's folder");
  expectBuildRefused(input("glb_std_out_of_range_message.glb"), "not a valid glTF file");
}

TEST(HostileInputs, DeepGltfGraphsAndJsonAreWalkedWithoutRecursion) {
  const std::string dir = test::tempDir();
  SourceScene cube = loadMeshFile(test::cgalMesh("cube_quad.off"));
  // A chain of 20,000 nodes with the mesh at the end: one instance, no recursion on the depth.
  std::string chain = test::gltfOf(dir, "base.gltf", cube.meshes[0], "");
  std::string text = test::readFile(chain);
  std::string nodes = "\"nodes\": [";
  for (int i = 0; i < 20000; i++) nodes += "{\"children\": [" + std::to_string(i + 1) + "]}, ";
  nodes += "{\"mesh\": 0}]";
  text.replace(text.find("\"nodes\": [{\"mesh\": 0}]"), std::string("\"nodes\": [{\"mesh\": 0}]").size(), nodes);
  const std::string chainPath = test::writeFile(dir, "chain.gltf", text);
  test::RunResult r = test::runVgeo("build " + chainPath + " -o " + dir + "/chain.vgeo -q");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  // A cycle, and 'extras' nested 20,000 deep.
  std::string cyclic = test::readFile(chain);
  cyclic.replace(cyclic.find("\"nodes\": [{\"mesh\": 0}]"), std::string("\"nodes\": [{\"mesh\": 0}]").size(),
                 "\"nodes\": [{\"mesh\": 0, \"children\": [1]}, {\"children\": [0]}]");
  expectBuildRefused(test::writeFile(dir, "cyclic.gltf", cyclic), "cyclic node graph");
  std::string deep = test::readFile(chain);
  deep.insert(deep.rfind('}'), ", \"extras\": " + std::string(20000, '[') + std::string(20000, ']'));
  expectBuildRefused(test::writeFile(dir, "deep.gltf", deep), "nests deeper than");
}

TEST(HostileInputs, GltfBuffersStayInsideTheGltfsFolder) {
  // model/scene.gltf names its buffer as 'data/b.bin' (fine), '../b.bin' (outside), a link to a file
  // outside, and the folder itself.
  const std::string dir = test::tempDir();
  SourceScene cube = loadMeshFile(test::cgalMesh("cube_quad.off"));
  std::string embedded = test::readFile(test::gltfOf(dir, "embedded.gltf", cube.meshes[0], ""));
  const size_t uri = embedded.find("data:application/octet-stream;base64,");
  const size_t end = embedded.find('"', uri);
  std::string b64 = embedded.substr(uri + 37, end - uri - 37);
  std::string bytes;  // decode: the writer's own base64 back to bytes
  for (size_t i = 0; i + 3 < b64.size(); i += 4) {
    auto val = [](char c) {
      return c == '=' ? 0 : c == '+' ? 62 : c == '/' ? 63 : c <= '9' ? c - '0' + 52 : c <= 'Z' ? c - 'A' : c - 'a' + 26;
    };
    uint32_t v = uint32_t(val(b64[i]) << 18 | val(b64[i + 1]) << 12 | val(b64[i + 2]) << 6 | val(b64[i + 3]));
    bytes += char(v >> 16);
    if (b64[i + 2] != '=') bytes += char(v >> 8 & 255);
    if (b64[i + 3] != '=') bytes += char(v & 255);
  }
  fs::create_directories(dir + "/model/data");
  test::writeFile(dir + "/model/data", "b.bin", bytes);
  test::writeFile(dir, "b.bin", bytes);
  fs::create_symlink(dir + "/b.bin", dir + "/model/link.bin");
  auto withUri = [&](const std::string& name, const std::string& u) {
    return test::writeFile(dir + "/model", name, embedded.substr(0, uri) + u + embedded.substr(end));
  };
  test::RunResult ok = test::runVgeo("build " + withUri("ok.gltf", "data/b.bin") + " -o " + dir + "/ok.vgeo -q");
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
  expectBuildRefused(withUri("up.gltf", "../b.bin"), "inside the glTF's folder");
  expectBuildRefused(withUri("link.gltf", "link.bin"), "inside the glTF's folder");
  expectBuildRefused(withUri("folder.gltf", "data"), "inside the glTF's folder");
  expectBuildRefused(withUri("absolute.gltf", dir + "/b.bin"), "inside the glTF's folder");
}

TEST(HostileInputs, CraftedPlyOffAndObjFilesAreRefusedOrBuildRight) {
  expectBuildRefused(input("ply_nan_list_count_ub.ply"), "bad list size");
  expectBuildRefused(input("ply_second_vertex_element_shrinks.ply"), "a second 'vertex' element");
  // An element without properties holds nothing, whatever its count: it is skipped, not looped over.
  const std::string dir = test::tempDir();
  for (const std::string name :
       {"ply_element_without_properties_hang.ply", "off_small_faces_input_triangles_underflow.off"}) {
    test::RunResult r = test::runVgeo("build " + input(name) + " -o " + dir + "/o.vgeo -q --stats " + dir + "/s.json");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("18446744073709551"), std::string::npos) << "no wrapped count: " << r.output;
    EXPECT_EQ(test::readFile(dir + "/s.json").find("18446744073709551"), std::string::npos);
    EXPECT_EQ(test::runVgeo("check " + dir + "/o.vgeo").exitCode, 0);
  }
}

TEST(HostileInputs, EveryFileTheBuilderWritesPassesItsCheck) {
  // Inputs on which the builder once wrote a file its own checker refused (a folded surface, an
  // inconsistently wound tetrahedron, coordinates near 3e38, a tetrahedron 2.4e9 long and 1 wide whose
  // limit surface rounds distinct vertices onto one position): now a build passes check, or fails with
  // one line.
  const std::string dir = test::tempDir();
  for (const std::string name :
       {"build_output_fails_check_huge_coords.obj", "build_output_fails_check_overlap.obj",
        "build_output_fails_check_patch_corner.obj", "build_output_unloadable_nonfinite_error.obj",
        "build_pipeline_fuzz_1.obj", "build_pipeline_fuzz_2.obj", "build_pipeline_fuzz_3.obj",
        "build_pipeline_fuzz_bowtie.off", "build_pipeline_fuzz_long_tetra.off"}) {
    // The fuzzed files name normals they lack; without those references they reach the later steps.
    std::string text = test::readFile(input(name)), stripped;
    for (size_t i = 0; i < text.size(); i++) {
      if (text[i] == '/' && (i == 0 || text[i - 1] != ' ')) {
        while (i < text.size() && text[i] != ' ' && text[i] != '\n') i++;
        if (i < text.size()) stripped += text[i];
        continue;
      }
      stripped += text[i];
    }
    for (const std::string& file : {input(name), test::writeFile(dir, "stripped_" + name, stripped)})
      for (int subdiv = 0; subdiv <= 2; subdiv++) {
        SCOPED_TRACE(file + " --subdiv " + std::to_string(subdiv));
        fs::remove(dir + "/o.vgeo");
        test::RunResult r =
            test::runVgeo("build '" + file + "' -o " + dir + "/o.vgeo -q --subdiv " + std::to_string(subdiv));
        if (r.exitCode != 0) {
          EXPECT_EQ(r.exitCode, 1) << r.output;
          EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
          EXPECT_EQ(r.output.rfind(file + ": ", 0), 0u) << r.output;
          continue;
        }
        test::RunResult check = test::runVgeo("check " + dir + "/o.vgeo --cuts 64");
        EXPECT_EQ(check.exitCode, 0) << check.output;
      }
  }
}

TEST(HostileInputs, CraftedVgeoAndSceneFilesAreRefused) {
  expectRefused("check " + input("check_cluster_vertex_underflow.vgeo"), input("check_cluster_vertex_underflow.vgeo"),
                "another geometry");
  expectRefused("check " + input("check_cluster_vertex_other_geometry.vgeo"),
                input("check_cluster_vertex_other_geometry.vgeo"), "another geometry");
  // A BVH of 30,000 nodes in a chain: refused on load, before any walk over it.
  VgeoData d = test::build(test::cgalMesh("cube_quad.off"), 0);
  const shaderio::BvhNode root = d.nodes[0];
  d.nodes.assign(30000, shaderio::BvhNode{});
  for (uint32_t i = 0; i + 1 < d.nodes.size(); i++) {
    d.nodes[i] = root;
    d.nodes[i].childOffset = i + 1;
    d.nodes[i].childCountAndFlags = 1;
  }
  d.nodes.back() = root;
  d.geometries[0].nodeCount = uint32_t(d.nodes.size());
  const std::string dir = test::tempDir(), chain = dir + "/chain.vgeo";
  test::writeFile(dir, "chain.vgeo",
                  std::string(reinterpret_cast<const char*>(serializeVgeo(d).data()), serializeVgeo(d).size()));
  expectRefused("check " + chain, chain, "deeper than");
  expectRefused("render " + chain + " -o " + dir + "/o.png", chain, "deeper than");
  // Scenes with a geometry index of 1.8e20 and instances at +-3e38.
  writeVgeo(test::build(test::cgalMesh("cube_quad.off"), 0), dir + "/a.vgeo");
  for (const std::string name : {"scene_geometry_index_float_cast_ub.json", "huge_translation.json"}) {
    fs::copy_file(input(name), dir + "/" + name);
    expectRefused("render " + dir + "/" + name + " -o " + dir + "/o.png", dir + "/" + name, "instance 0");
  }
}

}  // namespace
}  // namespace vgeo

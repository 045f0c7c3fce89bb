// test_hostile_values.cpp: what an attacker or a careless user can give the renderer besides a bad
// mesh: .vgeo values `check` refuses (render refuses them too: one validation), cameras and transforms
// past float, scene files nested deep or naming files thousands of times, inputs that are not regular
// files, links planted at an output's temporary name, an output named twice. Each ends with one line
// and exit 1 (the file's fault) or 2 (the command line's), quickly, never a crash.
#include <chrono>
#include <filesystem>
#include <fstream>

#include "../common/atomic_file.h"
#include "../renderer/gpu_renderer.h"
#include "gltf_writer.h"
#include "render_util.h"
#include "test_util.h"

namespace vgeo {
namespace {

namespace fs = std::filesystem;

// Runs `args`; expects exit `code` within 20 s and one line holding `expected`.
void expectOneLine(const std::string& args, int code, const std::string& expected) {
  SCOPED_TRACE(args);
  const auto start = std::chrono::steady_clock::now();
  const test::RunResult r = test::runVgeo(args);
  EXPECT_EQ(r.exitCode, code) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << "expected '" << expected << "' in: " << r.output;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
}

std::string save(const std::string& dir, const std::string& name, const VgeoData& d) {
  const std::vector<uint8_t> bytes = serializeVgeo(d);
  return test::writeFile(dir, name, std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

TEST(HostileValues, WhatCheckRefusesRenderRefusesToo) {
  // A subdivided cage (cage faces, patches), each crafted value in a copy: `check` and `render` both
  // refuse it on load with the file's name, before the GPU could follow it.
  const std::string dir = test::tempDir();
  const VgeoData good = test::build(test::asset("horned_cube.obj"), 1);
  ASSERT_FALSE(good.cageFaces.empty());
  struct Case {
    const char* name;
    std::function<void(VgeoData&)> craft;
    const char* cause;
  };
  const float nan = std::nanf("");
  const std::vector<Case> cases = {
      {"first_triangle", [](VgeoData& d) { d.cageFaces[3].firstTriangle = 1000000; }, "triangles outside the cluster"},
      {"first_triangle_edge",
       [](VgeoData& d) {
         const auto& c = d.clusters[d.cageFaces[0].leafCluster];
         d.cageFaces[0].firstTriangle =
             shaderio::clusterTriangleCount(c.counts) - 1;  // its second triangle past the end
       },
       "triangles outside the cluster"},
      {"face_other_cluster", [](VgeoData& d) { d.cageFaces[0].leafCluster = d.cageFaces.back().leafCluster; },
       "cage face"},
      {"nan_cluster_sphere", [nan](VgeoData& d) { d.clusters[5].selfSphere.w = nan; }, "bad bounding sphere"},
      {"negative_error", [](VgeoData& d) { d.clusters[7].selfError = -1.0f; }, "negative or NaN error"},
      {"nan_group_error", [nan](VgeoData& d) { d.groups[2].error = nan; }, "group 2"},
      {"nan_group_sphere", [nan](VgeoData& d) { d.groups[1].sphere.x = nan; }, "group 1"},
      {"nan_node_error", [nan](VgeoData& d) { d.nodes[1].maxError = nan; }, "BVH node 1"},
      {"childless_root", [](VgeoData& d) { d.nodes[0].childCountAndFlags &= VGEO_NODE_LEAF_BIT; }, "no children"},
      {"far_instance", [](VgeoData& d) { d.instances[0].row0.w = -1.7e38f; }, "reaches past"},
      {"zero_scale", [](VgeoData& d) { d.instances[0].maxScale = 0.0f; }, "zero or non-finite scale"},
      {"no_instances", [](VgeoData& d) { d.instances.clear(); }, "no instances"},
  };
  for (const Case& c : cases) {
    VgeoData d = good;
    c.craft(d);
    const std::string path = save(dir, std::string(c.name) + ".vgeo", d);
    expectOneLine("check " + path, 1, path + ": ");
    expectOneLine("check " + path, 1, c.cause);
    expectOneLine("render " + path + " -o " + dir + "/o.png --size 64x48", 1, c.cause);
    EXPECT_FALSE(fs::exists(dir + "/o.png")) << c.name;
  }
  // The good file passes both.
  const std::string path = save(dir, "good.vgeo", good);
  EXPECT_EQ(test::runVgeo("check " + path + " --cuts 2").exitCode, 0);
  EXPECT_EQ(test::runVgeo("render " + path + " -o " + dir + "/o.png --size 64x48").exitCode, 0);
}

TEST(HostileValues, ViewsAndPlacesPastFloatAreRefused) {
  const std::string dir = test::tempDir();
  const std::string cube = dir + "/cube.vgeo", out = " -o " + dir + "/o.png --size 64x48";
  writeVgeo(test::build(test::cgalMesh("cube_quad.off"), 0), cube);
  // Finite in double, not in the float view-projection: refused as the option's fault, no crash.
  expectOneLine("render " + cube + out + " --camera 3e19,0,0,0,0,0", 2, "--camera");
  expectOneLine("render " + cube + out + " --freeze-camera 1e20,0,0,0,0,0", 2, "--freeze-camera");
  expectOneLine("render " + cube + out + " --fov 1e-20", 2, "not finite in float");
  expectOneLine("render " + cube + out + " --mode frozen-diff --freeze-camera 3e19,1,1,0,0,0", 2, "--freeze-camera");
  // A scene with two instances at +-1e20, and a grid that would lay copies past float: the file's fault.
  const std::string scene =
      test::writeFile(dir, "far.json",
                      R"({"geometries": ["cube.vgeo"], "instances": [{"geometry": 0, "translation": [1e20, 0, 0]},)"
                      R"({"geometry": 0, "translation": [-1e20, 0, 0]}]})");
  expectOneLine("render " + scene + out, 1, scene + ": instance 0");
  const std::string edge =
      test::writeFile(dir, "edge.json",
                      R"({"geometries": ["cube.vgeo"], "instances": [{"geometry": 0, "scale": [1e13, 1e13, 1e13]}]})");
  expectOneLine("render " + edge + out + " --grid 2000", 1, "past +-1e15");
  EXPECT_FALSE(fs::exists(dir + "/o.png"));
}

TEST(HostileValues, SceneFilesAreCountedAndNestedShallow) {
  const std::string dir = test::tempDir();
  const std::string cube = dir + "/cube.vgeo", out = " -o " + dir + "/o.png --size 64x48";
  writeVgeo(test::build(test::cgalMesh("cube_quad.off"), 0), cube);
  // 80,000 levels of arrays inside an instance: refused before parsing, not by a stack overflow.
  const std::string deep = test::writeFile(dir, "deep.json",
                                           R"({"geometries": ["cube.vgeo"], "instances": [{"geometry": 0, "x": )" +
                                               std::string(80000, '[') + std::string(80000, ']') + "}]}");
  expectOneLine("render " + deep + out, 1, "nested deeper than 64");
  // One path named 400,000 times: read once (the scene draws one instance of it).
  std::string names = R"({"geometries": [)";
  for (int i = 0; i < 400000; i++) names += std::string(i ? "," : "") + "\"cube.vgeo\"";
  const std::string many = test::writeFile(dir, "many.json", names + R"(], "instances": [{"geometry": 399999}]})");
  const auto start = std::chrono::steady_clock::now();
  const test::RunResult r = test::runVgeo("render " + many + out);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  // Instances counted before any is made: a file of 65,536 instances placed 1,100 times, and a grid of
  // 33 x 33 copies of 65,536, pass the 67 M a scene may hold; refused at once.
  VgeoData d = test::build(test::cgalMesh("cube_quad.off"), 0);
  const shaderio::Instance one = d.instances[0];
  d.instances.assign(65536, one);
  for (size_t i = 0; i < d.instances.size(); i++) d.instances[i].row0.w = float(i) * 4.0f;
  writeVgeo(d, dir + "/crowd.vgeo");
  std::string placed = R"({"geometries": ["crowd.vgeo"], "instances": [)";
  for (int i = 0; i < 1100; i++) placed += std::string(i ? "," : "") + R"({"geometry": 0})";
  const std::string crowd = test::writeFile(dir, "crowd.json", placed + "]}");
  expectOneLine("render " + crowd + out, 1, "more than 67108863 instances");
  expectOneLine("render " + dir + "/crowd.vgeo" + out + " --grid 33", 1, "more than 67108863 instances");
}

TEST(HostileValues, InputsMustBeRegularFilesAndOutputsNamedOnce) {
  const std::string dir = test::tempDir();
  // A link to /dev/zero and a FIFO named like meshes: refused at once, neither read forever nor waited on.
  fs::remove(dir + "/zero.obj");
  fs::create_symlink("/dev/zero", dir + "/zero.obj");
  expectOneLine("build " + dir + "/zero.obj -o " + dir + "/z.vgeo -q", 1, "not a regular file");
  for (const char* fifo : {"pipe.off", "pipe.ply", "pipe.obj"}) {
    fs::remove(dir + "/" + fifo);
    test::runShell("mkfifo " + dir + "/" + fifo);
    expectOneLine("build " + dir + "/" + fifo + " -o " + dir + "/p.vgeo -q", 1, "not a regular file");
  }
  EXPECT_FALSE(fs::exists(dir + "/z.vgeo") || fs::exists(dir + "/p.vgeo"));
  // --stats naming the output, before either exists (and through ./): refused, nothing written.
  const std::string cow = test::cgalMesh("cow.off");
  expectOneLine("build " + cow + " -o " + dir + "/new.vgeo --stats " + dir + "/new.vgeo -q", 2, "--stats");
  expectOneLine("build " + cow + " -o " + dir + "/new.vgeo --stats " + dir + "/./new.vgeo -q", 2, "--stats");
  EXPECT_FALSE(fs::exists(dir + "/new.vgeo"));
}

TEST(HostileValues, ALinkPlantedAtTheTemporaryNameIsNotFollowed) {
  // The temporary name once was OUT.tmp.PID: a link planted there sent the write to its target, outside
  // the output's folder. Planted at that name and its neighbours now, the target stays as it was.
  const std::string dir = test::tempDir(), outside = test::tempDir();
  const std::string target = test::writeFile(outside, "precious.txt", "keep me\n");
  const std::string out = dir + "/planted.vgeo";
  const std::string base = out + ".tmp." + std::to_string(::getpid());
  fs::remove(base);
  fs::create_symlink(target, base);
  writeFileAtomically(out, "new contents\n");
  std::ifstream in(target);
  std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, "keep me\n");
  std::ifstream written(out);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(written)), std::istreambuf_iterator<char>()), "new contents\n");
  EXPECT_TRUE(fs::is_symlink(base));
}

TEST(HostileValues, GltfPlacementsAndRequiredExtensionsAreSaid) {
  const std::string dir = test::tempDir(), out = " -o " + dir + "/g.vgeo -q";
  SourceScene cube = loadMeshFile(test::cgalMesh("cube_quad.off"));
  // A scale past float's reach once left "0 instances" and exit 0; a zero scale hides a node.
  expectOneLine("build " + test::gltfOf(dir, "huge.gltf", cube.meshes[0], R"(, "scale": [1e20, 1e20, 1e20])") + out, 1,
                "past +-1e15");
  expectOneLine("build " + test::gltfOf(dir, "zero.gltf", cube.meshes[0], R"(, "scale": [0, 0, 0])") + out, 1,
                "every instance has a zero scale");
  EXPECT_FALSE(fs::exists(dir + "/g.vgeo"));
  // Required extensions: one that carries geometry vgeo does not read is refused; one of appearance is not.
  const std::string plain = test::readFile(test::gltfOf(dir, "plain.gltf", cube.meshes[0], ""));
  auto requiring = [&](const std::string& name, const std::string& ext) {
    std::string text = plain;
    text.replace(0, 1, "{\"extensionsUsed\": [\"" + ext + "\"], \"extensionsRequired\": [\"" + ext + "\"], ");
    return test::writeFile(dir, name, text);
  };
  expectOneLine("build " + requiring("instancing.gltf", "EXT_mesh_gpu_instancing") + out, 1,
                "requires the extension EXT_mesh_gpu_instancing");
  expectOneLine("build " + requiring("unknown.gltf", "VENDOR_something_new") + out, 1, "VENDOR_something_new");
  const test::RunResult texture = test::runVgeo("build " + requiring("texture.gltf", "KHR_texture_transform") + out);
  EXPECT_EQ(texture.exitCode, 0) << texture.output;
  // A skin without inverseBindMatrices (optional in glTF: identity) was refused by the parser's word.
  std::string skinned = plain;
  skinned.replace(skinned.find("\"nodes\": [{\"mesh\": 0"), 20,
                  "\"skins\": [{\"joints\": [0]}], \"nodes\": [{\"mesh\": 0, \"skin\": 0");
  const test::RunResult skin = test::runVgeo("build " + test::writeFile(dir, "skin.gltf", skinned) + out);
  EXPECT_EQ(skin.exitCode, 0) << skin.output;
}

TEST(HostileValues, NumbersAndHeadersReadAsWritten) {
  const std::string dir = test::tempDir(), cube = dir + "/cube.vgeo";
  writeVgeo(test::build(test::cgalMesh("cube_quad.off"), 0), cube);
  const std::string out = " -o " + dir + "/o.png";
  // Values past float, sizes that wrapped through sscanf's %u, junk after a size, unbounded workgroups.
  expectOneLine("render " + cube + out + " --tau 1e39", 2, "--tau");
  expectOneLine("render " + cube + out + " --size 4294967616x240", 2, "--size");
  expectOneLine("render " + cube + out + " --size 64x48junk", 2, "--size");
  expectOneLine("render " + cube + out + " --workgroups 4294967295", 2, "--workgroups");
  EXPECT_FALSE(fs::exists(dir + "/o.png"));
  // A UTF-8 byte order mark before an OBJ's first vertex; a PLY comment naming end_header: both read.
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const test::RunResult bom = test::runVgeo("build " + test::writeFile(dir, "bom.obj", "\xEF\xBB\xBF" + triangle) +
                                            " -o " + dir + "/bom.vgeo --stats " + dir + "/bom.json -q");
  EXPECT_EQ(bom.exitCode, 0) << bom.output;
  EXPECT_NE(test::readFile(dir + "/bom.json").find("\"input_triangles\": 4"), std::string::npos);
  const std::string ply =
      "ply\nformat ascii 1.0\ncomment written before end_header, not the end\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const test::RunResult comment =
      test::runVgeo("build " + test::writeFile(dir, "comment.ply", ply) + " -o " + dir + "/ply.vgeo -q");
  EXPECT_EQ(comment.exitCode, 0) << comment.output;
  // 4OFF has four coordinates a vertex: refused, not read as three and built into garbage.
  expectOneLine("build " +
                    test::writeFile(dir, "four.off", "4OFF\n4 1 0\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n3 0 1 2\n") +
                    " -o " + dir + "/four.vgeo -q",
                1, "unsupported OFF variant");
}

TEST(HostileValues, AHugePolygonBuildsInLinearTime) {
  // A 150,000-corner polygon: fanned from its first corner, its leaf clusters' dual graph looked through
  // 150,000 faces at that corner for each face (30 s). In strips it builds within the command's 20 s with
  // room to spare, and passes its check.
  const std::string dir = test::tempDir();
  std::string obj, face = "f";
  const int n = 150000;
  for (int i = 0; i < n; i++) {
    const double a = 6.283185307179586 * double(i) / double(n);
    obj += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    face += " " + std::to_string(i + 1);
  }
  const std::string path = test::writeFile(dir, "polygon.obj", obj + face + "\n");
  const auto start = std::chrono::steady_clock::now();
  const test::RunResult r = test::runVgeo("build " + path + " -o " + dir + "/p.vgeo -q");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  EXPECT_EQ(test::runVgeo("check " + dir + "/p.vgeo --cuts 2").exitCode, 0);
}

// The process's resident memory, bytes (Linux).
uint64_t residentBytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6)) << 10;
  return 0;
}

TEST(HostileValues, MemoryStaysFlatOverFrames) {
  // The viewer runs for hours: what a frame allocates must be given back. On lavapipe the frame constants
  // read from a uniform buffer had every dispatch compile its shader again with them inlined (Mesa 22.3
  // keeps each such variant until the pipeline goes): ~1 MB a frame at 64 x 64, 24 GB by 100,000 frames.
  VulkanContext vk({"", true});
  const std::string dir = test::tempDir();
  writeVgeo(test::build(test::asset("horned_cube.obj"), 2), dir + "/h.vgeo");
  const RenderScene scene = loadRenderScene(dir + "/h.vgeo", 2);
  GpuRenderer renderer(vk, scene, 64, 64);
  FrameSettings s = test::frameSettings(scene, test::orbit(scene, 0.4f, 0.3f, 2.5f), 1.0f, 64, 64);
  s.readDrawList = false;
  // Lists grown and every pipeline's code made (lavapipe compiles on first use) before measuring: one-
  // and two-pass frames both, since Auto picks by measured time and a loaded machine may switch late.
  for (Occlusion o : {Occlusion::Off, Occlusion::On, Occlusion::Auto}) {
    s.occlusion = o;
    for (int i = 0; i < 20; i++) renderer.renderFrame(s);
  }
  const uint64_t before = residentBytes();
  for (int i = 0; i < 300; i++) {
    s.drawView = s.cullView =
        makeView(test::orbit(scene, 0.4f + 0.01f * float(i % 7), 0.3f, 2.5f), 64, 64, scene.bounds);
    renderer.renderFrame(s);
  }
  const uint64_t after = residentBytes();
  EXPECT_LT(after, before + (uint64_t(24) << 20))
      << "resident memory grew from " << (before >> 20) << " to " << (after >> 20) << " MiB over 300 frames";
  EXPECT_EQ(vk.validationMessages(), 0u);
}

}  // namespace
}  // namespace vgeo

// load_gltf.cpp: glTF 2.0 reader (.gltf with external or embedded buffers, .glb) through tinygltf.
// Every triangle primitive of every mesh reached from the default scene is read; a mesh used by several
// nodes is read once and instanced, each node's world transform becoming an instance. Images are not
// decoded (the builder needs geometry and shading normals only).
//
// A glTF file names other files and nests JSON freely, so it is read defensively, before and around
// tinygltf:
// - the file is at most kMaxFileBytes, its JSON nested at most kMaxJsonDepth deep (tinygltf converts
//   `extras` recursively: a deep nest overflowed the stack);
// - a buffer or image URI is a data URI or a relative path to a regular file inside the glTF's folder
//   (no absolute path, no '..' or link out of it, no folder or device; tinygltf also looks in the
//   current folder, which the file system callbacks refuse), at most kMaxFileBytes;
// - the node graph is walked without recursion; a cycle, or more than kMaxInstances instances (a graph
//   that shares children level by level has 2^levels paths), is an error before anything is expanded;
// - every accessor is checked against its view and buffer with overflow-checked arithmetic before a
//   byte is read.
#include <tiny_gltf.h>

#include <filesystem>
#include <map>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "../common/json_depth.h"
#include "builder.h"
#include "text_reader.h"

namespace vgeo {
namespace {

constexpr uint64_t kMaxFileBytes = uint64_t(2) << 30;   // the glTF, the GLB, each buffer file
constexpr uint64_t kMaxInstances = uint64_t(1) << 18;   // node instances of meshes, from one file
constexpr uint64_t kMaxNodeVisits = 4 * kMaxInstances;  // node paths walked, meshes or not

bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

std::string firstLine(const std::string& text) {
  size_t start = text.find_first_not_of(" \n\r\t");
  if (start == std::string::npos) return "unknown error";
  size_t end = text.find_first_of("\n\r", start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// File system callbacks that keep tinygltf inside the glTF's folder.
struct Folder {
  std::filesystem::path root;  // canonical
  std::string file;            // the glTF, for messages
};

// The canonical path of `path` when it is a regular file inside the folder, else empty.
std::filesystem::path inside(const Folder& folder, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p(path);
  const fs::path resolved = fs::weakly_canonical(p.is_absolute() ? p : fs::current_path(ec) / p, ec);
  if (ec) return {};
  const fs::path rel = resolved.lexically_relative(folder.root);
  if (rel.empty() || *rel.begin() == ".." || rel.is_absolute()) return {};
  if (!fs::is_regular_file(resolved, ec)) return {};
  return resolved;
}

bool fileExists(const std::string& path, void* user) { return !inside(*static_cast<Folder*>(user), path).empty(); }

std::string expandFilePath(const std::string& path, void*) { return path; }  // no shell expansion

bool readFileInside(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const Folder& folder = *static_cast<Folder*>(user);
  const std::filesystem::path p = inside(folder, path);
  if (p.empty()) {
    *err = "not a file inside the glTF's folder";
    return false;
  }
  std::error_code ec;
  if (std::filesystem::file_size(p, ec) > kMaxFileBytes) {
    *err = "larger than " + std::to_string(kMaxFileBytes >> 30) + " GiB";
    return false;
  }
  const FillLaterVector<char> bytes = vgeo::readWholeFile(p.string());
  out->assign(bytes.begin(), bytes.end());
  return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "the builder writes no glTF files";
  return false;
}

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}

  SourceScene read() {
    SourceScene scene;
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (s >= int(model_.scenes.size())) fail("default scene " + std::to_string(s) + " does not exist");
      roots = model_.scenes[size_t(s)].nodes;
    } else {
      // No scene: every node that is nobody's child is a root.
      std::vector<bool> isChild(model_.nodes.size(), false);
      for (const auto& n : model_.nodes)
        for (int c : n.children)
          if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = true;
      for (size_t i = 0; i < model_.nodes.size(); i++)
        if (!isChild[i]) roots.push_back(int(i));
    }
    for (int r : roots) checkNode(r, "scene");
    countPaths(roots);
    if (model_.meshes.empty()) fail("empty mesh: no meshes (the 'meshes' array is missing, empty or not an array)");
    // Depth first, with an explicit stack of (node, parent transform).
    std::vector<std::pair<int, glm::mat4>> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.push_back({*r, glm::mat4(1.0f)});
    bool sawPrimitives = false;
    while (!stack.empty()) {
      auto [nodeIndex, parent] = stack.back();
      stack.pop_back();
      const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
      const glm::mat4 world = parent * localTransform(node, nodeIndex);
      if (node.mesh >= 0) {
        if (size_t(node.mesh) >= model_.meshes.size())
          fail("node " + std::to_string(nodeIndex) + " uses mesh " + std::to_string(node.mesh) +
               ", which does not exist");
        uint32_t id = meshId(node.mesh, scene, sawPrimitives);
        if (id != UINT32_MAX) scene.instances.push_back({world, id});
      }
      for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
    }
    if (scene.instances.empty())
      fail(sawPrimitives ? "empty mesh: the default scene shows points and lines only, no triangles"
                         : "empty mesh: the default scene shows no triangle mesh");
    return scene;
  }

 private:
  [[noreturn]] void fail(const std::string& cause) const { throw InputError(path_, cause); }

  void checkNode(int index, const std::string& from) const {
    if (index < 0 || size_t(index) >= model_.nodes.size())
      fail(from + " names node " + std::to_string(index) + ", which does not exist");
  }

  // Refuses cycles and graphs of more paths than kMaxInstances allows, before any is walked: nodes in
  // topological order (Kahn), then the paths reaching each node, saturating.
  void countPaths(const std::vector<int>& roots) const {
    const size_t n = model_.nodes.size();
    std::vector<uint32_t> parents(n, 0);
    for (size_t i = 0; i < n; i++)
      for (int c : model_.nodes[i].children) {
        checkNode(c, "node " + std::to_string(i));
        parents[size_t(c)]++;
      }
    std::vector<uint64_t> paths(n, 0);
    for (int r : roots) paths[size_t(r)] = std::min(paths[size_t(r)] + 1, kMaxNodeVisits + 1);
    std::vector<size_t> ready;
    for (size_t i = 0; i < n; i++)
      if (parents[i] == 0) ready.push_back(i);
    size_t ordered = 0;
    uint64_t visits = 0, instances = 0;
    while (!ready.empty()) {
      const size_t i = ready.back();
      ready.pop_back();
      ordered++;
      visits = std::min(visits + paths[i], kMaxNodeVisits + 1);
      if (model_.nodes[i].mesh >= 0) instances = std::min(instances + paths[i], kMaxInstances + 1);
      for (int c : model_.nodes[i].children) {
        paths[size_t(c)] = std::min(paths[size_t(c)] + paths[i], kMaxNodeVisits + 1);
        if (--parents[size_t(c)] == 0) ready.push_back(size_t(c));
      }
    }
    if (ordered < n) {
      for (size_t i = 0; i < n; i++)
        if (parents[i] > 0) fail("node " + std::to_string(i) + " is its own ancestor (cyclic node graph)");
    }
    if (instances > kMaxInstances)
      fail("the node graph places meshes more than " + std::to_string(kMaxInstances) +
           " times (the limit of instances from one file)");
    if (visits > kMaxNodeVisits)
      fail("the node graph reaches nodes by more than " + std::to_string(kMaxNodeVisits) + " paths");
  }

  glm::mat4 localTransform(const tinygltf::Node& node, int nodeIndex) const {
    glm::mat4 local(1.0f);
    if (node.matrix.size() == 16) {
      for (int i = 0; i < 16; i++) glm::value_ptr(local)[i] = float(node.matrix[size_t(i)]);
    } else {
      glm::mat4 t(1.0f), r(1.0f), s(1.0f);
      if (node.translation.size() == 3)
        t = glm::translate(glm::mat4(1.0f), glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
      if (node.rotation.size() == 4)
        r = glm::mat4_cast(glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]),
                                     float(node.rotation[2])));
      if (node.scale.size() == 3)
        s = glm::scale(glm::mat4(1.0f), glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
      local = t * r * s;
    }
    for (int i = 0; i < 16; i++)
      if (!std::isfinite(glm::value_ptr(local)[i]) || std::abs(glm::value_ptr(local)[i]) > 1e30f)
        fail("node " + std::to_string(nodeIndex) + " has a non-finite or huge transform");
    return local;
  }

  // The scene's id of glTF mesh `index`, reading it the first time; UINT32_MAX when it has no triangles.
  uint32_t meshId(int index, SourceScene& scene, bool& sawPrimitives) {
    auto found = meshIds_.find(index);
    if (found != meshIds_.end()) return found->second;
    PolygonMesh mesh = readMesh(model_.meshes[size_t(index)], index);
    sawPrimitives |= !model_.meshes[size_t(index)].primitives.empty();
    uint32_t id = UINT32_MAX;
    if (mesh.faceCount() > 0) {
      id = uint32_t(scene.meshes.size());
      scene.meshes.push_back(std::move(mesh));
      std::string name = model_.meshes[size_t(index)].name;
      scene.meshNames.push_back(name.empty() ? "mesh" + std::to_string(index) : name);
    }
    meshIds_[index] = id;
    return id;
  }

  // Checks an accessor against its view and buffer (every sum and product overflow-checked); returns a
  // pointer to element 0 and the stride.
  const unsigned char* accessorData(int index, int type, const std::vector<int>& componentTypes, size_t& stride,
                                    size_t& count, const char* what) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
      fail(std::string(what) + " accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    std::string name = std::string(what) + " accessor " + std::to_string(index);
    if (a.type != type) fail(name + " has the wrong type");
    bool typeOk = false;
    for (int ct : componentTypes) typeOk |= a.componentType == ct;
    if (!typeOk) fail(name + " has the wrong component type");
    if (a.sparse.isSparse) fail(name + " is sparse, which is not supported");
    if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size()) fail(name + " has no valid bufferView");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) fail(name + " refers to a missing buffer");
    const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
    const size_t elementSize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType)) *
                                      tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    stride = view.byteStride ? view.byteStride : elementSize;
    count = a.count;
    if (stride < elementSize)
      fail("bufferView " + std::to_string(a.bufferView) + " has a stride smaller than " + name + "'s elements");
    uint64_t span = 0, end = 0, viewEnd = 0;
    const bool overflow = count > 0 && (__builtin_mul_overflow(uint64_t(stride), uint64_t(count - 1), &span) ||
                                        __builtin_add_overflow(span, uint64_t(elementSize), &span));
    if (overflow || __builtin_add_overflow(uint64_t(a.byteOffset), span, &end) || end > view.byteLength)
      fail(name + " (" + std::to_string(count) + " elements from byte " + std::to_string(a.byteOffset) +
           ") reads past the end of bufferView " + std::to_string(a.bufferView));
    if (__builtin_add_overflow(uint64_t(view.byteOffset), uint64_t(view.byteLength), &viewEnd) ||
        viewEnd > buffer.data.size())
      fail("bufferView " + std::to_string(a.bufferView) + " reads past the end of buffer " +
           std::to_string(view.buffer) + (buffer.data.empty() ? " (the buffer is missing or empty)" : ""));
    return buffer.data.data() + view.byteOffset + a.byteOffset;
  }

  PolygonMesh readMesh(const tinygltf::Mesh& source, int meshIndex) const {
    PolygonMesh mesh;
    for (size_t p = 0; p < source.primitives.size(); p++) {
      const tinygltf::Primitive& prim = source.primitives[p];
      int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
        continue;
      auto position = prim.attributes.find("POSITION");
      std::string where = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p);
      if (position == prim.attributes.end()) fail(where + " has no POSITION attribute");
      size_t stride = 0, vertexCount = 0;
      const unsigned char* data = accessorData(position->second, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT},
                                               stride, vertexCount, "POSITION");
      uint32_t base = uint32_t(mesh.positions.size());
      if (uint64_t(base) + vertexCount > UINT32_MAX) fail(where + ": too many vertices for 32-bit indices");
      for (size_t v = 0; v < vertexCount; v++) {
        glm::vec3 pos;
        std::memcpy(&pos, data + v * stride, sizeof(pos));
        mesh.positions.push_back(pos);
      }
      // Shading normals: NORMAL where given; without it the specification asks for flat shading.
      std::vector<glm::vec3> normals;
      auto normal = prim.attributes.find("NORMAL");
      if (normal != prim.attributes.end()) {
        size_t nstride = 0, ncount = 0;
        const unsigned char* ndata = accessorData(normal->second, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT},
                                                  nstride, ncount, "NORMAL");
        if (ncount != vertexCount)
          fail(where + ": " + std::to_string(ncount) + " normals for " + std::to_string(vertexCount) + " positions");
        normals.resize(ncount);
        for (size_t v = 0; v < ncount; v++) std::memcpy(&normals[v], ndata + v * nstride, sizeof(glm::vec3));
      }
      std::vector<uint32_t> indices;
      if (prim.indices >= 0) {
        size_t istride = 0, icount = 0;
        const unsigned char* idata =
            accessorData(prim.indices, TINYGLTF_TYPE_SCALAR,
                         {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                         istride, icount, "index");
        int ct = model_.accessors[size_t(prim.indices)].componentType;
        indices.resize(icount);  // bounded by the buffer, checked above
        for (size_t i = 0; i < icount; i++) {
          const unsigned char* e = idata + i * istride;
          uint32_t v = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? *e
                       : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                           ? uint32_t(e[0] | e[1] << 8)
                           : uint32_t(e[0] | e[1] << 8 | e[2] << 16 | uint32_t(e[3]) << 24);
          if (v >= vertexCount)
            fail(where + ": index " + std::to_string(i) + " is " + std::to_string(v) + ", out of range (" +
                 std::to_string(vertexCount) + " vertices)");
          indices[i] = v;
        }
      } else {
        indices.resize(vertexCount);
        for (size_t i = 0; i < vertexCount; i++) indices[i] = uint32_t(i);
      }
      auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
        uint32_t t[3] = {base + a, base + b, base + c};
        glm::vec3 n[3];
        if (!normals.empty()) {
          n[0] = normals[a], n[1] = normals[b], n[2] = normals[c];
        } else {
          const glm::vec3 &pa = mesh.positions[t[0]], &pb = mesh.positions[t[1]], &pc = mesh.positions[t[2]];
          n[0] = n[1] = n[2] = glm::cross(pb - pa, pc - pa);
        }
        mesh.addFace(t, 3, n);
      };
      if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (indices.size() % 3)
          fail(where + ": " + std::to_string(indices.size()) + " indices is not a whole number of triangles");
        for (size_t i = 0; i + 2 < indices.size(); i += 3) add(indices[i], indices[i + 1], indices[i + 2]);
      } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < indices.size(); i++)
          i % 2 ? add(indices[i + 1], indices[i], indices[i + 2]) : add(indices[i], indices[i + 1], indices[i + 2]);
      } else {
        for (size_t i = 1; i + 1 < indices.size(); i++) add(indices[0], indices[i], indices[i + 1]);
      }
    }
    return mesh;
  }

  const tinygltf::Model& model_;
  std::string path_;
  std::map<int, uint32_t> meshIds_;
};

}  // namespace

SourceScene loadGltf(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path, "cannot open: not a regular file");
  if (fs::file_size(path, ec) > kMaxFileBytes)
    throw InputError(path, "larger than the " + std::to_string(kMaxFileBytes >> 30) + " GiB a glTF file may be");
  const FillLaterVector<char> bytes = vgeo::readWholeFile(path);
  const bool binary = bytes.size() >= 4 && std::string_view(bytes.data(), 4) == "glTF";
  // The JSON's nesting, before tinygltf walks it recursively (a GLB's JSON chunk follows its 20-byte
  // headers, its length in bytes 12..15).
  const char* json = bytes.data();
  size_t jsonSize = bytes.size();
  if (binary) {
    if (bytes.size() < 20) throw InputError(path, "truncated GLB: no JSON chunk");
    uint32_t chunk = 0;
    std::memcpy(&chunk, bytes.data() + 12, 4);
    json = bytes.data() + 20;
    jsonSize = std::min<size_t>(chunk, bytes.size() - 20);
  }
  if (jsonDepth(json, jsonSize, kMaxJsonDepth) > kMaxJsonDepth)
    throw InputError(path, "its JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");

  Folder folder{fs::weakly_canonical(fs::absolute(fs::path(path)).parent_path(), ec), path};
  tinygltf::FsCallbacks callbacks{fileExists, expandFilePath, readFileInside, writeWholeFile, &folder};
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  loader.SetFsCallbacks(callbacks);
  tinygltf::Model model;
  std::string err, warn;
  const std::string base = folder.root.string();
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                              unsigned(bytes.size()), base)
                : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base);
  } catch (const std::exception& e) {
    throw InputError(path, std::string("not a valid glTF file (") + e.what() + ")");
  }
  // tinygltf calls a skin's inverseBindMatrices required, where glTF makes it optional (identity), and
  // says so in `err` while loading on: not a fault of the file (and skins do not change a static mesh).
  for (const std::string benign :
       {"'inverseBindMatrices' property is missing in Skin.\n", "'inverseBindMatrices' property is missing in Skin."})
    for (size_t at; (at = err.find(benign)) != std::string::npos;) err.erase(at, benign.size());
  if (!ok || !err.empty()) {
    std::string cause = firstLine(err.empty() ? "not a valid glTF file" : err);
    if (cause.rfind("File not found", 0) == 0 || cause.rfind("File read error", 0) == 0)
      cause += " (a buffer is a data URI or a relative path to a regular file inside the glTF's folder)";
    throw InputError(path, cause);
  }
  // A required extension must be understood or the file refused (glTF 2.0, 3.12): those that change
  // geometry (instancing, compression, quantized positions) are not read here, and an unknown one may
  // be anything. Those that only change appearance leave the shape as the builder reads it.
  for (const std::string& ext : model.extensionsRequired) {
    const bool appearance = ext.rfind("KHR_materials_", 0) == 0 || ext == "KHR_texture_transform" ||
                            ext == "KHR_texture_basisu" || ext == "KHR_lights_punctual" || ext == "EXT_texture_webp";
    if (!appearance)
      throw InputError(path,
                       "requires the extension " + ext + ", which vgeo does not read (its geometry would be lost)");
  }
  return GltfReader(model, path).read();
}

}  // namespace vgeo

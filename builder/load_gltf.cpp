// load_gltf.cpp: glTF 2.0 reader (.gltf with external or embedded buffers, .glb) through tinygltf.
// Every triangle primitive of every mesh reached from the default scene is read; a mesh used by several
// nodes is read once and instanced, each node's world transform becoming an instance. Images are not
// decoded (the builder needs geometry and shading normals only). Accessors are checked against their buffers before any
// read, so a bad file is an error, never an out-of-bounds read.
#include <tiny_gltf.h>

#include <map>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "builder.h"

namespace vgeo {
namespace {

bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

std::string firstLine(const std::string& text) {
  size_t start = text.find_first_not_of(" \n\r\t");
  if (start == std::string::npos) return "unknown error";
  size_t end = text.find_first_of("\n\r", start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
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
    onPath_.assign(model_.nodes.size(), false);
    for (int r : roots) visit(r, glm::mat4(1.0f), scene);
    if (model_.meshes.empty()) fail("empty mesh: no meshes (the 'meshes' array is missing, empty or not an array)");
    if (scene.instances.empty()) fail("empty mesh: the default scene shows no triangle mesh");
    return scene;
  }

 private:
  [[noreturn]] void fail(const std::string& cause) const { throw InputError(path_, cause); }

  void visit(int nodeIndex, const glm::mat4& parent, SourceScene& scene) {
    if (nodeIndex < 0 || size_t(nodeIndex) >= model_.nodes.size()) fail("node index " + std::to_string(nodeIndex) + " is out of range");
    if (onPath_[size_t(nodeIndex)]) fail("node " + std::to_string(nodeIndex) + " is its own ancestor (cyclic node graph)");
    const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
    glm::mat4 local(1.0f);
    if (node.matrix.size() == 16) {
      for (int i = 0; i < 16; i++) glm::value_ptr(local)[i] = float(node.matrix[size_t(i)]);
    } else {
      glm::mat4 t(1.0f), r(1.0f), s(1.0f);
      if (node.translation.size() == 3) t = glm::translate(glm::mat4(1.0f), glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
      if (node.rotation.size() == 4)
        r = glm::mat4_cast(glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2])));
      if (node.scale.size() == 3) s = glm::scale(glm::mat4(1.0f), glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
      local = t * r * s;
    }
    glm::mat4 world = parent * local;
    for (int i = 0; i < 16; i++)
      if (!std::isfinite(glm::value_ptr(world)[i])) fail("node " + std::to_string(nodeIndex) + " has a non-finite transform");
    if (node.mesh >= 0) {
      if (size_t(node.mesh) >= model_.meshes.size()) fail("node " + std::to_string(nodeIndex) + " uses mesh " + std::to_string(node.mesh) + ", which does not exist");
      auto found = meshIds_.find(node.mesh);
      uint32_t id;
      if (found != meshIds_.end()) {
        id = found->second;
      } else {
        PolygonMesh mesh = readMesh(model_.meshes[size_t(node.mesh)], node.mesh);
        id = uint32_t(scene.meshes.size());
        meshIds_[node.mesh] = id;
        if (mesh.faceCount() > 0) {
          scene.meshes.push_back(std::move(mesh));
          std::string name = model_.meshes[size_t(node.mesh)].name;
          scene.meshNames.push_back(name.empty() ? "mesh" + std::to_string(node.mesh) : name);
        } else {
          id = UINT32_MAX;  // points or lines only: nothing to build
          meshIds_[node.mesh] = id;
        }
      }
      if (id != UINT32_MAX) scene.instances.push_back({world, id});
    }
    onPath_[size_t(nodeIndex)] = true;
    for (int c : node.children) visit(c, world, scene);
    onPath_[size_t(nodeIndex)] = false;
  }

  // Checks an accessor against its view and buffer; returns a pointer to element 0 and the stride.
  const unsigned char* accessorData(int index, int type, const std::vector<int>& componentTypes, size_t& stride,
                                    size_t& count, const char* what) const {
    if (index < 0 || size_t(index) >= model_.accessors.size()) fail(std::string(what) + " accessor " + std::to_string(index) + " does not exist");
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
    size_t elementSize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType)) * tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    stride = view.byteStride ? view.byteStride : elementSize;
    count = a.count;
    uint64_t end = uint64_t(a.byteOffset) + (count ? uint64_t(stride) * (count - 1) + elementSize : 0);
    if (end > view.byteLength) fail(name + " reads past the end of bufferView " + std::to_string(a.bufferView));
    if (uint64_t(view.byteOffset) + view.byteLength > buffer.data.size())
      fail("bufferView " + std::to_string(a.bufferView) + " reads past the end of buffer " + std::to_string(view.buffer) +
           (buffer.data.empty() ? " (the buffer is missing or empty)" : ""));
    return buffer.data.data() + view.byteOffset + a.byteOffset;
  }

  PolygonMesh readMesh(const tinygltf::Mesh& source, int meshIndex) const {
    PolygonMesh mesh;
    for (size_t p = 0; p < source.primitives.size(); p++) {
      const tinygltf::Primitive& prim = source.primitives[p];
      int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) continue;
      auto position = prim.attributes.find("POSITION");
      std::string where = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(p);
      if (position == prim.attributes.end()) fail(where + " has no POSITION attribute");
      size_t stride = 0, vertexCount = 0;
      const unsigned char* data = accessorData(position->second, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, stride, vertexCount, "POSITION");
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
        const unsigned char* ndata = accessorData(normal->second, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, nstride, ncount, "NORMAL");
        if (ncount != vertexCount) fail(where + ": " + std::to_string(ncount) + " normals for " + std::to_string(vertexCount) + " positions");
        normals.resize(ncount);
        for (size_t v = 0; v < ncount; v++) std::memcpy(&normals[v], ndata + v * nstride, sizeof(glm::vec3));
      }
      std::vector<uint32_t> indices;
      if (prim.indices >= 0) {
        size_t istride = 0, icount = 0;
        const unsigned char* idata = accessorData(prim.indices, TINYGLTF_TYPE_SCALAR,
            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
            istride, icount, "index");
        int ct = model_.accessors[size_t(prim.indices)].componentType;
        indices.resize(icount);
        for (size_t i = 0; i < icount; i++) {
          const unsigned char* e = idata + i * istride;
          uint32_t v = ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ? *e
                       : ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? uint32_t(e[0] | e[1] << 8)
                       : uint32_t(e[0] | e[1] << 8 | e[2] << 16 | uint32_t(e[3]) << 24);
          if (v >= vertexCount)
            fail(where + ": index " + std::to_string(i) + " is " + std::to_string(v) + ", out of range (" + std::to_string(vertexCount) + " vertices)");
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
        if (indices.size() % 3) fail(where + ": " + std::to_string(indices.size()) + " indices is not a whole number of triangles");
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
  std::vector<bool> onPath_;
  std::map<int, uint32_t> meshIds_;
};

}  // namespace

SourceScene loadGltf(const std::string& path) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  bool binary = path.size() >= 4 && (path.substr(path.size() - 4) == ".glb" || path.substr(path.size() - 4) == ".GLB");
  {
    // Fail early with a clear message when the file itself cannot be read.
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
    std::fclose(f);
  }
  bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path) : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok || !err.empty()) throw InputError(path, firstLine(err.empty() ? "not a valid glTF file" : err));
  return GltfReader(model, path).read();
}

}  // namespace vgeo

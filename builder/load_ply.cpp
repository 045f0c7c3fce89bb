// load_ply.cpp: Stanford PLY reader, ASCII and binary (either byte order). Reads the vertex element's
// x, y, z (and nx, ny, nz, the shading normals, when all three are there) and the face element's
// vertex_indices (or vertex_index) list; every other element and property is skipped by its declared
// type, so files with colours or extra elements load.
#include <cmath>
#include <cstring>

#include "text_reader.h"

namespace vgeo {
namespace {

enum class Type { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64, Invalid };

Type parseType(std::string_view name) {
  if (name == "char" || name == "int8") return Type::Int8;
  if (name == "uchar" || name == "uint8") return Type::Uint8;
  if (name == "short" || name == "int16") return Type::Int16;
  if (name == "ushort" || name == "uint16") return Type::Uint16;
  if (name == "int" || name == "int32") return Type::Int32;
  if (name == "uint" || name == "uint32") return Type::Uint32;
  if (name == "float" || name == "float32") return Type::Float32;
  if (name == "double" || name == "float64") return Type::Float64;
  return Type::Invalid;
}
size_t typeSize(Type t) {
  static const size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8, 0};
  return sizes[int(t)];
}

struct Property {
  std::string name;
  Type type = Type::Invalid;
  Type countType = Type::Invalid;  // lists only
  bool isList = false;
};
struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

// The value of type T in the first sizeof(T) bytes (host byte order), as a double.
template <class T>
double as(const unsigned char* bytes) {
  T v;
  std::memcpy(&v, bytes, sizeof v);
  return double(v);
}

// Reads values one at a time from either the ASCII body or a binary body of either byte order.
class ValueReader {
 public:
  ValueReader(std::string_view body, size_t bodyOffset, const std::string& file, int format)
      : text_(body, file), body_(body), file_(file), format_(format), bodyOffset_(bodyOffset) {}

  double read(Type t) {
    if (format_ == 0) return text_.number<double>("a number");
    size_t size = typeSize(t);
    if (pos_ + size > body_.size())
      throw InputError(file_, "truncated: binary data ends at byte " + std::to_string(bodyOffset_ + body_.size()));
    unsigned char bytes[8];
    std::memcpy(bytes, body_.data() + pos_, size);
    pos_ += size;
    if (format_ == 2)
      for (size_t i = 0; i < size / 2; i++) std::swap(bytes[i], bytes[size - 1 - i]);
    switch (t) {
      case Type::Int8:
        return as<int8_t>(bytes);
      case Type::Uint8:
        return as<uint8_t>(bytes);
      case Type::Int16:
        return as<int16_t>(bytes);
      case Type::Uint16:
        return as<uint16_t>(bytes);
      case Type::Int32:
        return as<int32_t>(bytes);
      case Type::Uint32:
        return as<uint32_t>(bytes);
      case Type::Float32:
        return as<float>(bytes);
      case Type::Float64:
        return as<double>(bytes);
      default:
        return 0;
    }
  }
  uint64_t bytesLeft() const { return format_ == 0 ? body_.size() : body_.size() - pos_; }

 private:
  TextReader text_;
  std::string_view body_;
  std::string file_;
  int format_;  // 0 ascii, 1 little endian, 2 big endian
  size_t bodyOffset_;
  size_t pos_ = 0;
};

}  // namespace

SourceScene loadPly(const std::string& path) {
  const FillLaterVector<char> bytes = readWholeFile(path);
  const std::string_view data(bytes.data(), bytes.size());
  // The header ends at a line that is "end_header" (a comment may contain the words).
  size_t headerEnd = std::string_view::npos;
  for (size_t at = 0; at < data.size();) {
    const size_t eol = std::min(data.find('\n', at), data.size());
    std::string_view line = data.substr(at, eol - at);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    if (line == "end_header") {
      headerEnd = at;
      break;
    }
    at = eol + 1;
  }
  if (data.compare(0, 3, "ply") != 0) throw InputError(path, "not a PLY file (no 'ply' magic)");
  if (headerEnd == std::string_view::npos) throw InputError(path, "truncated: no 'end_header' line");
  size_t bodyStart = data.find('\n', headerEnd);
  bodyStart = bodyStart == std::string_view::npos ? data.size() : bodyStart + 1;

  TextReader header(std::string_view(data).substr(0, headerEnd), path);
  int format = -1;
  std::vector<Element> elements;
  header.skipLine();  // "ply"
  while (!header.atEnd()) {
    std::string_view keyword = header.token();
    if (keyword == "format") {
      std::string_view f = header.token();
      format = f == "ascii" ? 0 : f == "binary_little_endian" ? 1 : f == "binary_big_endian" ? 2 : -1;
      if (format < 0) header.fail("unknown PLY format '" + std::string(f) + "'");
    } else if (keyword == "element") {
      Element e;
      e.name = std::string(header.token());
      if (!header.tryNumber(e.count)) header.fail("element '" + e.name + "' needs a count");
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) header.fail("property before any element");
      Property p;
      std::string_view type = header.token();
      if (type == "list") {
        p.isList = true;
        p.countType = parseType(header.token());
        type = header.token();
        if (p.countType == Type::Invalid || p.countType == Type::Float32 || p.countType == Type::Float64)
          header.fail("bad list count type");
      }
      p.type = parseType(type);
      if (p.type == Type::Invalid) header.fail("unknown property type '" + std::string(type) + "'");
      p.name = std::string(header.token());
      elements.back().properties.push_back(p);
    }
    header.skipLine();
  }
  if (format < 0) throw InputError(path, "no 'format' line in the header");

  ValueReader in(std::string_view(data).substr(bodyStart), bodyStart, path, format);
  PolygonMesh mesh;
  std::vector<glm::vec3> vertexNormals;
  bool sawVertices = false;
  std::vector<uint32_t> corners;
  bool sawFaces = false;
  for (const Element& e : elements) {
    // An element without properties holds nothing to read, whatever its count (a count of 2^63 with
    // nothing to read made the loop below spin for ever).
    if (e.properties.empty()) continue;
    // Every item of any other element takes at least one byte: larger counts are lies, not allocations.
    if (e.count > in.bytesLeft())
      throw InputError(path, "truncated: element '" + e.name + "' declares " + std::to_string(e.count) +
                                 " items, more than the file holds");
    bool isVertex = e.name == "vertex", isFace = e.name == "face";
    if ((isVertex && sawVertices) || (isFace && sawFaces)) throw InputError(path, "a second '" + e.name + "' element");
    sawFaces |= isFace;
    int xyz[3] = {-1, -1, -1}, nxyz[3] = {-1, -1, -1};
    int indexList = -1;
    for (size_t i = 0; i < e.properties.size(); i++) {
      const Property& p = e.properties[i];
      if (isVertex && !p.isList && (p.name == "x" || p.name == "y" || p.name == "z")) xyz[p.name[0] - 'x'] = int(i);
      if (isVertex && !p.isList && (p.name == "nx" || p.name == "ny" || p.name == "nz")) nxyz[p.name[1] - 'x'] = int(i);
      if (isFace && p.isList && (p.name == "vertex_indices" || p.name == "vertex_index")) indexList = int(i);
    }
    if (isVertex) {
      if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw InputError(path, "vertex element lacks x, y or z");
      if (e.count > UINT32_MAX) throw InputError(path, "too many vertices for 32-bit indices");
      mesh.positions.resize(e.count);
      vertexNormals.assign(nxyz[0] >= 0 && nxyz[1] >= 0 && nxyz[2] >= 0 ? e.count : 0, glm::vec3(0.0f));
      sawVertices = true;
    }
    if (isFace && indexList < 0) throw InputError(path, "face element lacks a vertex_indices list");
    for (uint64_t item = 0; item < e.count; item++) {
      for (size_t i = 0; i < e.properties.size(); i++) {
        const Property& p = e.properties[i];
        if (!p.isList) {
          double v = in.read(p.type);
          for (int k = 0; k < 3; k++) {
            if (isVertex && int(i) == xyz[k]) mesh.positions[item][k] = float(v);
            if (isVertex && int(i) == nxyz[k] && !vertexNormals.empty()) vertexNormals[item][k] = float(v);
          }
          continue;
        }
        double n = in.read(p.countType);
        if (!(n >= 0 && n <= double(1 << 20) && n == std::floor(n)))  // NaN fails every comparison
          throw InputError(path, "bad list size " + std::to_string(n) + " in element '" + e.name + "'");
        if (isFace && int(i) == indexList) corners.resize(size_t(n));
        for (size_t k = 0; k < size_t(n); k++) {
          double v = in.read(p.type);
          if (isFace && int(i) == indexList) {
            // In range first (NaN fails it), so that the casts below are defined.
            if (!sawVertices || !(v >= 0 && v < double(mesh.positions.size())) || v != std::floor(v))
              throw InputError(path, "face " + std::to_string(item) + " has vertex index " + std::to_string(v) +
                                         ", out of range (" + std::to_string(mesh.positions.size()) + " vertices)");
            corners[k] = uint32_t(v);
          }
        }
        if (isFace && int(i) == indexList) mesh.addFace(corners.data(), corners.size());
      }
    }
  }
  if (!sawVertices) throw InputError(path, "no vertex element");
  if (!vertexNormals.empty())
    for (uint32_t v : mesh.faceVertices) mesh.cornerNormals.push_back(vertexNormals[v]);
  return singleMeshScene(std::move(mesh));
}

}  // namespace vgeo

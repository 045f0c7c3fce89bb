// load_obj.cpp: Wavefront OBJ reader. Keeps polygons (faces of any size); reads `v`, `vn` and `f`
// records: positions, connectivity and the shading normals a face's corners name (v//vn, v/vt/vn). A
// corner without a normal, in a file whose other corners have them, shades with its face's normal.
// All objects and groups of the file become one mesh.
// A record is one line, and only a negative index looks back (at the vertices or normals read so
// far), so a large file is read in pieces of whole lines on several threads: a first pass counts each
// piece's lines, `v` and `vn` records, and the second parses each piece knowing where it starts. The
// first error in the file is the one reported, as a reading from the start would find it.
#include <algorithm>
#include <exception>

#include "../common/parallel.h"
#include "text_reader.h"

namespace vgeo {

namespace {
// The line of the file's face record number `face` (0-based), for an error found after reading: lines
// are not kept for every face, which on a large file would take more memory than the faces.
size_t lineOfFace(std::string_view data, const std::string& path, size_t face) {
  TextReader in(data, path);
  for (size_t seen = 0;; in.skipLine()) {
    in.skipWhitespaceAndComments();
    if (in.atEnd()) return in.line();
    if (in.token() == "f" && seen++ == face) return in.line();
  }
}

// What a piece of the file holds. cornerNormal: a corner's vn index (0-based, -1 for none), kept only
// from the first face that names a normal on (`named`; most large files have none, and this list
// would be the largest), with -1 for the corners before.
struct ObjPiece {
  PolygonMesh mesh;
  std::vector<glm::vec3> normals;
  std::vector<int64_t> cornerNormal;
  bool named = false;
};

// A piece's lines, and its `v`, `vn` and `f` records: a record's keyword is the first word of its line
// (TextReader's words: ends at a blank, '\r' or '\n'; a line starting with '#' is a comment).
struct PieceCounts {
  size_t lines = 0, vertices = 0, normals = 0, faces = 0;
};
PieceCounts countPiece(std::string_view text) {
  PieceCounts c;
  for (size_t i = 0; i < text.size();) {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r')) i++;
    const size_t start = i;
    while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\r' && text[i] != '\n') i++;
    const std::string_view word = text.substr(start, i - start);
    if (word == "v") c.vertices++;
    if (word == "vn") c.normals++;
    if (word == "f") c.faces++;
    const size_t end = text.find('\n', i);
    if (end == std::string_view::npos) break;
    c.lines++;
    i = end + 1;
  }
  return c;
}

// Parses one piece of whole lines, which starts at line `firstLine` after `vertexBase` vertices and
// `normalBase` normals of the file; `counts` are the piece's own (its arrays are made that size, its
// corners three a face, at once).
ObjPiece parsePiece(std::string_view text, const std::string& path, size_t firstLine, size_t vertexBase,
                    size_t normalBase, const PieceCounts& counts) {
  TextReader in(text, path, firstLine);
  ObjPiece piece;
  PolygonMesh& mesh = piece.mesh;
  std::vector<glm::vec3>& normals = piece.normals;
  mesh.positions.reserve(counts.vertices);
  normals.reserve(counts.normals);
  mesh.faceStart.reserve(counts.faces + 1);
  mesh.faceVertices.reserve(3 * counts.faces);
  std::vector<int64_t>& cornerNormal = piece.cornerNormal;
  std::vector<uint32_t> corners;
  std::vector<int64_t> rawCorners, rawNormals;
  while (true) {
    in.skipWhitespaceAndComments();
    if (in.atEnd()) break;
    std::string_view keyword = in.token();
    if (keyword == "v") {
      glm::vec3 p;
      for (int i = 0; i < 3; i++)
        if (!in.tryNumber(p[i])) in.fail("vertex needs three numbers");
      mesh.positions.push_back(p);
    } else if (keyword == "vn") {
      glm::vec3 n;
      for (int i = 0; i < 3; i++)
        if (!in.tryNumber(n[i])) in.fail("normal needs three numbers");
      normals.push_back(n);
    } else if (keyword == "f") {
      rawCorners.clear();
      rawNormals.clear();
      while (!in.atLineEnd()) {
        int64_t plain = 0;
        if (in.tryPlainIndex(plain)) {  // most files' corners: a vertex index alone
          rawNormals.push_back(-1);
          rawCorners.push_back(plain - 1);
          continue;
        }
        std::string_view whole = in.token();
        std::string_view t = whole.substr(0, whole.find('/'));  // v/vt/vn: the position index comes first
        int64_t normalIndex = -1;
        size_t second = whole.find('/', t.size() + 1);
        if (t.size() < whole.size() && second != std::string_view::npos && second + 1 < whole.size()) {
          std::string_view n = whole.substr(second + 1);
          int64_t value = 0;
          auto [nend, nec] = std::from_chars(n.data(), n.data() + n.size(), value);
          if (nec != std::errc() || nend != n.data() + n.size() || value == 0)
            in.fail("bad normal index '" + std::string(n) + "'");
          if (value < 0) value += int64_t(normalBase + normals.size()) + 1;
          if (value <= 0) in.fail("normal index " + std::string(n) + " refers before the first normal");
          normalIndex = value - 1;
        }
        rawNormals.push_back(normalIndex);
        int64_t index = 0;
        auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), index);
        if (ec != std::errc() || end != t.data() + t.size() || index == 0)
          in.fail("bad face index '" + std::string(t) + "'");
        // Negative indices count back from the vertices read so far.
        if (index < 0) index += int64_t(vertexBase + mesh.positions.size()) + 1;
        if (index <= 0) in.fail("face index " + std::string(t) + " refers before the first vertex");
        rawCorners.push_back(index - 1);
      }
      corners.clear();
      for (int64_t c : rawCorners) {
        if (c > int64_t(UINT32_MAX) - 1) in.fail("face index too large for 32-bit indices");
        corners.push_back(uint32_t(c));
      }
      const bool named = std::any_of(rawNormals.begin(), rawNormals.end(), [](int64_t n) { return n >= 0; });
      if (named && !piece.named) {
        cornerNormal.assign(mesh.faceVertices.size(), -1);
        piece.named = true;
      }
      mesh.addFace(corners.data(), corners.size());
      if (piece.named) cornerNormal.insert(cornerNormal.end(), rawNormals.begin(), rawNormals.end());
    }
    in.skipLine();
  }
  return piece;
}

}  // namespace

SourceScene loadObj(const std::string& path, int threads) {
  const FillLaterVector<char> bytes = readWholeFile(path, threads);
  const std::string_view data = withoutByteOrderMark(std::string_view(bytes.data(), bytes.size()));
  const std::vector<std::string_view> piece = linePieces(data, threads, 20);  // pieces of 1 MB or more
  const size_t pieces = piece.size();
  std::vector<PieceCounts> counts(pieces);
  parallelFor(pieces, threads, [&](size_t k) { counts[k] = countPiece(piece[k]); });
  std::vector<ObjPiece> parsed(pieces);
  std::vector<std::exception_ptr> errors(pieces);
  std::vector<PieceCounts> before(pieces);  // of the pieces before each
  for (size_t k = 1; k < pieces; k++)
    before[k] = {before[k - 1].lines + counts[k - 1].lines, before[k - 1].vertices + counts[k - 1].vertices,
                 before[k - 1].normals + counts[k - 1].normals};
  // The joined positions and normals, whose sizes the counts give, are made (zeroed, on one thread)
  // while the other threads parse.
  PolygonMesh mesh;
  std::vector<glm::vec3> normals;
  auto makeJoined = [&] {
    mesh.positions.resize(before[pieces - 1].vertices + counts[pieces - 1].vertices);
    normals.resize(before[pieces - 1].normals + counts[pieces - 1].normals);
  };
  auto parseAll = [&] {
    parallelFor(pieces, threads, [&](size_t k) {
      try {
        parsed[k] = parsePiece(piece[k], path, 1 + before[k].lines, before[k].vertices, before[k].normals, counts[k]);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    });
  };
  withThreads(threads, [&] { parallelInvoke(threads > 1, makeJoined, parseAll); });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);  // the first in the file

  // The pieces joined in file order, each copied to its place on the threads.
  bool named = false;
  std::vector<size_t> faceBase(pieces + 1, 0), cornerBase(pieces + 1, 0), vertexBase(pieces + 1, 0),
      normalBase(pieces + 1, 0);
  for (size_t k = 0; k < pieces; k++) {
    named = named || parsed[k].named;
    faceBase[k + 1] = faceBase[k] + parsed[k].mesh.faceCount();
    cornerBase[k + 1] = cornerBase[k] + parsed[k].mesh.faceVertices.size();
    vertexBase[k + 1] = vertexBase[k] + parsed[k].mesh.positions.size();
    normalBase[k + 1] = normalBase[k] + parsed[k].normals.size();
  }
  if (cornerBase[pieces] > UINT32_MAX) throw InputError(path, "more than 4294967295 face corners");
  std::vector<int64_t> cornerNormal(named ? cornerBase[pieces] : 0);
  mesh.positions.resize(vertexBase[pieces]);  // as counted: a `v` record is a vertex or an error
  normals.resize(normalBase[pieces]);
  mesh.faceStart.resize(faceBase[pieces] + 1);
  mesh.faceVertices.resize(cornerBase[pieces]);
  parallelFor(pieces, threads, [&](size_t k) {
    ObjPiece& p = parsed[k];
    for (size_t f = 1; f < p.mesh.faceStart.size(); f++)
      mesh.faceStart[faceBase[k] + f] = uint32_t(cornerBase[k] + p.mesh.faceStart[f]);
    std::copy(p.mesh.faceVertices.begin(), p.mesh.faceVertices.end(), mesh.faceVertices.begin() + cornerBase[k]);
    std::copy(p.mesh.positions.begin(), p.mesh.positions.end(), mesh.positions.begin() + vertexBase[k]);
    std::copy(p.normals.begin(), p.normals.end(), normals.begin() + normalBase[k]);
    if (named && p.named)
      std::copy(p.cornerNormal.begin(), p.cornerNormal.end(), cornerNormal.begin() + cornerBase[k]);
    else if (named)
      std::fill(cornerNormal.begin() + cornerBase[k], cornerNormal.begin() + cornerBase[k + 1], -1);
    p = ObjPiece();
  });

  // Positive indices may point forward, so ranges are checked once every vertex is known: the first
  // face with a vertex index out of range is reported, else the first with a normal index out of range.
  size_t badVertex = SIZE_MAX, badNormal = SIZE_MAX;
  parallelForRanges(mesh.faceCount(), threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; f++)
      for (uint32_t c = mesh.faceStart[f]; c < mesh.faceStart[f + 1]; c++) {
        if (mesh.faceVertices[c] >= mesh.positions.size()) atomicMin(badVertex, f);
        if (named && cornerNormal[c] >= int64_t(normals.size())) atomicMin(badNormal, f);
      }
  });
  if (badVertex != SIZE_MAX)
    for (uint32_t c = mesh.faceStart[badVertex]; c < mesh.faceStart[badVertex + 1]; c++)
      if (mesh.faceVertices[c] >= mesh.positions.size())
        throw InputError(path, "line " + std::to_string(lineOfFace(data, path, badVertex)) + ": face index " +
                                   std::to_string(mesh.faceVertices[c] + 1) + " is out of range (" +
                                   std::to_string(mesh.positions.size()) + " vertices)");
  if (badNormal != SIZE_MAX)
    for (uint32_t c = mesh.faceStart[badNormal]; c < mesh.faceStart[badNormal + 1]; c++)
      if (cornerNormal[c] >= int64_t(normals.size()))
        throw InputError(path, "line " + std::to_string(lineOfFace(data, path, badNormal)) + ": normal index " +
                                   std::to_string(cornerNormal[c] + 1) + " is out of range (" +
                                   std::to_string(normals.size()) + " normals)");
  if (named) {
    mesh.cornerNormals.resize(mesh.faceVertices.size());
    parallelForRanges(mesh.faceVertices.size(), threads, [&](size_t begin, size_t end) {
      for (size_t c = begin; c < end; c++)  // zero: its face's normal
        mesh.cornerNormals[c] = cornerNormal[c] >= 0 ? normals[size_t(cornerNormal[c])] : glm::vec3(0.0f);
    });
  }
  return singleMeshScene(std::move(mesh));
}

}  // namespace vgeo

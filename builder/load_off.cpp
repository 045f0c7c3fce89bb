// load_off.cpp: Object File Format reader (OFF, COFF, NOFF headers; per-element colours after the
// indices are skipped). Polygons are kept.
// The format is a stream of numbers: a vertex is three of them wherever the lines break, a face its
// size and then as many indices, the rest of the face's last line skipped. Nearly every file writes
// one element a line, and then element k is on the k-th line that is neither blank nor a comment, so
// a large file is read in pieces of whole lines on several threads: a first pass counts each piece's
// element lines, the second parses each piece knowing which element it starts at. A file that breaks
// that form anywhere (two vertices on a line, a face over two lines, any error) is read again from
// the start by the one-thread reader, which gives every file, and every error, its meaning.
#include <algorithm>
#include <atomic>
#include <optional>

#include "../common/parallel.h"
#include "text_reader.h"

namespace vgeo {

namespace {

constexpr size_t kPiecewiseBytes = size_t(256) << 10;  // smaller files parse in about a millisecond on one thread
constexpr int kPieceBytesLog2 = 16;  // pieces of 64 KB or more: a piece costs a task, a few microseconds

struct OffHeader {
  int64_t vertices = 0, faces = 0;
  bool extras = false;  // values after a vertex's coordinates, to the end of its line
};

// The header, `in` left just after the edge count.
OffHeader readHeader(TextReader& in, size_t fileSize) {
  OffHeader h;
  in.skipWhitespaceAndComments();
  std::string_view header = in.token();
  if (header.size() < 3 || header.substr(header.size() - 3) != "OFF")
    in.fail("not an OFF file (first word is '" + std::string(header.substr(0, 16)) + "')");
  // [ST][C][N]OFF: texture coordinates, colours and normals follow a vertex's x y z (read as extras).
  // 4OFF and nOFF have other than three coordinates a vertex: refused, not misread.
  std::string_view prefix = header.substr(0, header.size() - 3);
  for (std::string_view part : {"ST", "C", "N"})
    if (prefix.substr(0, part.size()) == part) prefix.remove_prefix(part.size());
  if (!prefix.empty())
    in.fail("unsupported OFF variant '" + std::string(header.substr(0, 16)) +
            "' (4D or n-dimensional vertices; OFF, COFF, NOFF, STOFF are read)");
  h.extras = header.size() > 3;
  h.vertices = in.number<int64_t>("vertex count");
  h.faces = in.number<int64_t>("face count");
  in.number<int64_t>("edge count");
  if (h.vertices < 0 || h.faces < 0) in.fail("negative element count");
  if (h.vertices > int64_t(UINT32_MAX) || h.faces > int64_t(UINT32_MAX))
    in.fail("too many elements for 32-bit indices");
  // Each vertex takes at least 6 bytes ("0 0 0\n"): a count larger than the file can hold is an error,
  // not an allocation.
  if (uint64_t(h.vertices) * 6 > fileSize || uint64_t(h.faces) * 8 > fileSize)
    in.fail("truncated: the header promises " + std::to_string(h.vertices) + " vertices and " +
            std::to_string(h.faces) + " faces, more than the file holds");
  return h;
}

// The one-thread reader, from just after the counts.
PolygonMesh readElements(TextReader& in, const OffHeader& h) {
  PolygonMesh mesh;
  mesh.positions.resize(size_t(h.vertices));
  for (auto& p : mesh.positions) {
    for (int i = 0; i < 3; i++) p[i] = in.number<float>("vertex coordinate");
    if (h.extras) in.skipLine();  // extra per-vertex values
  }
  std::vector<uint32_t> corners;
  for (int64_t f = 0; f < h.faces; f++) {
    int64_t n = in.number<int64_t>("face size");
    if (n < 0 || n > 1 << 20) in.fail("bad face size " + std::to_string(n));
    corners.resize(size_t(n));
    for (auto& c : corners) {
      int64_t index = in.number<int64_t>("face index");
      if (index < 0 || index >= h.vertices)
        in.fail("face index " + std::to_string(index) + " is out of range (" + std::to_string(h.vertices) +
                " vertices)");
      c = uint32_t(index);
    }
    mesh.addFace(corners.data(), corners.size());
    in.skipLine();  // optional face colour
  }
  return mesh;
}

// Whether the line at the reader is an element's (neither blank nor a comment); skips it if not.
bool atElementLine(TextReader& in) {
  in.skipBlanks();
  if (!in.atLineEnd()) return true;
  in.skipLine();
  return false;
}

size_t countElementLines(std::string_view text) {
  TextReader in(text, std::string());
  size_t lines = 0;
  while (!in.atEnd())
    if (atElementLine(in)) lines++, in.skipLine();
  return lines;
}

// One piece's faces, in the order of their lines.
struct OffPieceFaces {
  std::vector<uint32_t> sizes, corners;
};

// Parses a piece whose first element line is element `first`, writing its vertices into `positions`;
// false where the piece leaves the one-element-a-line form or has anything the one-thread reader would
// call an error.
bool parsePiece(std::string_view text, const OffHeader& h, size_t first, std::vector<glm::vec3>& positions,
                OffPieceFaces& out) {
  TextReader in(text, std::string());
  const size_t vertices = size_t(h.vertices), elements = vertices + size_t(h.faces);
  for (size_t e = first; e < elements && !in.atEnd();) {
    if (!atElementLine(in)) continue;
    if (e < vertices) {
      glm::vec3& p = positions[e];
      for (int i = 0; i < 3; i++)
        if (!in.tryNumber(p[i])) return false;         // none at the line's end, a comment or the text's end
      if (!h.extras && !in.atLineEnd()) return false;  // the next vertex starts on this line
    } else {
      int64_t n = 0;
      if (!in.tryNumber(n) || n < 0 || n > 1 << 20) return false;
      out.sizes.push_back(uint32_t(n));
      for (int64_t k = 0; k < n; k++) {
        int64_t index = 0;
        if (!in.tryNumber(index) || index < 0 || index >= h.vertices) return false;
        out.corners.push_back(uint32_t(index));
      }
    }
    in.skipLine();  // a vertex's extra values, a face's colour
    e++;
  }
  return true;
}

// The elements of `body` (the lines after the counts') read on up to `threads` threads, or nothing
// where the file is not in the one-element-a-line form.
std::optional<PolygonMesh> readElementsByLines(std::string_view body, const OffHeader& h, int threads) {
  const std::vector<std::string_view> piece = linePieces(body, threads, kPieceBytesLog2);
  const size_t pieces = piece.size();
  std::vector<size_t> first(pieces + 1, 0);
  parallelFor(pieces, threads, [&](size_t k) { first[k + 1] = countElementLines(piece[k]); });
  for (size_t k = 0; k < pieces; k++) first[k + 1] += first[k];
  if (first[pieces] < size_t(h.vertices) + size_t(h.faces)) return std::nullopt;  // truncated, or not a line each

  PolygonMesh mesh;
  mesh.positions.resize(size_t(h.vertices));
  std::vector<OffPieceFaces> faces(pieces);
  std::atomic<bool> lineForm{true};
  parallelFor(pieces, threads, [&](size_t k) {
    if (!parsePiece(piece[k], h, first[k], mesh.positions, faces[k])) lineForm = false;
  });
  if (!lineForm) return std::nullopt;

  std::vector<size_t> faceBase(pieces + 1, 0), cornerBase(pieces + 1, 0);
  for (size_t k = 0; k < pieces; k++) {
    faceBase[k + 1] = faceBase[k] + faces[k].sizes.size();
    cornerBase[k + 1] = cornerBase[k] + faces[k].corners.size();
  }
  if (cornerBase[pieces] > UINT32_MAX) return std::nullopt;
  mesh.faceStart.resize(faceBase[pieces] + 1);
  mesh.faceVertices.resize(cornerBase[pieces]);
  parallelFor(pieces, threads, [&](size_t k) {
    uint32_t corner = uint32_t(cornerBase[k]);
    for (size_t f = 0; f < faces[k].sizes.size(); f++)
      mesh.faceStart[faceBase[k] + f + 1] = corner += faces[k].sizes[f];
    std::copy(faces[k].corners.begin(), faces[k].corners.end(), mesh.faceVertices.begin() + long(cornerBase[k]));
    faces[k] = OffPieceFaces();
  });
  return mesh;
}

}  // namespace

SourceScene loadOff(const std::string& path, int threads) {
  const FillLaterVector<char> data = readWholeFile(path, threads);
  const std::string_view text = withoutByteOrderMark(std::string_view(data.data(), data.size()));
  TextReader in(text, path);
  const OffHeader header = readHeader(in, data.size());
  if (threads > 1 && data.size() >= kPiecewiseBytes && in.atLineEnd()) {  // the elements on lines of their own
    TextReader body = in;
    body.skipLine();
    if (std::optional<PolygonMesh> mesh = readElementsByLines(text.substr(body.offset()), header, threads))
      return singleMeshScene(std::move(*mesh));
  }
  return singleMeshScene(readElements(in, header));
}

}  // namespace vgeo

#include "geometry/MeshIO.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>

namespace spacetree::geometry {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw MeshError(path + ": " + what);
}

std::string readWholeFile(const std::string& path) {
  // A directory opens as a stream on Linux and only fails inside the read, with a message
  // that does not name it: refuse it first.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    fail(path, "is a directory, not a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open mesh file (") + std::strerror(errno) + ")");
  std::string bytes;
  try {
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::exception& e) {
    fail(path, std::string("read error (") + e.what() + ")");
  }
  if (in.bad()) fail(path, "read error");
  if (bytes.empty()) fail(path, "empty mesh file");
  return bytes;
}

// Non-finite coordinates are refused where they are read: the vertex merger below orders
// points by value, which NaN would break (a NaN corner could be merged into a valid vertex).
void requireFinite(const std::string& path, const Eigen::Vector3d& p, const std::string& where) {
  if (p.allFinite()) return;
  std::ostringstream text;
  text.precision(17);
  text << where << ": non-finite vertex coordinate (" << p.x() << ", " << p.y() << ", " << p.z()
       << ")";
  fail(path, text.str());
}

std::string lowerExtension(const std::string& path) {
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Merges bitwise-identical points (STL stores every triangle's corners separately). Points
// must be finite (requireFinite): std::map needs a strict weak order, which NaN breaks.
class VertexMerger {
 public:
  explicit VertexMerger(TriangleMesh& mesh) : mesh_(mesh) {}
  int index(Eigen::Vector3d p) {
    for (int c = 0; c < 3; ++c)
      if (p[c] == 0.0) p[c] = 0.0;  // -0 and +0 are one point
    const std::array<double, 3> key{p.x(), p.y(), p.z()};
    const auto [it, inserted] = index_.emplace(key, int(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(p);
    return it->second;
  }

 private:
  TriangleMesh& mesh_;
  std::map<std::array<double, 3>, int> index_;
};

std::uint32_t littleEndian32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}

float littleEndianFloat(const unsigned char* p) {
  const std::uint32_t bits = littleEndian32(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

bool looksLikeBinaryStl(const std::string& bytes) {
  if (bytes.size() < 84) return false;
  const auto count = littleEndian32(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
  return bytes.size() == 84 + 50 * std::uint64_t(count);
}

TriangleMesh parseBinaryStl(const std::string& path, const std::string& bytes) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::uint32_t count = littleEndian32(data + 80);
  if (bytes.size() != 84 + 50 * std::uint64_t(count))
    fail(path, "binary STL truncated or too long: header announces " + std::to_string(count) +
                   " triangles (" + std::to_string(84 + 50 * std::uint64_t(count)) +
                   " bytes), file has " + std::to_string(bytes.size()) + " bytes");
  TriangleMesh mesh;
  VertexMerger merger(mesh);
  mesh.triangles.reserve(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const unsigned char* record = data + 84 + 50 * std::size_t(t) + 12;  // skip the normal
    std::array<int, 3> face;
    for (int v = 0; v < 3; ++v) {
      const Eigen::Vector3d p(littleEndianFloat(record + 12 * v),
                              littleEndianFloat(record + 12 * v + 4),
                              littleEndianFloat(record + 12 * v + 8));
      requireFinite(path, p, "triangle " + std::to_string(t) + " corner " + std::to_string(v));
      face[v] = merger.index(p);
    }
    mesh.triangles.push_back(face);
  }
  if (mesh.triangles.empty()) fail(path, "binary STL without triangles");
  return mesh;
}

// Whitespace tokenizer that knows the line of each token (for the error messages).
class Tokens {
 public:
  Tokens(const std::string& path, const std::string& text) : path_(path), text_(text) {}
  bool next(std::string& token) {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= text_.size()) return false;
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    token.assign(text_, begin, pos_ - begin);
    return true;
  }
  std::string expectAny(const char* what) {
    std::string token;
    if (!next(token)) fail(path_, std::string("unexpected end of file, expected ") + what);
    return token;
  }
  void expect(const char* keyword) {
    const std::string token = expectAny(keyword);
    if (token != keyword)
      fail(path_, "line " + std::to_string(line_) + ": expected '" + keyword + "', found '" +
                      token + "'");
  }
  double number() {
    const std::string token = expectAny("a number");
    return parseNumber(path_, token, line_);
  }
  int line() const { return line_; }

  static double parseNumber(const std::string& path, const std::string& token, int line) {
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0')
      fail(path, "line " + std::to_string(line) + ": malformed number '" + token + "'");
    return value;  // inf/nan parse; requireFinite rejects them with the line
  }

 private:
  const std::string& path_;
  const std::string& text_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

TriangleMesh parseAsciiStl(const std::string& path, const std::string& text) {
  Tokens tokens(path, text);
  tokens.expect("solid");
  TriangleMesh mesh;
  VertexMerger merger(mesh);
  std::string token;
  // The solid's name may have several words: skip to the first "facet" or "endsolid".
  while (tokens.next(token) && token != "facet" && token != "endsolid") {
  }
  while (token == "facet") {
    tokens.expect("normal");
    for (int c = 0; c < 3; ++c) tokens.number();
    tokens.expect("outer");
    tokens.expect("loop");
    std::array<int, 3> face;
    for (int v = 0; v < 3; ++v) {
      tokens.expect("vertex");
      Eigen::Vector3d p;
      for (int c = 0; c < 3; ++c) p[c] = tokens.number();
      requireFinite(path, p, "line " + std::to_string(tokens.line()));
      face[v] = merger.index(p);
    }
    const std::string after = tokens.expectAny("'endloop'");
    if (after != "endloop")
      fail(path, "line " + std::to_string(tokens.line()) +
                     ": expected 'endloop' (ASCII STL facets are triangles), found '" + after +
                     "'");
    tokens.expect("endfacet");
    mesh.triangles.push_back(face);
    if (!tokens.next(token)) fail(path, "unexpected end of file, expected 'endsolid'");
  }
  if (token != "endsolid")
    fail(path, "line " + std::to_string(tokens.line()) + ": expected 'facet' or 'endsolid', found '" +
                   token + "'");
  if (mesh.triangles.empty()) fail(path, "ASCII STL without facets");
  return mesh;
}

TriangleMesh parseObj(const std::string& path, const std::string& text) {
  TriangleMesh mesh;
  std::istringstream lines(text);
  std::string line;
  int lineNumber = 0;
  struct Face {
    std::vector<long> corners;
    int line;
  };
  std::vector<Face> faces;
  while (std::getline(lines, line)) {
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword)) continue;
    if (keyword == "v") {
      Eigen::Vector3d p;
      for (int c = 0; c < 3; ++c) {
        std::string token;
        if (!(words >> token))
          fail(path, "line " + std::to_string(lineNumber) + ": vertex needs three coordinates");
        p[c] = Tokens::parseNumber(path, token, lineNumber);
      }
      requireFinite(path, p, "line " + std::to_string(lineNumber));
      mesh.vertices.push_back(p);
    } else if (keyword == "f") {
      Face face{{}, lineNumber};
      std::string corner;
      while (words >> corner) {
        const std::string index = corner.substr(0, corner.find('/'));
        char* end = nullptr;
        const long value = std::strtol(index.c_str(), &end, 10);
        if (index.empty() || *end != '\0' || value == 0)
          fail(path, "line " + std::to_string(lineNumber) + ": malformed face corner '" + corner +
                         "'");
        // Negative indices count back from the vertices defined so far.
        face.corners.push_back(value > 0 ? value - 1 : long(mesh.vertices.size()) + value);
      }
      if (face.corners.size() < 3)
        fail(path, "line " + std::to_string(lineNumber) + ": face with " +
                       std::to_string(face.corners.size()) + " corners (need at least 3)");
      faces.push_back(std::move(face));
    }
  }
  for (const Face& face : faces) {
    for (long c : face.corners)
      if (c < 0 || c >= long(mesh.vertices.size()))
        fail(path, "line " + std::to_string(face.line) + ": face index " +
                       std::to_string(c + 1) + " out of range (file has " +
                       std::to_string(mesh.vertices.size()) + " vertices)");
    for (std::size_t k = 1; k + 1 < face.corners.size(); ++k)
      mesh.triangles.push_back(
          {int(face.corners[0]), int(face.corners[k]), int(face.corners[k + 1])});
  }
  if (mesh.triangles.empty()) fail(path, "OBJ file without faces");
  return mesh;
}

bool looksLikeAsciiStl(const std::string& bytes) {
  const auto start = bytes.find_first_not_of(" \t\r\n");
  return start != std::string::npos && bytes.compare(start, 5, "solid") == 0 &&
         bytes.find("facet") != std::string::npos;
}

TriangleMesh parseStl(const std::string& path, const std::string& bytes) {
  if (looksLikeBinaryStl(bytes)) return parseBinaryStl(path, bytes);
  const auto start = bytes.find_first_not_of(" \t\r\n");
  if (start != std::string::npos && bytes.compare(start, 5, "solid") == 0)
    return parseAsciiStl(path, bytes);
  if (bytes.size() >= 84) return parseBinaryStl(path, bytes);  // reports the size mismatch
  fail(path, "not an STL file (neither 'solid' nor a binary header of 84 bytes)");
}

std::ofstream openForWriting(const std::string& path, bool binary) {
  std::ofstream out(path, binary ? std::ios::binary : std::ios::out);
  if (!out) fail(path, std::string("cannot write mesh file (") + std::strerror(errno) + ")");
  out.precision(17);
  return out;
}

}  // namespace

TriangleMesh readStl(const std::string& path) { return parseStl(path, readWholeFile(path)); }

TriangleMesh readObj(const std::string& path) { return parseObj(path, readWholeFile(path)); }

TriangleMesh readMesh(const std::string& path) { return parseMesh(path, readWholeFile(path)); }

TriangleMesh parseMesh(const std::string& name, const std::string& bytes) {
  if (bytes.empty()) fail(name, "empty mesh file");
  const std::string ext = lowerExtension(name);
  if (ext == "stl") return parseStl(name, bytes);
  if (ext == "obj") return parseObj(name, bytes);
  if (looksLikeBinaryStl(bytes)) return parseBinaryStl(name, bytes);
  if (looksLikeAsciiStl(bytes)) return parseAsciiStl(name, bytes);
  return parseObj(name, bytes);
}

void writeStlAscii(const TriangleMesh& mesh, const std::string& path,
                   const std::string& solidName) {
  std::ofstream out = openForWriting(path, false);
  out << "solid " << solidName << "\n";
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Eigen::Vector3d n = mesh.areaVector(t).normalized();
    out << "  facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n    outer loop\n";
    for (int v = 0; v < 3; ++v) {
      const Eigen::Vector3d& p = mesh.vertices[mesh.triangles[t][v]];
      out << "      vertex " << p.x() << ' ' << p.y() << ' ' << p.z() << "\n";
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid " << solidName << "\n";
  if (!out) fail(path, "write error");
}

void writeStlBinary(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out = openForWriting(path, true);
  char header[80] = {};
  std::strncpy(header, "binary STL written by spacetree-dem", sizeof header - 1);
  out.write(header, sizeof header);
  const auto put32 = [&out](std::uint32_t v) {
    const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                                static_cast<unsigned char>(v >> 16),
                                static_cast<unsigned char>(v >> 24)};
    out.write(reinterpret_cast<const char*>(b), 4);
  };
  const auto putFloat = [&put32](double value) {
    const float f = float(value);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    put32(bits);
  };
  put32(std::uint32_t(mesh.triangleCount()));
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Eigen::Vector3d n = mesh.areaVector(t).normalized();
    for (int c = 0; c < 3; ++c) putFloat(n[c]);
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) putFloat(mesh.vertices[mesh.triangles[t][v]][c]);
    const char attribute[2] = {0, 0};
    out.write(attribute, 2);
  }
  if (!out) fail(path, "write error");
}

void writeObj(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out = openForWriting(path, false);
  out << "# written by spacetree-dem\n";
  for (const auto& v : mesh.vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << "\n";
  for (const auto& f : mesh.triangles)
    out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << "\n";
  if (!out) fail(path, "write error");
}

}  // namespace spacetree::geometry

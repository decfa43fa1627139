// Reading and writing triangle meshes: STL (ASCII and binary) and Wavefront OBJ.
//
// readMesh() picks the format from the extension (.stl / .obj, any case); a file with another
// extension is sniffed (binary STL by its size, "solid" + "facet" for ASCII STL, otherwise OBJ).
//   - STL: binary when the size is exactly 84 + 50 n bytes for the n triangles in the header
//     (so an ASCII file starting with "solid" is still recognised as binary when it is one);
//     otherwise ASCII (solid / facet normal / outer loop / vertex x3 / endloop / endfacet /
//     endsolid). The stored facet normals are ignored (orientation comes from the vertex order).
//     STL stores triangles as separate points: vertices with identical coordinates are merged
//     into one (bitwise equality after -0 -> +0; no tolerance, so no two distinct points are
//     ever glued together).
//   - OBJ: `v x y z [w]` and `f a b c ...` with the forms i, i/t, i//n, i/t/n and negative
//     (relative) indices; polygons with more than three corners are fan-triangulated from the
//     first corner; every other statement (vt, vn, o, g, s, usemtl, mtllib, l, p, comments) is
//     ignored.
// Every problem throws MeshError whose message starts with the file name and says what is
// wrong and where (line number or triangle index): missing/unreadable file, a directory, empty
// file, truncated binary STL, malformed number or keyword, non-finite coordinate (inf, nan, or
// a number beyond the double range), face index out of range, face with fewer than three
// corners, no triangles at all. Geometry checks (coordinate range, zero-area triangles, open or
// inconsistently oriented surfaces) are validateMesh()'s job (MeshValidation.h), which throws
// MeshError as well.
#pragma once

#include <stdexcept>
#include <string>

#include "geometry/TriangleMesh.h"

namespace spacetree::geometry {

class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

TriangleMesh readMesh(const std::string& path);
// readMesh() on bytes already in memory; `name` stands for the path (format from its extension,
// else sniffed) and starts every error message.
TriangleMesh parseMesh(const std::string& name, const std::string& bytes);
TriangleMesh readStl(const std::string& path);  // ASCII or binary, detected from the content
TriangleMesh readObj(const std::string& path);

// Writers (tests, tools, the template of a generated particle). Coordinates are written with
// 17 significant digits in the text formats, so a round trip is exact; binary STL stores
// floats. Throw MeshError when the file cannot be written.
void writeStlAscii(const TriangleMesh& mesh, const std::string& path,
                   const std::string& solidName = "mesh");
void writeStlBinary(const TriangleMesh& mesh, const std::string& path);
void writeObj(const TriangleMesh& mesh, const std::string& path);

}  // namespace spacetree::geometry

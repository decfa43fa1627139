// libFuzzer harness for the mesh readers and validation (MeshIO, MeshValidation) and the
// particle template built from an accepted mesh (RigidShape): what `fix trimesh/template ...
// file PATH` does with a user's file.
//
// Input: the first byte picks the name the bytes are read under, hence the format: 0 -> an
// .stl file, 1 -> an .obj file, anything else -> a file without extension (sniffed); the rest
// is the file. A MeshError (or std::invalid_argument from the shape) is a clean refusal. Any
// other exception, a crash, a sanitizer report, or an accepted mesh whose template is not
// finite and positive is a finding. Build and run: scripts/check.sh fuzz (clang, libFuzzer).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "geometry/MeshIO.h"
#include "geometry/MeshValidation.h"
#include "geometry/RigidShape.h"

namespace geo = spacetree::geometry;

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "mesh_reader_fuzzer: %s\n", what);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* names[] = {"fuzz.stl", "fuzz.obj", "fuzz"};
  const std::string name = names[data[0] < 2 ? data[0] : 2];
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);

  geo::TriangleMesh mesh;
  try {
    mesh = geo::parseMesh(name, bytes);
    geo::validateMesh(mesh, name);
  } catch (const geo::MeshError& e) {
    if (std::string(e.what()).rfind(name + ": ", 0) != 0) finding("MeshError without the file name");
    return 0;
  }

  // Accepted: the template must be usable (finite, positive mass properties and size).
  geo::RigidShape shape;
  try {
    shape = geo::RigidShape::fromMesh(mesh);
  } catch (const std::invalid_argument&) {
    finding("validateMesh accepted a mesh that RigidShape::fromMesh refuses");
  }
  if (!(shape.volume > 0.0) || !std::isfinite(shape.volume)) finding("volume not finite and > 0");
  if (!(shape.boundingRadius > 0.0) || !std::isfinite(shape.boundingRadius))
    finding("bounding radius not finite and > 0");
  if (!shape.principalInertiaPerUnitDensity.allFinite() ||
      !(shape.principalInertiaPerUnitDensity.minCoeff() >= 0.0))
    finding("principal moments not finite and >= 0");
  if (shape.triangleCount() != mesh.triangleCount()) finding("template lost triangles");
  return 0;
}

// Meshes a careless or hostile user may give: files with non-finite coordinates (which the STL
// vertex merger must never see: NaN breaks the ordering of its map, so a NaN corner used to be
// merged into a valid vertex and accepted), coordinates whose areas or volumes overflow or
// underflow, a directory instead of a file (each must end in a MeshError naming the file and
// the problem); generated spheres of absurd triangle counts (bounded, linear time).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include "mesh_file_fixture.h"

#include "geometry/DentedSphere.h"
#include "geometry/MeshIO.h"
#include "geometry/MeshValidation.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/SphereMesh.h"

using namespace spacetree::geometry;
using Eigen::Vector3d;

namespace {

class HostileMeshFiles : public MeshFileFixture {};

// readValidatedMesh(file) must throw a MeshError whose message holds the file and `what`.
void expectRejected(const std::string& file, const std::string& what) {
  try {
    readValidatedMesh(file);
    ADD_FAILURE() << file << " accepted; expected: " << what;
  } catch (const MeshError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

// The unit cube as ASCII STL, one line per token group; `corner` replaces the text of the
// `which`-th "vertex" line (counted from 0 over the whole file) when not empty.
std::string asciiCube(double scale, int which = -1, const std::string& corner = "") {
  TriangleMesh cube = boxMesh(Vector3d(1, 1, 1));
  std::ostringstream out;
  out.precision(17);
  out << "solid cube\n";
  int vertexLine = 0;
  for (std::size_t t = 0; t < cube.triangleCount(); ++t) {
    out << "facet normal 0 0 0\nouter loop\n";
    for (int v = 0; v < 3; ++v, ++vertexLine) {
      const Vector3d p = scale * cube.vertices[cube.triangles[t][v]];
      if (vertexLine == which)
        out << corner << "\n";
      else
        out << "vertex " << p.x() << ' ' << p.y() << ' ' << p.z() << "\n";
    }
    out << "endloop\nendfacet\n";
  }
  out << "endsolid cube\n";
  return out.str();
}

// Line number (1-based) of the `which`-th vertex line of asciiCube: "solid" line, then per
// facet two header lines, three vertices and two closing lines.
int asciiCubeVertexLine(int which) { return 1 + 7 * (which / 3) + 2 + which % 3 + 1; }

TEST_F(HostileMeshFiles, NanCornerInAsciiStlIsNamedNotMerged) {
  // Every corner in turn becomes (x, nan, z) with the x and z of its vertex: in a lexicographic
  // map it compares "equivalent" to a vertex with that x and z, so it used to be merged into
  // one (silently accepted when that was its own vertex, else a misleading "open surface").
  // It must be refused where it is read, with its line.
  const TriangleMesh cube = boxMesh(Vector3d(1, 1, 1));
  for (int which = 0; which < 36; ++which) {
    const Vector3d p = cube.vertices[cube.triangles[which / 3][which % 3]];
    std::ostringstream corner;
    corner << "vertex " << p.x() << " nan " << p.z();
    const std::string file =
        write("nan" + std::to_string(which) + ".stl", asciiCube(1.0, which, corner.str()));
    expectRejected(file, "line " + std::to_string(asciiCubeVertexLine(which)) +
                             ": non-finite vertex coordinate (");
  }
}

TEST_F(HostileMeshFiles, InfiniteAndOverflowingNumbersInAsciiStlAreNamed) {
  const std::string inf = write("inf.stl", asciiCube(1.0, 7, "vertex 1 inf 0"));
  expectRejected(inf, "line " + std::to_string(asciiCubeVertexLine(7)) + ": non-finite");
  const std::string huge = write("huge.stl", asciiCube(1.0, 0, "vertex 1e400 0 0"));
  expectRejected(huge, "line " + std::to_string(asciiCubeVertexLine(0)) + ": non-finite");
}

TEST_F(HostileMeshFiles, NanCornerInBinaryStlIsNamedNotMerged) {
  writeStlBinary(boxMesh(Vector3d(1, 1, 1)), path("cube.stl"));
  // Triangle 5, corner 2: its y coordinate becomes a quiet NaN (float bits 0x7fc00000).
  std::fstream file(path("cube.stl"), std::ios::in | std::ios::out | std::ios::binary);
  const unsigned char nan[4] = {0x00, 0x00, 0xc0, 0x7f};
  file.seekp(84 + 50 * 5 + 12 + 12 * 2 + 4);
  file.write(reinterpret_cast<const char*>(nan), 4);
  file.close();
  expectRejected(path("cube.stl"), "triangle 5 corner 2: non-finite vertex coordinate");
}

TEST_F(HostileMeshFiles, NanVertexInObjIsNamedWithItsLine) {
  const std::string file =
      write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 nan\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  expectRejected(file, "line 4: non-finite vertex coordinate");
}

TEST_F(HostileMeshFiles, CoordinatesWhoseVolumeOverflowsOrUnderflowsAreNamed) {
  // 1e200: areas and volumes are inf in double (was reported as "zero area (inf ...)").
  const std::string big = write("big.stl", asciiCube(1e200));
  expectRejected(big, "bounding-box diagonal 1.73205e+200 is outside [1e-50, 1e+50]");
  const std::string tiny = write("tiny.stl", asciiCube(1e-200));
  expectRejected(tiny, "bounding-box diagonal 1.73205e-200 is outside [1e-50, 1e+50]");
  const std::string above = write("above.stl", asciiCube(1e50));
  expectRejected(above, "bounding-box diagonal 1.73205e+50 is outside");
  // Inside the range near both ends: cubes of edge 5e49 and 1e-50 are valid meshes.
  EXPECT_NO_THROW(readValidatedMesh(write("large.stl", asciiCube(5e49))));
  EXPECT_NO_THROW(readValidatedMesh(write("small.stl", asciiCube(1e-50))));
}

TEST_F(HostileMeshFiles, SelfIntersectingSurfaceWithUnphysicalInertiaIsNamed) {
  // Found by tests/fuzz: the cube of quads with one corner moved from (0, 1, 0) to (5, 1, 0).
  // Its bottom quad becomes a bow-tie; the surface stays closed and consistently oriented with
  // a positive volume, but it crosses itself and its inertia is not a solid's (a negative
  // principal moment): the template would have turned the wrong way.
  const std::string bowTie = write("bowtie.obj",
                                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 5 1 0\nv 0 0 1\nv 1 0 1\n"
                                   "v 1 1 1\nv 0 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\n"
                                   "f 2 3 7 6\nf 4 8 7 3\nf 1 5 8 4\n");
  expectRejected(bowTie, "are not those of a solid");
  expectRejected(bowTie, "the surface intersects itself");
  // The same file with the corner where it belongs is the unit cube.
  const std::string cube = write("cube.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\n"
                                 "v 1 1 1\nv 0 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\n"
                                 "f 2 3 7 6\nf 4 8 7 3\nf 1 5 8 4\n");
  EXPECT_NO_THROW(readValidatedMesh(cube));
}

TEST_F(HostileMeshFiles, DirectoryGivenAsMeshIsNamed) {
  std::filesystem::create_directories(path("shapes.stl"));
  expectRejected(path("shapes.stl"), "is a directory, not a mesh file");
  std::filesystem::create_directories(path("shapes"));
  expectRejected(path("shapes"), "is a directory, not a mesh file");
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Generated spheres: bounded size, linear-time search, no integer overflow

namespace {

TEST(SphereMeshLimits, LargeCountsAreMetExactlyWithoutOverflow) {
  // 2 * slices * (stacks - 1) overflowed int from about 114 000 requested triangles on (UBSan);
  // the search was quadratic (63 s at 200 000, no end at 10^6).
  for (int triangles : {200000, kMaxSphereMeshTriangles}) {
    const TriangleMesh sphere = latitudeLongitudeSphereMeshWithAbout(triangles, 1.0);
    EXPECT_EQ(int(sphere.triangleCount()), triangles);
    EXPECT_EQ(sphere.vertexCount(), sphere.triangleCount() / 2 + 2);  // closed genus-0 surface
  }
  TriangleMesh sphere = latitudeLongitudeSphereMeshWithAbout(200000, 1.0);
  EXPECT_NO_THROW(validateMesh(sphere, "sphere"));
}

TEST(SphereMeshLimits, MoreThanTheLimitIsRefused) {
  EXPECT_THROW(latitudeLongitudeSphereMeshWithAbout(kMaxSphereMeshTriangles + 1, 1.0),
               std::invalid_argument);
  EXPECT_THROW(latitudeLongitudeSphereMeshWithAbout(2000000000, 1.0), std::invalid_argument);
  EXPECT_THROW(latitudeLongitudeSphereMesh(100000, 100000, 1.0), std::invalid_argument);
  DentedSphereOptions options;
  options.triangles = 2000000000;
  EXPECT_THROW(dentedSphere(options), std::invalid_argument);
  options.triangles = kMaxSphereMeshTriangles;
  EXPECT_EQ(int(dentedSphere(options).triangleCount()), kMaxSphereMeshTriangles);
}

}  // namespace

// Triangle meshes: STL (ASCII, binary) and OBJ reading and writing, validation (with its
// errors and documented repairs), the box/torus/sphere generators and the dented spheres.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
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

class MeshFiles : public MeshFileFixture {};

// A mesh with awkward coordinates: rotated, shifted, non-round numbers.
TriangleMesh awkwardBox() {
  TriangleMesh mesh = boxMesh(Vector3d(0.3, 1.7, 2.9));
  mesh.transform(Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix(),
                 Vector3d(1.0 / 3.0, -12.5, 1e3));
  return mesh;
}

// Error message must name the file and contain `what`.
template <class F>
void expectMeshError(F&& f, const std::string& file, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no MeshError for " << what;
  } catch (const MeshError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b, double tolerance) {
  ASSERT_EQ(a.vertexCount(), b.vertexCount());
  ASSERT_EQ(a.triangleCount(), b.triangleCount());
  for (std::size_t t = 0; t < a.triangleCount(); ++t)
    for (int v = 0; v < 3; ++v)
      EXPECT_LE((a.triangle(t)[v] - b.triangle(t)[v]).norm(), tolerance) << t << " " << v;
}

TEST_F(MeshFiles, AsciiStlRoundTripIsExactAndMergesVertices) {
  const TriangleMesh mesh = awkwardBox();
  writeStlAscii(mesh, path("box.stl"), "my box");
  const TriangleMesh read = readMesh(path("box.stl"));
  EXPECT_EQ(read.vertexCount(), 8u);  // 36 corners merged into 8 vertices
  expectSameMesh(mesh, read, 0.0);
  TriangleMesh copy = read;
  EXPECT_NO_THROW(validateMesh(copy, "box.stl"));
}

TEST_F(MeshFiles, BinaryStlRoundTripIsFloatExact) {
  const TriangleMesh mesh = latitudeLongitudeSphereMesh(7, 5, 0.37);
  writeStlBinary(mesh, path("sphere.STL"));
  EXPECT_EQ(std::filesystem::file_size(path("sphere.STL")), 84u + 50u * mesh.triangleCount());
  const TriangleMesh read = readMesh(path("sphere.STL"));
  EXPECT_EQ(read.vertexCount(), mesh.vertexCount());
  expectSameMesh(mesh, read, 1e-7);  // floats
  TriangleMesh copy = read;
  EXPECT_NO_THROW(validateMesh(copy, "sphere.STL"));
}

TEST_F(MeshFiles, BinaryStlWhoseHeaderStartsWithSolidIsStillBinary) {
  const TriangleMesh mesh = boxMesh(Vector3d(1, 2, 3));
  writeStlBinary(mesh, path("b.stl"));
  std::fstream f(path("b.stl"), std::ios::in | std::ios::out | std::ios::binary);
  f.write("solid trap", 10);
  f.close();
  const TriangleMesh read = readMesh(path("b.stl"));
  expectSameMesh(mesh, read, 0.0);
}

TEST_F(MeshFiles, ObjRoundTripIsExact) {
  const TriangleMesh mesh = awkwardBox();
  writeObj(mesh, path("box.obj"));
  expectSameMesh(mesh, readMesh(path("box.obj")), 0.0);
}

TEST_F(MeshFiles, ObjFormsPolygonsAndNegativeIndices) {
  // A unit cube as six quads, every corner form, a negative index, comments and ignored lines.
  const std::string file = write("cube.obj",
                                 "# cube\nmtllib none.mtl\no cube\n"
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                 "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1 1.0\n"
                                 "vt 0 0\nvn 0 0 1\ns off\n"
                                 "f 1 4 3 2\n"
                                 "f 5/1 6/1 7/1 8/1\n"
                                 "f 1//1 2//1 6//1 5//1\r\n"
                                 "f 2/1/1 3/1/1 7/1/1 6/1/1\n"
                                 "f 3 4 8 7 # trailing comment\n"
                                 "f -4 -1 -5 -8\n");
  TriangleMesh mesh = readMesh(file);
  EXPECT_EQ(mesh.vertexCount(), 8u);
  EXPECT_EQ(mesh.triangleCount(), 12u);  // six quads fan-triangulated
  const MeshValidationReport report = validateMesh(mesh, file);
  EXPECT_FALSE(report.flippedInwardOrientation);
  EXPECT_NEAR(signedVolume(mesh), 1.0, 1e-15);
}

TEST_F(MeshFiles, UnknownExtensionIsSniffed) {
  const TriangleMesh mesh = boxMesh(Vector3d(1, 2, 3));
  writeStlBinary(mesh, path("a.mesh"));
  writeStlAscii(mesh, path("b.txt"));
  writeObj(mesh, path("c"));
  for (const char* name : {"a.mesh", "b.txt", "c"}) expectSameMesh(mesh, readMesh(path(name)), 0.0);
}

TEST_F(MeshFiles, EachBadFileGivesItsMeshError) {
  const std::string missing = path("missing.stl");
  expectMeshError([&] { readMesh(missing); }, missing, "cannot open");
  const std::string empty = write("empty.obj", "");
  expectMeshError([&] { readMesh(empty); }, empty, "empty mesh file");

  // Binary STL announcing more triangles than it has.
  writeStlBinary(boxMesh(Vector3d(1, 1, 1)), path("cut.stl"));
  std::filesystem::resize_file(path("cut.stl"), 84 + 50 * 12 - 7);
  expectMeshError([&] { readMesh(path("cut.stl")); }, path("cut.stl"), "truncated");

  const std::string badNumber =
      write("n.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                     "vertex 1 0 zero\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n");
  expectMeshError([&] { readMesh(badNumber); }, badNumber, "line 5: malformed number 'zero'");
  const std::string quadFacet =
      write("q.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                     "vertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n");
  expectMeshError([&] { readMesh(quadFacet); }, quadFacet, "expected 'endloop'");
  const std::string unterminated =
      write("u.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                     "vertex 0 1 0\nendloop\nendfacet\n");
  expectMeshError([&] { readMesh(unterminated); }, unterminated, "end of file");
  const std::string noFacets = write("nf.stl", "solid x\nendsolid x\n");
  expectMeshError([&] { readMesh(noFacets); }, noFacets, "without facets");
  const std::string notStl = write("junk.stl", "hello world\n");
  expectMeshError([&] { readMesh(notStl); }, notStl, "not an STL file");

  const std::string outOfRange = write("r.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  expectMeshError([&] { readMesh(outOfRange); }, outOfRange, "line 4: face index 4 out of range");
  const std::string twoCorners = write("t.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  expectMeshError([&] { readMesh(twoCorners); }, twoCorners, "face with 2 corners");
  const std::string badCorner = write("c.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n");
  expectMeshError([&] { readMesh(badCorner); }, badCorner, "malformed face corner 'x'");
  const std::string shortVertex = write("v.obj", "v 0 0\n");
  expectMeshError([&] { readMesh(shortVertex); }, shortVertex, "three coordinates");
  const std::string noFaces = write("nf.obj", "v 0 0 0\n");
  expectMeshError([&] { readMesh(noFaces); }, noFaces, "without faces");
}

// ---------------------------------------------------------------------------------------------
// Validation

TEST(MeshValidation, RejectsNonFiniteCoordinates) {
  TriangleMesh mesh = boxMesh(Vector3d(1, 1, 1));
  mesh.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  expectMeshError([&] { validateMesh(mesh, "nan.stl"); }, "nan.stl",
                  "vertex 3 has a non-finite coordinate");
  mesh.vertices[3].y() = std::numeric_limits<double>::infinity();
  expectMeshError([&] { validateMesh(mesh, "inf.stl"); }, "inf.stl", "non-finite");
}

TEST(MeshValidation, RejectsZeroAreaTriangles) {
  TriangleMesh mesh = boxMesh(Vector3d(1, 1, 1));
  mesh.vertices.push_back(0.5 * (mesh.vertices[0] + mesh.vertices[1]));  // on an edge
  mesh.triangles.push_back({0, 1, 8});
  expectMeshError([&] { validateMesh(mesh, "flat.obj"); }, "flat.obj",
                  "triangle 12 has zero area");
  TriangleMesh repeated = boxMesh(Vector3d(1, 1, 1));
  repeated.triangles[5] = {2, 2, 7};
  expectMeshError([&] { validateMesh(repeated, "rep.obj"); }, "rep.obj", "triangle 5 has zero area");
}

TEST(MeshValidation, RejectsOpenAndNonManifoldSurfaces) {
  TriangleMesh open = boxMesh(Vector3d(1, 1, 1));
  open.triangles.pop_back();
  expectMeshError([&] { validateMesh(open, "open.stl"); }, "open.stl", "open surface");
  TriangleMesh doubled = boxMesh(Vector3d(1, 1, 1));
  doubled.triangles.push_back(doubled.triangles[0]);
  expectMeshError([&] { validateMesh(doubled, "nm.stl"); }, "nm.stl", "non-manifold");
  TriangleMesh badIndex = boxMesh(Vector3d(1, 1, 1));
  badIndex.triangles[2][1] = 8;
  expectMeshError([&] { validateMesh(badIndex, "i.stl"); }, "i.stl",
                  "triangle 2 refers to vertex 8");
}

TEST(MeshValidation, RejectsInconsistentOrientation) {
  TriangleMesh mesh = boxMesh(Vector3d(1, 2, 3));
  std::swap(mesh.triangles[4][1], mesh.triangles[4][2]);  // one triangle flipped
  expectMeshError([&] { validateMesh(mesh, "flip.stl"); }, "flip.stl", "inconsistent orientation");
}

TEST(MeshValidation, InwardCubeIsTurnedInsideOutOrRejected) {
  TriangleMesh inward = boxMesh(Vector3d(1, 2, 3));
  inward.flipOrientation();
  ASSERT_NEAR(signedVolume(inward), -6.0, 1e-14);
  TriangleMesh repaired = inward;
  const MeshValidationReport report = validateMesh(repaired, "in.stl");
  EXPECT_TRUE(report.flippedInwardOrientation);
  EXPECT_NEAR(report.signedVolumeBefore, -6.0, 1e-14);
  EXPECT_NEAR(signedVolume(repaired), 6.0, 1e-14);
  MeshValidationOptions strict;
  strict.repairInwardOrientation = false;
  expectMeshError([&] { validateMesh(inward, "in.stl", strict); }, "in.stl", "inward orientation");
}

TEST(MeshValidation, RemovesUnreferencedVertices) {
  TriangleMesh mesh = boxMesh(Vector3d(1, 1, 1));
  mesh.vertices.insert(mesh.vertices.begin(), Vector3d(1e9, 0, 0));  // unused, far away
  for (auto& f : mesh.triangles)
    for (int& v : f) ++v;
  const TriangleMesh before = mesh;
  const MeshValidationReport report = validateMesh(mesh, "u.obj");
  EXPECT_EQ(report.removedVertices, 1u);
  EXPECT_EQ(mesh.vertexCount(), 8u);
  expectSameMesh(mesh, boxMesh(Vector3d(1, 1, 1)), 0.0);
  (void)before;
}

TEST(MeshValidation, AcceptsTorusAndSeveralComponents) {
  TriangleMesh torus = torusMesh(2.0, 0.5, 24, 12);
  EXPECT_NO_THROW(validateMesh(torus, "torus"));
  // Euler characteristic V - E + F = 0 for genus 1.
  EXPECT_EQ(int(torus.vertexCount()) - 3 * int(torus.triangleCount()) / 2 +
                int(torus.triangleCount()),
            0);
  TriangleMesh two = boxMesh(Vector3d(1, 1, 1));
  TriangleMesh other = boxMesh(Vector3d(1, 1, 1));
  other.transform(Eigen::Matrix3d::Identity(), Vector3d(3, 0, 0));
  const int offset = int(two.vertexCount());
  for (const auto& v : other.vertices) two.vertices.push_back(v);
  for (auto f : other.triangles) two.triangles.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  EXPECT_NO_THROW(validateMesh(two, "two"));
  EXPECT_NEAR(signedVolume(two), 2.0, 1e-14);
}

TEST(MeshValidation, ReadValidatedMeshRepairsAnInwardFile) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("spacetree_mesh_test_rv_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  TriangleMesh inward = boxMesh(Vector3d(2, 2, 2));
  inward.flipOrientation();
  writeObj(inward, (dir / "in.obj").string());
  MeshValidationReport report;
  const TriangleMesh mesh = readValidatedMesh((dir / "in.obj").string(), {}, &report);
  EXPECT_TRUE(report.flippedInwardOrientation);
  EXPECT_NEAR(signedVolume(mesh), 8.0, 1e-14);
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Generators

TEST(SphereMesh, IndexedSphereIsClosedWithTheRequestedCounts) {
  for (int triangles : {12, 20, 40, 80, 160, 320, 640, 1000}) {
    TriangleMesh sphere = latitudeLongitudeSphereMeshWithAbout(triangles, 2.0);
    EXPECT_EQ(int(sphere.triangleCount()), triangles);
    EXPECT_NO_THROW(validateMesh(sphere, "sphere"));
    for (const auto& v : sphere.vertices) EXPECT_NEAR(v.norm(), 2.0, 1e-14);
    EXPECT_EQ(sphere.triangleSoup().size(), sphere.triangleCount());
  }
}

TEST(DentedSphere, IsClosedOutwardSeededAndDentedWithinTheAmplitude) {
  DentedSphereOptions options;
  options.triangles = 320;
  options.radius = 0.01;
  options.amplitude = 0.3;
  options.seed = 42;
  TriangleMesh mesh = dentedSphere(options);
  EXPECT_EQ(mesh.triangleCount(), 320u);
  const MeshValidationReport report = validateMesh(mesh, "dented");
  EXPECT_FALSE(report.flippedInwardOrientation);
  double smallest = 1e300, largest = 0.0;
  for (const auto& v : mesh.vertices) {
    smallest = std::min(smallest, v.norm());
    largest = std::max(largest, v.norm());
  }
  EXPECT_GE(smallest, 0.01 * 0.7 - 1e-15);
  EXPECT_LE(largest, 0.01 * 1.3 + 1e-15);
  // Really dented: the radii spread over most of the allowed band.
  EXPECT_LT(smallest, 0.01 * 0.75);
  EXPECT_GT(largest, 0.01 * 1.25);
  // Every tetrahedron (centre, triangle) keeps a positive volume (radial graph).
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const Triangle tri = mesh.triangle(t);
    EXPECT_GT(tri[0].dot(tri[1].cross(tri[2])), 0.0) << t;
  }
  // Same seed, same particle; another seed, another particle.
  const TriangleMesh again = dentedSphere(options);
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    EXPECT_EQ(mesh.vertices[v], again.vertices[v]);
  options.seed = 43;
  const TriangleMesh other = dentedSphere(options);
  EXPECT_NE(other.vertices[5], mesh.vertices[5]);
}

TEST(DentedSphere, RejectsBadOptions) {
  DentedSphereOptions options;
  options.amplitude = 1.0;
  EXPECT_THROW(dentedSphere(options), std::invalid_argument);
  options.amplitude = 0.1;
  options.triangles = 10;
  EXPECT_THROW(dentedSphere(options), std::invalid_argument);
  options.triangles = 20;
  options.radius = 0.0;
  EXPECT_THROW(dentedSphere(options), std::invalid_argument);
}

TEST(PrimitiveMeshes, BoxIsClosedOutwardWithTheRightVolume) {
  TriangleMesh box = boxMesh(Vector3d(1, 2, 3));
  EXPECT_EQ(box.triangleCount(), 12u);
  const MeshValidationReport report = validateMesh(box, "box");
  EXPECT_FALSE(report.flippedInwardOrientation);
  EXPECT_NEAR(signedVolume(box), 6.0, 1e-14);
  EXPECT_NEAR(box.surfaceArea(), 2 * (2 + 3 + 6), 1e-13);
  EXPECT_NEAR(box.minimumEdgeLength(), 1.0, 1e-15);
  EXPECT_THROW(boxMesh(Vector3d(1, 0, 1)), std::invalid_argument);
}

}  // namespace

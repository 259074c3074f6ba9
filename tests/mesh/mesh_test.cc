// Meshes (mesh/): structured rectangles and boxes (measure, orientation,
// conformity through the boundary, masses, node sets), and Gmsh: meshed
// shapes (measure within the discretisation error, orientation), .msh files in
// formats 2.2 and 4.1 with physical groups, and the errors for bad files.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/gmsh_mesh.h"
#include "mesh/mesh_boundary.h"
#include "mesh/simplex_mesh.h"
#include "mesh/structured_mesh.h"

namespace ipstep {
namespace {

void ExpectPositive(const SimplexMesh& mesh) {
  EXPECT_EQ(CheckMesh(mesh), "");
  for (int e = 0; e < mesh.num_elements(); ++e) ASSERT_GT(SignedMeasure(mesh, e), 0.0) << e;
}

TEST(StructuredMesh, RectangleCoversItsAreaWithPositiveTriangles) {
  const SimplexMesh mesh = StructuredRectangle({-1.0, 2.0}, {3.0, 0.5}, {6, 4});
  EXPECT_EQ(mesh.num_nodes(), 7 * 5);
  EXPECT_EQ(mesh.num_elements(), 2 * 6 * 4);
  ExpectPositive(mesh);
  EXPECT_NEAR(TotalMeasure(mesh), 1.5, 1e-14);
  // Conforming: interior edges are shared, the boundary is the perimeter.
  EXPECT_EQ(BoundaryFacets(mesh).size(), 2u * (6 + 4));
  EXPECT_EQ(mesh.node_sets.at("x_min").size(), 5u);
  for (int i : mesh.node_sets.at("y_max")) EXPECT_EQ(mesh.positions[2 * i + 1], 2.5);
  EXPECT_EQ(mesh.node_sets.at("boundary").size(), 2u * (6 + 4));
  double mass = 0.0;
  for (double m : LumpedMasses(mesh, 10.0)) mass += m;
  EXPECT_NEAR(mass, 15.0, 1e-12);
}

TEST(StructuredMesh, BoxIsAConformingTetrahedralisation) {
  const SimplexMesh mesh = StructuredBox({0.0, 0.0, 0.0}, {2.0, 1.0, 0.5}, {4, 3, 2});
  EXPECT_EQ(mesh.num_elements(), 6 * 4 * 3 * 2);
  ExpectPositive(mesh);
  EXPECT_NEAR(TotalMeasure(mesh), 1.0, 1e-14);
  // Each boundary square gives two triangles; a non-conforming split would
  // leave unmatched interior faces on the boundary list.
  EXPECT_EQ(BoundaryFacets(mesh).size(), 2u * 2 * (4 * 3 + 3 * 2 + 4 * 2));
  // Outward normals: the boundary's flux of x (the divergence theorem) is 3 V.
  double flux = 0.0;
  for (const auto& f : BoundaryFacets(mesh)) {
    const double* a = &mesh.positions[3 * f[0]];
    const double* b = &mesh.positions[3 * f[1]];
    const double* c = &mesh.positions[3 * f[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                         u[0] * v[1] - u[1] * v[0]};  // 2 x area x normal
    for (int k = 0; k < 3; ++k) flux += 0.5 * n[k] * (a[k] + b[k] + c[k]) / 3.0;
  }
  EXPECT_NEAR(flux, 3.0, 1e-12);
  EXPECT_EQ(mesh.node_sets.at("z_max").size(), 5u * 4);
}

TEST(CheckMesh, NamesTheBadElement) {
  SimplexMesh mesh = StructuredRectangle({0.0, 0.0}, {1.0, 1.0}, {2, 2});
  std::swap(mesh.elements[3][0], mesh.elements[3][1]);
  EXPECT_EQ(CheckMesh(mesh).rfind("element 3 is inverted", 0), 0u) << CheckMesh(mesh);
  EXPECT_EQ(OrientPositively(&mesh), 1);
  EXPECT_EQ(CheckMesh(mesh), "");
  mesh.elements[2][1] = 99;
  EXPECT_EQ(CheckMesh(mesh).rfind("element 2 refers to node 99", 0), 0u);
}

// An element listed twice made all its facets interior (seen twice): the
// body lost that part of its contact surface. Any order of its nodes repeats it.
TEST(CheckMesh, RejectsRepeatedElements) {
  SimplexMesh mesh = StructuredRectangle({0.0, 0.0}, {1.0, 1.0}, {1, 1});
  ASSERT_EQ(mesh.num_elements(), 2);
  const size_t facets = BoundaryFacets(mesh).size();
  std::array<int, 4> again = mesh.elements[0];
  std::swap(again[0], again[1]);
  std::swap(again[1], again[2]);  // a rotation: still positively oriented
  mesh.elements.push_back(again);
  EXPECT_LT(BoundaryFacets(mesh).size(), facets);  // what the check prevents
  EXPECT_EQ(CheckMesh(mesh), "element 2 repeats element 0 (the same nodes)");
  SimplexMesh box = StructuredBox({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {1, 1, 1});
  box.elements.push_back(box.elements[4]);
  EXPECT_EQ(CheckMesh(box), "element 6 repeats element 4 (the same nodes)");
}

// Uniform masses: equal, with the lumped total (the body's mass).
TEST(Masses, UniformMassesAreEqualWithTheLumpedTotal) {
  const SimplexMesh mesh = StructuredRectangle({0.0, 0.0}, {1.0, 1.0}, {4, 4});
  const std::vector<double> uniform = UniformMasses(mesh, 1000.0);
  const std::vector<double> lumped = LumpedMasses(mesh, 1000.0);
  ASSERT_EQ(uniform.size(), 25u);
  double total_uniform = 0.0, total_lumped = 0.0;
  for (size_t i = 0; i < uniform.size(); ++i) {
    EXPECT_DOUBLE_EQ(uniform[i], 40.0);  // the course code's section 6: 1000 kg / 25 nodes
    total_uniform += uniform[i];
    total_lumped += lumped[i];
  }
  EXPECT_NEAR(total_uniform, 1000.0, 1e-9);
  EXPECT_NEAR(total_lumped, 1000.0, 1e-9);
  EXPECT_NE(lumped.front(), lumped[12]);  // lumping is not uniform: corner vs centre
}

// A 3D tetrahedral file read by a 2D scene took its z = 0 triangles.
TEST(GmshFile, RejectsA3DMeshReadAs2D) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "ipstep_mesh_test_tet.msh").string();
  std::ofstream(path) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
                         "2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n2\n"
                         "1 2 2 1 1 1 2 3\n2 4 2 2 2 1 2 3 4\n$EndElements\n";
  try {
    GmshRead(path, 2);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("has 3D elements"), std::string::npos) << e.what();
  }
  EXPECT_EQ(GmshRead(path, 3).num_elements(), 1);
  std::filesystem::remove(path);
}

// Devices and NUL bytes: one error, no read.
TEST(GmshFile, RejectsDevicesAndNulBytes) {
  for (const std::string& path : {std::string("/dev/zero"), std::string("a.msh\0b", 7)}) {
    try {
      GmshRead(path, 2);
      ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("cannot read mesh file"), std::string::npos) << e.what();
    }
  }
}

TEST(Gmsh, DiskAndBallHaveTheirMeasureAndPositiveElements) {
  GmshShape disk;
  disk.dimension = 2;
  disk.name = "disk";
  disk.origin = {0.5, -1.0, 0.0};
  disk.radius = 0.5;
  disk.element_size = 0.05;
  const SimplexMesh d = GmshGenerate(disk);
  ExpectPositive(d);
  EXPECT_GT(d.num_elements(), 200);
  // Inscribed polygon: the area is short by O(h^2 / r^2).
  EXPECT_NEAR(TotalMeasure(d) / (M_PI * 0.25), 1.0, 0.01);
  for (int i : d.node_sets.at("boundary")) {
    EXPECT_NEAR(std::hypot(d.positions[2 * i] - 0.5, d.positions[2 * i + 1] + 1.0), 0.5, 1e-9);
  }

  GmshShape ball;
  ball.dimension = 3;
  ball.name = "ball";
  ball.radius = 1.0;
  ball.element_size = 0.25;
  const SimplexMesh b = GmshGenerate(ball);
  ExpectPositive(b);
  EXPECT_NEAR(TotalMeasure(b) / (4.0 / 3.0 * M_PI), 1.0, 0.05);
}

class GmshFile : public ::testing::TestWithParam<double> {};

TEST_P(GmshFile, ReadsWhatGmshWroteWithPhysicalGroups) {
  const auto dir = std::filesystem::temp_directory_path() / "ipstep_mesh_test";
  std::filesystem::create_directories(dir);
  for (int dim : {2, 3}) {
    GmshShape shape;
    shape.dimension = dim;
    shape.name = dim == 2 ? "rectangle" : "box";
    shape.origin = {1.0, 0.0, 0.0};
    shape.size = {2.0, 1.0, 0.5};
    shape.element_size = 0.2;
    const std::string path =
        (dir / ("shape" + std::to_string(dim) + "_" + std::to_string(GetParam()) + ".msh"))
            .string();
    GmshWriteShape(shape, path, GetParam());
    const SimplexMesh mesh = GmshRead(path, dim);
    ExpectPositive(mesh);
    EXPECT_NEAR(TotalMeasure(mesh), dim == 2 ? 2.0 : 1.0, 1e-12);
    ASSERT_TRUE(mesh.node_sets.count("x_min") && mesh.node_sets.count("x_max"));
    EXPECT_GE(mesh.node_sets.at("x_min").size(), 6u);
    for (int i : mesh.node_sets.at("x_min")) EXPECT_NEAR(mesh.positions[dim * i], 1.0, 1e-12);
    for (int i : mesh.node_sets.at("x_max")) EXPECT_NEAR(mesh.positions[dim * i], 3.0, 1e-12);
    EXPECT_EQ(mesh.node_sets.at("domain").size(), static_cast<size_t>(mesh.num_nodes()));
    // The wrong dimension: a 2D mesh has no tetrahedra.
    if (dim == 2) {
      try {
        GmshRead(path, 3);
        ADD_FAILURE() << "a 2D mesh read as 3D";
      } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("has no 3D elements"), std::string::npos) << e.what();
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Versions, GmshFile, ::testing::Values(2.2, 4.1));

std::string ReadError(const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / "ipstep_mesh_test_bad.msh";
  std::ofstream(path) << text;
  try {
    GmshRead(path.string(), 2);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(Gmsh, BadFilesGiveOneClearError) {
  EXPECT_NE(ReadError("").find("has no 2D elements"), std::string::npos) << ReadError("");
  // A 4-node quadrangle (MSH type 3): unsupported.
  const std::string quad =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n"
      "$EndNodes\n$Elements\n1\n1 3 2 0 1 1 2 3 4\n$EndElements\n";
  EXPECT_NE(ReadError(quad).find("only linear 3-node triangles"), std::string::npos)
      << ReadError(quad);
  // A quadrangle next to a triangle.
  const std::string mixed =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 1 1 0\n"
      "4 0 1 0\n5 2 0 0\n$EndNodes\n$Elements\n2\n1 3 2 0 1 1 2 3 4\n2 2 2 0 1 2 5 3\n"
      "$EndElements\n";
  // A 6-node (second-order) triangle, MSH type 9.
  const std::string quadratic =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
      "4 0.5 0 0\n5 0.5 0.5 0\n6 0 0.5 0\n$EndNodes\n$Elements\n1\n"
      "1 9 2 0 1 1 2 3 4 5 6\n$EndElements\n";
  EXPECT_NE(ReadError(quadratic).find("Triangle 6 elements (order 2): only linear"),
            std::string::npos)
      << ReadError(quadratic);
  EXPECT_NE(ReadError(mixed).find("mixes element types ("), std::string::npos) << ReadError(mixed);
  EXPECT_NE(ReadError("$MeshFormat\ngarbage").find("Gmsh could not read"), std::string::npos);
  EXPECT_NE(ReadError("hello world\n").find("Gmsh could not read"), std::string::npos);
  try {
    GmshRead("/nonexistent/file.msh", 2);
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open mesh file"), std::string::npos);
  }
}

}  // namespace
}  // namespace ipstep

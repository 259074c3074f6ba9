// What cannot be a body is rejected (problems/hard/reject/): the built ipstep
// program on each reject scene exits with 2 and one error line naming the
// scene file and the key (and index), never a crash, an abort, a hang or a
// run (issue 20, part 1).
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/run_program.h"

namespace {

namespace fs = std::filesystem;

struct RejectCase {
  const char* file;  // in problems/hard/reject/
  const char* key;   // the key path the error names
  const char* what;  // a piece of the reason
};

const RejectCase kCases[] = {
    {"repeated_triangle.json", "solid.mesh", "element 2 repeats element 0"},
    {"repeated_tetrahedron.json", "solid.mesh", "element 1 repeats element 0"},
    {"repeated_element_msh.json", "solid.mesh.file", "element 2 repeats element 0"},
    {"repeated_surface_edge.json", "surface.edges[3]", "repeats surface.edges[0]"},
    {"repeated_surface_triangle.json", "surface.triangles[1]", "repeats surface.triangles[0]"},
    {"dimension_mismatch.json", "solid.mesh.file", "has 3D elements"},
    {"mesh_dev_zero.json", "solid.mesh.file", "not a regular file"},
    {"mesh_nul_path.json", "solid.mesh.file", "NUL byte"},
    {"density_tiny.json", "solid.density", "must be in [1e-12, 1e12] kg"},
    {"too_many_nodes.json", "solid.mesh.cells", "1002001 nodes"},
    {"ball_tiny.json", "solid.mesh.radius", "must be in [1e-06"},
    {"masses_unknown.json", "solid.masses", "\"lumped\" or \"uniform\""},
};

class BodyInput : public ipstep::testing::ProgramTest {
 protected:
  void ExpectRejected(const std::string& scene, const std::string& key, const std::string& what) {
    const ipstep::testing::ProgramOutcome o =
        ipstep::testing::RunProgram(IPSTEP_BINARY, "--scene=" + scene + " --noprogress");
    EXPECT_EQ(o.exit_code, 2) << scene << "\n" << o.output;
    const std::string name = fs::path(scene).filename().string();
    EXPECT_NE(o.output.find(name + ": " + key + ": "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find(what), std::string::npos) << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  }
};

TEST_F(BodyInput, EveryRejectSceneExitsTwoNamingFileAndKey) {
  const fs::path folder = fs::path(IPSTEP_SOURCE_DIR) / "problems" / "hard" / "reject";
  for (const RejectCase& c : kCases) {
    SCOPED_TRACE(c.file);
    ExpectRejected((folder / c.file).string(), c.key, c.what);
  }
}

// A named pipe as the mesh file hung (Gmsh waited for a writer).
TEST_F(BodyInput, NamedPipeMeshIsNotARegularFile) {
  const std::string pipe = (dir_ / "mesh.msh").string();
  ASSERT_EQ(mkfifo(pipe.c_str(), 0600), 0);
  const std::string scene = Write("pipe.json", R"({
  "dimension": 2, "effects": ["elasticity"],
  "solid": {"mesh": {"file": "mesh.msh"}, "youngs_modulus": 1e5, "poisson_ratio": 0.3,
            "density": 1000}
})");
  ExpectRejected(scene, "solid.mesh.file", "not a regular file");
}

// The documented limit of 10^6 nodes holds for solids too: 999 x 1000 cells
// are 1,001,000 nodes.
TEST_F(BodyInput, NodeLimitIsTheDocumentedOne) {
  const auto grid = [&](int ny) {
    return Write("grid.json", R"({
  "dimension": 2, "steps": 0, "effects": ["elasticity"],
  "solid": {"mesh": {"shape": "rectangle", "size": [1, 1], "cells": [999, )" +
                                  std::to_string(ny) + R"(]},
            "youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000}
})");
  };
  ExpectRejected(grid(1000), "solid.mesh.cells", "1001000 nodes");  // 1000 x 1001
}

}  // namespace

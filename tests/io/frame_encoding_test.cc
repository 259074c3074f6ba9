// The frames' encodings and a 3D solid's frames (io/frame_writer.h,
// io/vtk_unstructured_grid.h, io/element_fields.h, io/pvd_series.h): ASCII,
// raw and zlib hold the same numbers; Float32 frames agree with Float64 ones
// to float's precision; raw's appended data is laid out as VTK
// reads it; a 3D solid is written as tetrahedra with its per-element fields
// and its boundary as part 2; the per-element fields are exact on a uniform
// stretch; times are printed in their shortest round-trip form.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "energies/effect_registry.h"
#include "io/element_fields.h"
#include "io/frame_writer.h"
#include "io/pvd_series.h"
#include "io/surface_triangles.h"
#include "io/vtk_unstructured_grid.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"
#include "tests/support/run_program.h"
#include "tests/support/vtu_arrays.h"

namespace {

namespace fs = std::filesystem;
using ipstep::VtkEncoding;
using ipstep::VtkPrecision;
using ipstep::testing::VtuArrays;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class FrameEncoding : public ipstep::testing::ProgramTest {
 protected:
  // Writes frames 0..steps of `scene` to Dir(encoding, precision).
  void Run(const std::string& name, int steps, VtkEncoding encoding,
           VtkPrecision precision = VtkPrecision::kFloat64) {
    ipstep::SceneLoadOptions load;
    load.extra_effects = ipstep::DefaultEffects().UserNames();
    scene_ = ipstep::LoadScene(name, load);
    ipstep::SimulationOptions options;
    options.steps = steps;
    ipstep::Simulation sim(scene_, options);
    ipstep::FrameWriter frames(Dir(encoding, precision).string(), sim, "frames", encoding,
                               precision);
    frames.Write(0);
    for (int step = 1; step <= steps; ++step) {
      ASSERT_TRUE(sim.Step().converged);
      frames.Write(step);
    }
    x_ = sim.state().x;
  }
  // DIR/<encoding name>, DIR/<encoding name>_float32 for Float32.
  fs::path Dir(VtkEncoding encoding, VtkPrecision precision = VtkPrecision::kFloat64) const {
    return dir_ / (std::string(ipstep::VtkEncodingName(encoding)) +
                   (precision == VtkPrecision::kFloat32 ? "_float32" : ""));
  }

  ipstep::Scene scene_;
  Eigen::VectorXd x_;
};

const char* const kArrays[] = {
    "",  // the points
    "velocity", "contact_force", "kind", "J", "energy_density", "von_mises_stress", "connectivity",
    "offsets",  "types"};

// The same run written three ways: every array of every file has the same
// numbers (ASCII's shortest round-trip text reads back to the same doubles).
TEST_F(FrameEncoding, AsciiRawAndZlibHoldTheSameNumbers) {
  for (VtkEncoding e : {VtkEncoding::kAscii, VtkEncoding::kRaw, VtkEncoding::kZlib}) {
    Run("ball_drop_3d", 2, e);
  }
  for (const char* file : {"frame_00002.vtu", "surface_00002.vtu", "obstacles.vtu"}) {
    const VtuArrays ascii(ReadFile(Dir(VtkEncoding::kAscii) / file));
    const VtuArrays raw(ReadFile(Dir(VtkEncoding::kRaw) / file));
    const VtuArrays zlib(ReadFile(Dir(VtkEncoding::kZlib) / file));
    for (const char* name : kArrays) {
      const std::vector<double> values = ascii.Values(name);
      EXPECT_EQ(raw.Values(name), values) << file << " " << name;
      EXPECT_EQ(zlib.Values(name), values) << file << " " << name;
    }
    EXPECT_FALSE(ascii.Values("").empty()) << file;
  }
  EXPECT_EQ(ReadFile(Dir(VtkEncoding::kAscii) / "run.pvd"),
            ReadFile(Dir(VtkEncoding::kZlib) / "run.pvd"));
}

// Float32 (the app's default): the points and fields are Float32 arrays whose
// values are the Float64 ones rounded to float (within 1e-6 of each array's
// largest value); ASCII Float32 text reads back to the same floats as zlib's.
TEST_F(FrameEncoding, Float32FramesAreFloat64RoundedToFloat) {
  Run("ball_drop_3d", 2, VtkEncoding::kZlib);
  Run("ball_drop_3d", 2, VtkEncoding::kZlib, VtkPrecision::kFloat32);
  Run("ball_drop_3d", 2, VtkEncoding::kAscii, VtkPrecision::kFloat32);
  for (const char* file : {"frame_00002.vtu", "surface_00002.vtu"}) {
    const std::string text = ReadFile(Dir(VtkEncoding::kZlib, VtkPrecision::kFloat32) / file);
    EXPECT_EQ(text.find("Float64"), std::string::npos) << file;
    EXPECT_NE(text.find("<DataArray type=\"Float32\" Name=\"J\""), std::string::npos) << file;
    const VtuArrays exact(ReadFile(Dir(VtkEncoding::kZlib) / file));
    const VtuArrays zlib(text);
    const VtuArrays ascii(ReadFile(Dir(VtkEncoding::kAscii, VtkPrecision::kFloat32) / file));
    for (const char* name : kArrays) {
      const std::vector<double> e = exact.Values(name), z = zlib.Values(name),
                                a = ascii.Values(name);
      ASSERT_EQ(z.size(), e.size()) << file << " " << name;
      ASSERT_EQ(a.size(), e.size()) << file << " " << name;
      double largest = 0.0;
      for (double v : e) largest = std::max(largest, std::abs(v));
      for (size_t i = 0; i < e.size(); ++i) {
        EXPECT_EQ(z[i], static_cast<double>(static_cast<float>(e[i]))) << file << " " << name;
        EXPECT_LE(std::abs(z[i] - e[i]), 1e-6 * largest) << file << " " << name;
        EXPECT_EQ(static_cast<float>(a[i]), static_cast<float>(z[i])) << file << " " << name;
      }
    }
  }
}

// Raw appended data: after '_', per array in the order of the offsets, a
// UInt64 byte count (the values' count times their size) and the bytes; the
// next array starts right after.
TEST_F(FrameEncoding, RawAppendedDataIsCountThenBytes) {
  Run("twisted_bar_3d", 1, VtkEncoding::kRaw);
  const std::string vtu = ReadFile(Dir(VtkEncoding::kRaw) / "frame_00001.vtu");
  ASSERT_NE(vtu.find("<AppendedData encoding=\"raw\">\n_"), std::string::npos);
  EXPECT_EQ(vtu.find("compressor"), std::string::npos);
  const VtuArrays arrays(vtu);
  const std::regex array("type=\"(\\w+)\"[^>]*format=\"appended\" offset=\"(\\d+)\"");
  size_t expected_offset = 0, arrays_seen = 0;
  for (auto m = std::sregex_iterator(vtu.begin(), vtu.begin() + vtu.find("<AppendedData"), array);
       m != std::sregex_iterator(); ++m, ++arrays_seen) {
    const size_t offset = std::stoul((*m)[2]);
    EXPECT_EQ(offset, expected_offset) << (*m)[0];
    const size_t size = (*m)[1] == "Float64"                         ? 8
                        : (*m)[1] == "Int32" || (*m)[1] == "Float32" ? 4
                                                                     : 1;
    const std::uint64_t bytes = arrays.Header(offset);
    EXPECT_EQ(bytes % size, 0u);
    expected_offset = offset + 8 + bytes;
  }
  EXPECT_EQ(arrays_seen, 9u);  // velocity, kind, 3 fields, points, 3 cell arrays
  const size_t data = vtu.find('_', vtu.find("<AppendedData")) + 1;
  EXPECT_EQ(vtu.substr(data + expected_offset), "\n</AppendedData>\n</VTKFile>\n");
  const int n = scene_.num_nodes(), elements = scene_.solid->mesh.num_elements();
  EXPECT_EQ(arrays.Values("").size(), 3u * n);
  EXPECT_EQ(arrays.Values("velocity").size(), 3u * n);
  EXPECT_EQ(arrays.Values("connectivity").size(), 4u * elements);
}

// A 3D solid: tetrahedra (type 10) with the solid's elements in order, the
// per-element fields of its state; part 2 its boundary triangles with the
// fields of the elements they bound.
TEST_F(FrameEncoding, SolidIsTetrahedraWithFieldsAndSurface) {
  Run("twisted_bar_3d", 3, VtkEncoding::kZlib);
  const VtuArrays body(ReadFile(Dir(VtkEncoding::kZlib) / "frame_00003.vtu"));
  const ipstep::SimplexMesh& mesh = scene_.solid->mesh;
  const std::vector<double> types = body.Values("types"),
                            connectivity = body.Values("connectivity");
  ASSERT_EQ(types.size(), static_cast<size_t>(mesh.num_elements()));
  for (int e = 0; e < mesh.num_elements(); ++e) {
    EXPECT_EQ(types[e], 10.0);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(connectivity[4 * e + k], mesh.elements[e][k]);
  }
  const ipstep::ElementFields fields = ipstep::SolidElementFields(*scene_.solid, x_);
  EXPECT_EQ(body.Values("J"), fields.J);
  EXPECT_EQ(body.Values("energy_density"), fields.energy_density);
  EXPECT_EQ(body.Values("von_mises_stress"), fields.von_mises_stress);
  double largest = 0.0;
  for (double s : fields.von_mises_stress) largest = std::max(largest, s);
  EXPECT_GT(largest, 0.0);  // twisted: stressed
  const VtuArrays surface(ReadFile(Dir(VtkEncoding::kZlib) / "surface_00003.vtu"));
  const size_t triangles = ipstep::SurfaceTriangles(scene_).size();
  EXPECT_EQ(triangles, 2u * (2 * 20 * 2 + 2 * 20 * 2 + 2 * 2 * 2));  // the box's cell faces
  EXPECT_EQ(surface.Values("types"), std::vector<double>(triangles, 5.0));
  EXPECT_EQ(surface.Values("J").size(), triangles);
  const std::string pvd = ReadFile(Dir(VtkEncoding::kZlib) / "run.pvd");
  EXPECT_NE(pvd.find("part=\"2\" name=\"surface\" file=\"surface_00003.vtu\""), std::string::npos);
}

ipstep::Solid OneTetrahedron(ipstep::ElasticModel model) {
  ipstep::Solid solid;
  solid.mesh.dimension = 3;
  solid.mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  solid.mesh.elements = {{0, 1, 2, 3}};
  solid.material.model = model;
  return solid;
}

// F = diag(a, 1, 1): J = a; neo-Hookean Psi = mu/2 (a^2 - 1) - mu ln a +
// lambda/2 ln^2 a, Cauchy stress (mu (F F^T - I) + lambda ln J I) / J, whose
// deviator gives von Mises |s_xx - s_yy| = mu (a^2 - 1) / a; linear:
// 2 mu |a - 1|. A rotation: J = 1, no energy, no stress.
TEST(ElementFields, ExactOnAUniformStretchAndARotation) {
  const double a = 1.3;
  for (ipstep::ElasticModel model :
       {ipstep::ElasticModel::kNeoHookean, ipstep::ElasticModel::kLinear}) {
    const ipstep::Solid solid = OneTetrahedron(model);
    const double mu = solid.material.mu(), lambda = solid.material.lambda(3);
    Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(solid.mesh.positions.data(), 12);
    for (int node = 0; node < 4; ++node) x[3 * node] *= a;
    const ipstep::ElementFields f = ipstep::SolidElementFields(solid, x);
    EXPECT_NEAR(f.J[0], a, 1e-15);
    if (model == ipstep::ElasticModel::kNeoHookean) {
      const double l = std::log(a);
      EXPECT_NEAR(f.energy_density[0], 0.5 * mu * (a * a - 1) - mu * l + 0.5 * lambda * l * l,
                  1e-12 * mu);
      EXPECT_NEAR(f.von_mises_stress[0], mu * (a * a - 1) / a, 1e-12 * mu);
    } else {
      EXPECT_NEAR(f.energy_density[0], mu * (a - 1) * (a - 1) + 0.5 * lambda * (a - 1) * (a - 1),
                  1e-12 * mu);
      EXPECT_NEAR(f.von_mises_stress[0], 2 * mu * (a - 1), 1e-12 * mu);
    }
  }
  const ipstep::Solid solid = OneTetrahedron(ipstep::ElasticModel::kNeoHookean);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  Eigen::VectorXd x(12);
  for (int node = 0; node < 4; ++node) {
    x.segment<3>(3 * node) = R * Eigen::Vector3d::Map(solid.mesh.positions.data() + 3 * node);
  }
  const ipstep::ElementFields f = ipstep::SolidElementFields(solid, x);
  EXPECT_NEAR(f.J[0], 1.0, 1e-15);
  EXPECT_NEAR(f.energy_density[0], 0.0, 1e-10 * solid.material.mu());
  EXPECT_NEAR(f.von_mises_stress[0], 0.0, 1e-10 * solid.material.mu());
}

// 2D, F = diag(a, 1): the in-plane Cauchy stress s_xx = (mu (a^2 - 1) +
// lambda ln a) / a, s_yy = lambda ln a / a, von Mises with s_zz = 0.
TEST(ElementFields, TwoDimensionalStretch) {
  ipstep::Solid solid;
  solid.mesh.dimension = 2;
  solid.mesh.positions = {0, 0, 1, 0, 0, 1};
  solid.mesh.elements = {{0, 1, 2, 0}};
  const double a = 0.8, mu = solid.material.mu(), lambda = solid.material.lambda(2);
  Eigen::VectorXd x(6);
  x << 0, 0, a, 0, 0, 1;
  const ipstep::ElementFields f = ipstep::SolidElementFields(solid, x);
  const double sxx = (mu * (a * a - 1) + lambda * std::log(a)) / a, syy = lambda * std::log(a) / a;
  EXPECT_NEAR(f.J[0], a, 1e-15);
  EXPECT_NEAR(f.von_mises_stress[0], std::sqrt(sxx * sxx - sxx * syy + syy * syy), 1e-12 * mu);
}

// An inverted element: J < 0, no energy or stress (NaN, written as 0).
TEST(ElementFields, InvertedElementHasNoEnergy) {
  const ipstep::Solid solid = OneTetrahedron(ipstep::ElasticModel::kNeoHookean);
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(solid.mesh.positions.data(), 12);
  x[9 + 2] = -1.0;  // node 3 through the base
  const ipstep::ElementFields f = ipstep::SolidElementFields(solid, x);
  EXPECT_NEAR(f.J[0], -1.0, 1e-15);
  EXPECT_TRUE(std::isnan(f.energy_density[0]));
  EXPECT_TRUE(std::isnan(f.von_mises_stress[0]));
}

// Times: the shortest text that reads back as the same double.
TEST_F(FrameEncoding, TimesAreShortestRoundTrip) {
  {
    ipstep::PvdSeries series((dir_ / "run.pvd").string(), "frames");
    series.Add(0.98, 0, "body", "a.vtu");
    series.Add(0.1 + 0.2, 0, "body", "b.vtu");
    series.Add(49 * 0.02, 0, "body", "c.vtu");
  }
  const std::string pvd = ReadFile(dir_ / "run.pvd");
  EXPECT_NE(pvd.find("timestep=\"0.98\" group=\"\" part=\"0\" name=\"body\" file=\"a.vtu\""),
            std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"0.30000000000000004\""), std::string::npos);
  std::smatch m;
  const std::string c = pvd.substr(pvd.find("timestep", pvd.find("b.vtu")));
  ASSERT_TRUE(std::regex_search(c, m, std::regex("timestep=\"([^\"]*)\"")));
  EXPECT_EQ(std::stod(m[1]), 49 * 0.02);
}

}  // namespace

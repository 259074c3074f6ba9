// The ipstep program with contact: bad contact parameters and flags give one
// error line and exit code 2; contact scenes run and report min_distance and
// active_contacts in the --stats CSV.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/run_program.h"

namespace {

namespace fs = std::filesystem;

using Outcome = ipstep::testing::ProgramOutcome;

Outcome RunIpstep(const std::string& arguments) {
  return ipstep::testing::RunProgram(IPSTEP_BINARY, arguments);
}

class ContactProgram : public ipstep::testing::ProgramTest {
 protected:
  void ExpectInputError(const std::string& arguments, const std::string& key) {
    const Outcome o = RunIpstep(arguments);
    EXPECT_EQ(o.exit_code, 2) << arguments << "\n" << o.output;
    EXPECT_NE(o.output.find(key), std::string::npos) << arguments << "\n" << o.output;
    EXPECT_EQ(o.output.find("Check failed"), std::string::npos) << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  }
};

std::string Particle(const std::string& contact, const std::string& friction = "") {
  return R"({"dimension": 2, "effects": ["gravity", "contact")" +
         std::string(friction.empty() ? "" : R"(, "friction")") +
         R"(], "gravity": [0, -9.81], "particle": {"position": [0, 0.5], "mass": 1},
             "contact": )" +
         contact + (friction.empty() ? "" : R"(, "friction": )" + friction) + "}";
}

const char* kGround = R"("obstacles": [{"type": "plane", "point": [0, 0], "normal": [0, 1]}])";

TEST_F(ContactProgram, BadContactParametersExitWithCode2) {
  ExpectInputError(
      "--scene=" + Write("a.json", Particle(std::string("{\"dhat\": 0, ") + kGround + "}")),
      "contact.dhat");
  ExpectInputError(
      "--scene=" + Write("b.json", Particle(std::string("{\"dhat\": -1, ") + kGround + "}")),
      "contact.dhat");
  ExpectInputError(
      "--scene=" + Write("c.json", Particle(std::string("{\"kappa\": -5, ") + kGround + "}")),
      "contact.kappa");
  ExpectInputError(
      "--scene=" + Write("d.json", Particle(std::string("{") + kGround + "}", R"({"mu": -0.5})")),
      "friction.mu");
  ExpectInputError(
      "--scene=" +
          Write(
              "e.json",
              Particle(R"({"obstacles": [{"type": "plane", "point": [0, 1], "normal": [0, 1]}]})")),
      "not free of contact");
  // Finite but overflowing contact parameters (core/input_limits.h).
  const auto bad = [&](const std::string& name, const std::string& contact,
                       const std::string& friction, const std::string& key) {
    ExpectInputError("--scene=" + Write(name, Particle(contact, friction)), key);
  };
  const std::string plane = R"({"type": "plane", "point": [0, 0], "normal": [0, 1]})";
  bad("k1.json", "{\"kappa\": 1e300, \"obstacles\": [" + plane + "]}", "", "contact.kappa");
  bad("d1.json", "{\"dhat\": 1e-300, \"obstacles\": [" + plane + "]}", "", "contact.dhat");
  bad("p1.json", R"({"obstacles": [{"type": "plane", "point": [0, -1e300], "normal": [0, 1]}]})",
      "", "contact.obstacles[0].point[1]");
  bad("r1.json", R"({"obstacles": [{"type": "circle", "center": [0, -2], "radius": 1e300}]})", "",
      "contact.obstacles[0].radius");
  bad("v1.json",
      "{\"obstacles\": [{\"type\": \"plane\", \"point\": [0, 0], \"normal\": [0, 1], "
      "\"velocity\": [1e300, 0]}]}",
      "", "contact.obstacles[0].velocity[0]");
  bad("b1.json", R"({"obstacles": [{"type": "box", "min": [-1e300, -2], "max": [1, -1]}]})", "",
      "contact.obstacles[0].min[0]");
  bad("m1.json", "{\"obstacles\": [" + plane + "]}", R"({"mu": 1e300})", "friction.mu");
  bad("e1.json", "{\"obstacles\": [" + plane + "]}", R"({"mu": 0.3, "epsilon_v": 1e-300})",
      "friction.epsilon_v");
  const std::string good = Write("good.json", Particle(std::string("{") + kGround + "}"));
  ExpectInputError("--scene=" + good + " --contact_dhat=-1", "--contact_dhat");
  ExpectInputError("--scene=" + good + " --contact_kappa=0", "--contact_kappa");
  ExpectInputError("--scene=" + good + " --friction_mu=-1", "--friction_mu");
  ExpectInputError("--scene=" + good + " --friction_iterations=0", "--friction_iterations");
  ExpectInputError("--scene=" + good + " --contact_kappa=1e300", "--contact_kappa");
  ExpectInputError("--scene=" + good + " --contact_dhat=1e-300", "--contact_dhat");
}

TEST_F(ContactProgram, ContactSceneWritesContactColumns) {
  const std::string stats = (dir_ / "drop.csv").string();
  const Outcome o =
      RunIpstep("--scene=drop --steps=35 --contact_kappa=2e5 --contact_dhat=0.02 --stats=" + stats);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("d_hat 0.02, kappa 200000"), std::string::npos) << o.output;
  std::ifstream in(stats);
  std::string header, line, last;
  std::getline(in, header);
  EXPECT_NE(header.find("min_distance,active_contacts"), std::string::npos) << header;
  while (std::getline(in, line)) last = line;
  // The square has landed: five bottom nodes within d_hat of the ground.
  EXPECT_EQ(last.substr(last.rfind(',') + 1), "5") << last;
}

}  // namespace

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

#include "tests/run_program.h"

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
  const std::string good = Write("good.json", Particle(std::string("{") + kGround + "}"));
  ExpectInputError("--scene=" + good + " --contact_dhat=-1", "--contact_dhat");
  ExpectInputError("--scene=" + good + " --contact_kappa=0", "--contact_kappa");
  ExpectInputError("--scene=" + good + " --friction_mu=-1", "--friction_mu");
  ExpectInputError("--scene=" + good + " --friction_iterations=0", "--friction_iterations");
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

// Reference files (io/reference_file.h): a reference with its checkpoints
// (NaN included) reads back as written, another key's file is not read, and
// two callers that need one reference at once compute it once.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "io/reference_file.h"

namespace ipstep {
namespace {

namespace fs = std::filesystem;

class ReferenceFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ipstep_reference_file_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

ReferenceSolution Sample(double marker) {
  ReferenceSolution r;
  r.x = Eigen::Vector4d(0.0, 1.0 / 3.0, marker, -2.5e-17);
  r.dt = 1e-3 / 7;
  r.error = std::nan("");
  r.ok = true;
  r.steps = 7000;
  r.description = "newmark(1/4,1/2) dt=0.0001429 tol=1e-08 projected_newton";
  r.checkpoint_times = {0.5, 1.0};
  r.checkpoint_x = {Eigen::Vector4d(1, 2, 3, std::nan("")), r.x};
  r.checkpoint_error = 1.25e-9;
  return r;
}

TEST_F(ReferenceFile, ReadsBackWhatWasWritten) {
  const std::string key = "scene|newmark|0.1|10|abc123";
  const std::string file = ReferenceFileName(dir_.string(), key);
  const ReferenceSolution written = Sample(4.0);
  WriteReferenceFile(file, key, written);
  ReferenceSolution read;
  ASSERT_TRUE(ReadReferenceFile(file, key, &read));
  EXPECT_EQ(read.x, written.x);
  EXPECT_EQ(read.dt, written.dt);
  EXPECT_TRUE(std::isnan(read.error));
  EXPECT_EQ(read.steps, 7000);
  EXPECT_EQ(read.description, written.description);
  ASSERT_EQ(read.checkpoint_x.size(), 2u);
  EXPECT_EQ(read.checkpoint_times, written.checkpoint_times);
  EXPECT_EQ(read.checkpoint_x[1], written.x);
  EXPECT_TRUE(std::isnan(read.checkpoint_x[0][3]));
  EXPECT_EQ(read.checkpoint_error, 1.25e-9);
  EXPECT_FALSE(ReadReferenceFile(file, key + "x", &read));
  EXPECT_NE(ReferenceFileName(dir_.string(), key + "x"), file);
}

TEST_F(ReferenceFile, CallersAtOnceComputeItOnce) {
  const std::string key = "slow reference";
  bool first_computed = false, second_computed = true;
  ReferenceSolution first, second;
  std::thread a([&] {
    first = CachedReference(
        dir_.string(), key,
        [] {
          std::this_thread::sleep_for(std::chrono::milliseconds(300));
          return Sample(1.0);
        },
        &first_computed);
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // a holds the lock
  second = CachedReference(
      dir_.string(), key, [] { return Sample(2.0); }, &second_computed);
  a.join();
  EXPECT_TRUE(first_computed);
  EXPECT_FALSE(second_computed);
  EXPECT_EQ(first.x[2], 1.0);
  EXPECT_EQ(second.x[2], 1.0);
  // No directory: computed, nothing kept.
  bool computed = false;
  EXPECT_EQ(CachedReference(
                "", key, [] { return Sample(3.0); }, &computed)
                .x[2],
            3.0);
  EXPECT_TRUE(computed);
}

}  // namespace
}  // namespace ipstep

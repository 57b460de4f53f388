// A fresh scratch directory per test, for tests that read and write real files.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "spdfit/io.hpp"
#include "test_support.hpp"

namespace spdfit::test {

class ScratchDirectory : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        std::filesystem::path(testing::TempDir()) / (std::string("spdfit_") + info->test_suite_name() + "_" +
                                                     info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    // A test may have taken the directory's permissions away (unreadable-file tests).
    std::error_code ignored;
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all, std::filesystem::perm_options::add,
                                 ignored);
    std::filesystem::remove_all(dir_, ignored);
  }

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  std::string Write(const std::string& name, const std::string& bytes) const {
    const std::string path = Path(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  std::filesystem::path dir_;
};

/// A scratch directory with noisy data A X ~= B, m x n, written as CSV (A) and .npy (B): both
/// readers at once.
class NoisyDataFiles : public ScratchDirectory {
 protected:
  void MakeData(Eigen::Index m, Eigen::Index n, unsigned seed) {
    Generator g(seed);
    const Eigen::MatrixXd X = g.spd(n, 10.0);
    A_ = g.gaussian(m, n) * 3.0;
    B_ = A_ * X + 0.1 * g.gaussian(m, n);
    a_path_ = Path("A.csv");
    b_path_ = Path("B.npy");
    io::write_csv(a_path_, A_);
    io::write_npy(b_path_, B_);
  }

  Eigen::MatrixXd A_, B_;
  std::string a_path_, b_path_;
};

}  // namespace spdfit::test

// read_table, read_matrix, write_csv and write_npy on real files: file checks, format
// detection, and errors that name the path.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <random>
#include <string>
#include <thread>

#include "file_test_support.hpp"
#include "spdfit/io.hpp"

namespace {

namespace fs = std::filesystem;
using Eigen::MatrixXd;
using spdfit::io::DataError;
using spdfit::io::read_matrix;
using spdfit::io::read_table;
using spdfit::io::Table;

class IoFiles : public spdfit::test::ScratchDirectory {};

DataError ReadError(const std::string& path) {
  try {
    read_table(path);
  } catch (const DataError& e) {
    return e;
  }
  ADD_FAILURE() << "no DataError for " << path;
  return DataError("", 0, 0, "");
}

void ExpectReadError(const std::string& path, const std::string& problem) {
  const DataError e = ReadError(path);
  EXPECT_EQ(e.source(), path);
  EXPECT_EQ(e.line(), 0u);
  EXPECT_EQ(e.problem(), problem) << e.what();
  EXPECT_EQ(std::string(e.what()), path + ": " + problem);
}

const MatrixXd k2x3 = (MatrixXd(2, 3) << 1, 2, 3, 4, 5, 6).finished();

TEST_F(IoFiles, ReadsCsv) {
  const Table table = read_table(Write("A.csv", "x,y,z\r\n1,2,3\r\n4,5,6\r\n"));
  EXPECT_EQ(table.values, k2x3);
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_EQ(read_matrix(Path("A.csv")), k2x3);
}

TEST_F(IoFiles, ReadsExcelStyleSemicolonCsv) {
  const Table table = read_table(Write("B.csv", "\xEF\xBB\xBFZeit;Kraft\r\n0.5;1.25\r\n"));
  EXPECT_EQ(table.column_names, (std::vector<std::string>{"Zeit", "Kraft"}));
  EXPECT_EQ(table.values, (MatrixXd(1, 2) << 0.5, 1.25).finished());
}

TEST_F(IoFiles, TextErrorsNameThePath) {
  const std::string path = Write("A.csv", "1,2,3\n4,abc,6\n");
  const DataError e = ReadError(path);
  EXPECT_EQ(e.source(), path);
  EXPECT_EQ(std::string(e.what()), path + ":2:3: 'abc' is not a number");
}

TEST_F(IoFiles, NonfiniteOption) {
  const std::string path = Write("A.csv", "1,nan\n");
  EXPECT_EQ(ReadError(path).problem(), "NaN is not allowed");
  spdfit::io::ReadOptions options;
  options.allow_nonfinite = true;
  EXPECT_TRUE(std::isnan(read_matrix(path, options)(0, 1)));
}

TEST_F(IoFiles, NpyRecognizedByMagicBytesNotName) {
  spdfit::io::write_npy(Path("matrix.csv"), k2x3);
  EXPECT_EQ(read_matrix(Path("matrix.csv")), k2x3);
  const Table table = read_table(Path("matrix.csv"));
  EXPECT_TRUE(table.column_names.empty());
  // And a text file is text whatever its name.
  EXPECT_EQ(read_matrix(Write("text.npy", "1 2 3\n4 5 6\n")), k2x3);
}

TEST_F(IoFiles, NpyErrorsNameThePath) {
  spdfit::io::write_npy(Path("X.npy"), k2x3);
  fs::resize_file(Path("X.npy"), fs::file_size(Path("X.npy")) - 8);
  ExpectReadError(Path("X.npy"), "header claims 6 values, file holds 5 (shape is (2, 3))");
}

TEST_F(IoFiles, MissingFile) {
  ExpectReadError(Path("missing.csv"), "no such file");
  ExpectReadError(Path("missing/A.csv"), "no such file");
  // A path through a regular file.
  ExpectReadError(Write("A.csv", "1\n") + "/B.csv", "no such file");
}

TEST_F(IoFiles, Directory) { ExpectReadError(dir_.string(), "is a directory"); }

TEST_F(IoFiles, Symlink) {
  const std::string target = Write("A.csv", "1,2,3\n4,5,6\n");
  fs::create_symlink(target, Path("link.csv"));
  EXPECT_EQ(read_matrix(Path("link.csv")), k2x3);
  fs::create_symlink(Path("nowhere.csv"), Path("dangling.csv"));
  ExpectReadError(Path("dangling.csv"), "no such file");
}

TEST_F(IoFiles, FifoIsRefusedWithoutBlocking) {
  const std::string path = Path("pipe");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  auto result = std::async(std::launch::async, [&path] { return ReadError(path).problem(); });
  if (result.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    // The reader is stuck in open(): open the writing end and close it so that it sees EOF.
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
    FAIL() << "read_table blocked on a FIFO";
  }
  EXPECT_EQ(result.get(), "is not a regular file (it is a named pipe)");
}

// Regression: a sparse file of 8 GB of zeros (no disk space) was read whole before the reader
// found its first byte was not text.
TEST_F(IoFiles, SparseFileOfZerosIsRefusedFromItsFirstBytes) {
  const std::string path = Write("sparse.csv", "");
  fs::resize_file(path, std::uintmax_t{8} << 30);
  EXPECT_EQ(std::string(ReadError(path).what()),
            path + ":1:1: looks like a binary file, not text (NUL byte at byte offset 0)");
  // Binary content after the first 64 KiB is found by the whole-text check, with the same message.
  const std::string late = Write("late.csv", std::string(1 << 17, '1') + std::string(1, '\0'));
  EXPECT_EQ(std::string(ReadError(late).what()),
            late + ":1:131073: looks like a binary file, not text (NUL byte at byte offset 131072)");
}

TEST_F(IoFiles, DeviceIsRefused) { ExpectReadError("/dev/null", "is not a regular file (it is a device)"); }

TEST_F(IoFiles, PermissionDenied) {
  const std::string path = Write("secret.csv", "1,2\n");
  fs::permissions(path, fs::perms::none);
  if (std::ifstream(path).is_open()) GTEST_SKIP() << "running with permission to read anything";
  ExpectReadError(path, "permission denied");
}

TEST_F(IoFiles, UnsearchableDirectory) {
  const std::string path = Write("A.csv", "1,2\n");
  fs::permissions(dir_, fs::perms::none);
  const bool readable = std::ifstream(path).is_open();
  fs::permissions(dir_, fs::perms::owner_all);
  if (readable) GTEST_SKIP() << "running with permission to read anything";
  fs::permissions(dir_, fs::perms::none);
  const DataError e = ReadError(path);
  fs::permissions(dir_, fs::perms::owner_all);
  EXPECT_EQ(e.problem(), "permission denied");
}

TEST_F(IoFiles, EmptyFile) {
  ExpectReadError(Write("empty.csv", ""), "file is empty");
  EXPECT_EQ(ReadError(Write("bom.csv", "\xEF\xBB\xBF")).problem(), "no data rows (the text is empty)");
  EXPECT_EQ(ReadError(Write("blank.csv", "\n\n")).problem(), "no data rows (only comments and blank lines)");
}

TEST_F(IoFiles, BinaryFile) {
  const DataError e = ReadError(Write("data.mat", std::string("MATLAB 5.0 MAT-file\0\x01", 21)));
  EXPECT_EQ(e.line(), 1u);
  EXPECT_EQ(e.column(), 20u);
  EXPECT_EQ(e.problem(), "looks like a binary file, not text (NUL byte at byte offset 19)");
}

TEST_F(IoFiles, WriteCsvThenReadBack) {
  std::mt19937_64 rng(1);
  std::normal_distribution<double> normal;
  MatrixXd X(300, 20);
  for (Eigen::Index i = 0; i < X.size(); ++i) X(i) = std::ldexp(normal(rng), int(rng() % 200) - 100);
  X(0, 0) = std::numeric_limits<double>::denorm_min();
  spdfit::io::write_csv(Path("X.csv"), X);
  const MatrixXd back = read_matrix(Path("X.csv"));
  ASSERT_EQ(back.rows(), X.rows());
  ASSERT_EQ(back.cols(), X.cols());
  EXPECT_TRUE((back.array() == X.array()).all());
}

TEST_F(IoFiles, WriteReplacesAnExistingFile) {
  Write("X.csv", "a much longer old content that must disappear\n1,2,3,4,5\n");
  spdfit::io::write_csv(Path("X.csv"), k2x3);
  EXPECT_EQ(read_matrix(Path("X.csv")), k2x3);
  Write("X.npy", std::string(10000, 'x'));
  spdfit::io::write_npy(Path("X.npy"), k2x3);
  EXPECT_EQ(read_matrix(Path("X.npy")), k2x3);
}

TEST_F(IoFiles, WriteErrors) {
  const auto expect_write_error = [](auto write, const std::string& path, const std::string& problem) {
    try {
      write(path, k2x3);
      ADD_FAILURE() << "no DataError writing " << path;
    } catch (const DataError& e) {
      EXPECT_EQ(e.source(), path);
      EXPECT_EQ(e.problem(), problem);
    }
  };
  const auto csv = [](const std::string& p, const MatrixXd& X) { spdfit::io::write_csv(p, X); };
  const auto npy = [](const std::string& p, const MatrixXd& X) { spdfit::io::write_npy(p, X); };
  expect_write_error(csv, Path("missing/X.csv"), "cannot be written (no such directory)");
  expect_write_error(npy, Path("missing/X.npy"), "cannot be written (no such directory)");
  expect_write_error(csv, dir_.string(), "cannot be written (is a directory)");
  expect_write_error(npy, dir_.string(), "cannot be written (is a directory)");
  if (fs::exists("/dev/full")) {
    expect_write_error(csv, "/dev/full", "writing failed (no space left on the device)");
    expect_write_error(npy, "/dev/full", "writing failed (no space left on the device)");
    // Large enough to fail while writing, before the final flush.
    const MatrixXd big = MatrixXd::Ones(1000, 100);
    const auto expect_full = [&big](auto write) {
      try {
        write("/dev/full", big);
        ADD_FAILURE() << "no DataError writing to /dev/full";
      } catch (const DataError& e) {
        EXPECT_EQ(e.problem(), "writing failed (no space left on the device)");
      }
    };
    expect_full(csv);
    expect_full(npy);
  }
}

}  // namespace

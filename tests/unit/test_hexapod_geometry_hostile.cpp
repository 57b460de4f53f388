// The geometry file reader on hostile files: paths that are not regular files, JSON nested to
// exhaust memory, files too large to be geometries, numbers beyond the double range. Each is an
// io::DataError naming the file, without blocking, reading forever or parsing the whole text.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>

#include "hexapod_support.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/io.hpp"

namespace spdfit {
namespace {

namespace fs = std::filesystem;

// The message read_geometry (or parse_geometry, for text) gives, which must be an io::DataError.
std::string file_error(const std::string& path) {
  try {
    hexapod::read_geometry(path);
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.source(), path);
    return e.what();
  }
  ADD_FAILURE() << "accepted " << path;
  return "";
}

std::string text_error(const std::string& text) {
  try {
    hexapod::parse_geometry(text, "G.json");
  } catch (const io::DataError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted " << text.substr(0, 200);
  return "";
}

class GeometryFiles : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(testing::TempDir()) / ("spdfit_geometry_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// Regression: the reader opened the path with std::ifstream, which blocks on a FIFO until a
// writer comes (spdfit hexapod model --geometry FIFO hung).
TEST_F(GeometryFiles, FifoIsRefusedWithoutBlocking) {
  const std::string path = Path("pipe.json");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  auto result = std::async(std::launch::async, [&path] { return file_error(path); });
  if (result.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);  // let the stuck reader see EOF
    if (fd >= 0) ::close(fd);
    FAIL() << "read_geometry blocked on a FIFO";
  }
  EXPECT_EQ(result.get(), path + ": is not a regular file (it is a named pipe)");
}

// Regression: /dev/zero was read until memory ran out.
TEST_F(GeometryFiles, DeviceIsRefusedWithoutReading) {
  EXPECT_EQ(file_error("/dev/zero"), "/dev/zero: is not a regular file (it is a device)");
}

// Regression: a directory was reported as "not valid JSON ... unexpected end of input".
TEST_F(GeometryFiles, DirectoryIsCalledOne) { EXPECT_EQ(file_error(dir_.string()), dir_.string() + ": is a directory"); }

TEST_F(GeometryFiles, LargeFileIsRefusedBeforeReading) {
  const std::string path = Path("sparse.json");
  { std::ofstream touch(path); }
  fs::resize_file(path, std::uintmax_t{8} << 30);  // 8 GB of zeros, no disk space
  EXPECT_EQ(file_error(path), path + ": is 8589934592 bytes long; at most 1048576 are accepted for a geometry file");
}

TEST(GeometryText, NestingBeyondSixtyFourLevelsIsRefusedWithItsPosition) {
  EXPECT_EQ(text_error(std::string(1000, '[') + std::string(1000, ']')),
            "G.json:1:65: JSON nested more than 64 levels deep; a geometry file needs 3");
  std::string deep = "{\n \"_c\": \"[[[[\",\n \"base_points\": " + std::string(100000, '[');
  EXPECT_EQ(text_error(deep), "G.json:3:80: JSON nested more than 64 levels deep; a geometry file needs 3");
  // Sixty-four levels are parsed (and found not to be a geometry).
  EXPECT_NE(text_error("{\"_c\": " + std::string(63, '[') + std::string(63, ']') + "}").find("missing key"),
            std::string::npos);
}

TEST(GeometryText, MoreThanAMebibyteIsRefused) {
  EXPECT_EQ(text_error("{\"_pad\": \"" + std::string(1 << 20, ' ') + "\"}"),
            "G.json: is 1048588 bytes long; at most 1048576 are accepted for a geometry file");
}

// Regression: nlohmann's parser reports a number beyond the double range as out_of_range rather
// than parse_error, which escaped as an exception without the file's name.
TEST(GeometryText, NumberBeyondTheDoubleRangeNamesTheFile) {
  EXPECT_EQ(text_error("{\"payload_mass\": 1e999}"), "G.json: not valid JSON: number overflow parsing '1e999'");
}

}  // namespace
}  // namespace spdfit

// The libraries of the container formats (.mat: libmatio, .npz: libzip), opened at their first
// use (io/format_libraries.cpp): a library that cannot be opened, or lacks a function, is an
// error that says which, not a crash.
#include <gtest/gtest.h>

#include <string>

#include "io/format_libraries.hpp"

namespace spdfit::io::detail {
namespace {

TEST(FormatLibraries, ALibraryThatDoesNotExistIsAnErrorNamingIt) {
  const char* names[] = {"zip_open"};
  void* addresses[1] = {};
  std::string error;
  EXPECT_FALSE(open_library("libspdfit-no-such-library.so.0", names, 1, addresses, &error));
  EXPECT_NE(error.find("libspdfit-no-such-library.so.0"), std::string::npos) << error;
  EXPECT_EQ(addresses[0], nullptr);
}

TEST(FormatLibraries, AMissingFunctionIsAnErrorNamingIt) {
  // libm is in every process: a library that opens but has no such function.
  const char* names[] = {"cos", "spdfit_no_such_function"};
  void* addresses[2] = {};
  std::string error;
  EXPECT_FALSE(open_library("libm.so.6", names, 2, addresses, &error));
  EXPECT_NE(error.find("has no function spdfit_no_such_function"), std::string::npos) << error;
}

TEST(FormatLibraries, TheFunctionsFound) {
  const char* names[] = {"cos"};
  void* addresses[1] = {};
  std::string error;
  ASSERT_TRUE(open_library("libm.so.6", names, 1, addresses, &error)) << error;
  using Cos = double (*)(double);
  EXPECT_EQ(reinterpret_cast<Cos>(addresses[0])(0.0), 1.0);
}

TEST(FormatLibraries, LibmatioAndLibzipLoadWithEveryFunctionSpdfitCalls) {
  const Matio& mat = matio("x.mat");
  EXPECT_NE(mat.Mat_Open, nullptr);
  EXPECT_NE(mat.Mat_VarWrite, nullptr);
  EXPECT_EQ(&loaded_matio(), &mat);
  const Libzip& zip = libzip("x.npz");
  EXPECT_NE(zip.zip_open, nullptr);
  EXPECT_NE(zip.zip_stat_init, nullptr);
  EXPECT_EQ(&loaded_libzip(), &zip);
}

}  // namespace
}  // namespace spdfit::io::detail

// Reading prescribed pairs and weights for synthesis from data files: units, shapes, and the
// errors that name the file.
#include <gtest/gtest.h>

#include <string>

#include "linkage_support.hpp"
#include "spdfit/linkage/pairs_file.hpp"

namespace spdfit::linkage {
namespace {

using test::kDeg;

// The DataError parse_pairs throws on `text` (a failed test if none).
io::DataError PairsError(const std::string& text, const PairsFileOptions& options = {}) {
  try {
    parse_pairs(text, "pairs.csv", options);
  } catch (const io::DataError& e) {
    return e;
  }
  ADD_FAILURE() << "no DataError for: " << text;
  return io::DataError("", 0, 0, "");
}

TEST(PairsFile, DegreesByDefaultRadiansOnRequest) {
  const PrescribedPairs degrees = parse_pairs("psi,phi\n0,80\n10,82\n20,85\n", "pairs.csv");
  ASSERT_EQ(degrees.delta_psi.size(), 3);
  EXPECT_DOUBLE_EQ(degrees.delta_psi(1), 10 * kDeg);
  EXPECT_DOUBLE_EQ(degrees.delta_phi(2), 85 * kDeg);
  PairsFileOptions options;
  options.radians = true;
  const PrescribedPairs radians = parse_pairs("0 1\n0.5 1.25\n1 1.5\n", "pairs.txt", options);
  EXPECT_EQ(radians.delta_phi(1), 1.25);
}

TEST(PairsFile, ReadsNpy) {
  // A 3x2 float64 array as numpy.save writes it, values 0..5 in C order.
  std::string npy = "\x93NUMPY\x01";
  npy += '\0';
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 2), }";
  dict.append((64 - (10 + dict.size() + 1) % 64) % 64, ' ');  // data 64-byte aligned
  dict += '\n';
  npy += static_cast<char>(dict.size());
  npy += '\0';
  npy += dict;
  for (int k = 0; k < 6; ++k) {
    const double value = k;
    npy.append(reinterpret_cast<const char*>(&value), 8);  // little-endian hosts
  }
  PairsFileOptions options;
  options.radians = true;
  const PrescribedPairs pairs = parse_pairs(npy, "pairs.npy", options);
  EXPECT_EQ(pairs.delta_psi, Eigen::Vector3d(0, 2, 4));
  EXPECT_EQ(pairs.delta_phi, Eigen::Vector3d(1, 3, 5));
}

TEST(PairsFile, NeedsTwoColumns) {
  EXPECT_STREQ(PairsError("0,80,1\n10,82,1\n20,85,1\n").what(),
               "pairs.csv: the pairs file has 3 columns: two are needed, the input angle psi and the output "
               "angle phi");
  EXPECT_STREQ(PairsError("0\n10\n20\n").what(),
               "pairs.csv: the pairs file has 1 columns: two are needed, the input angle psi and the output "
               "angle phi");
}

TEST(PairsFile, NeedsEnoughPairs) {
  EXPECT_STREQ(PairsError("0,80\n10,82\n").what(),
               "pairs.csv: 2 pair(s): at least 3 are needed (3 give exact precision-point synthesis)");
  PairsFileOptions dial_zeros;
  dial_zeros.min_pairs = 5;
  EXPECT_NE(std::string(PairsError("0,80\n10,82\n20,85\n30,90\n", dial_zeros).what()).find("at least 5"),
            std::string::npos);
}

TEST(PairsFile, ReaderErrorsNameTheFileLineAndColumn) {
  const io::DataError nan = PairsError("psi,phi\n0,80\n10,nan\n20,85\n");
  EXPECT_EQ(nan.line(), 3u);
  EXPECT_EQ(nan.column(), 4u);
  EXPECT_STREQ(PairsError("").what(), "pairs.csv: file is empty");
}

TEST(PairsFile, Weights) {
  EXPECT_EQ(weights_from_matrix(Eigen::MatrixXd::Constant(1, 3, 2.0), 3, "w.csv"), Eigen::Vector3d(2, 2, 2));
  EXPECT_EQ(weights_from_matrix(Eigen::MatrixXd::Constant(3, 1, 2.0), 3, "w.csv"), Eigen::Vector3d(2, 2, 2));
  try {
    weights_from_matrix(Eigen::MatrixXd::Constant(2, 1, 1.0), 3, "w.csv");
    ADD_FAILURE() << "no error for 2 weights";
  } catch (const io::DataError& e) {
    EXPECT_STREQ(e.what(), "w.csv: the weights are 2x1: one column of 3 weights (one per pair) is needed");
  }
  Eigen::Vector3d w(1, 0, 1);
  try {
    weights_from_matrix(w, 3, "w.csv");
    ADD_FAILURE() << "no error for a zero weight";
  } catch (const io::DataError& e) {
    EXPECT_STREQ(e.what(), "w.csv: weight 2 is 0: weights must be positive");
  }
}

}  // namespace
}  // namespace spdfit::linkage

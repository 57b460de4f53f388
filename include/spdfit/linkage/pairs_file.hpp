// Reading prescribed input-output pairs (and their weights) for synthesis from data files.
#pragma once

#include <string>
#include <string_view>

#include <Eigen/Core>

#include "spdfit/io.hpp"
#include "spdfit/linkage/prescribed_function.hpp"

namespace spdfit::linkage {

/// How a pairs file is read.
struct PairsFileOptions {
  /// The angles in the file are radians; by default they are degrees.
  bool radians = false;
  /// Fewer pairs than this is an error: 3 for synthesize (its unknowns k1, k2, k3), 5 when it
  /// also fits the dial zeros (notes 002, eq. 3.7).
  Eigen::Index min_pairs = 3;
};

/// The pairs in a table read from a data file (io::read_table): two columns, the input angle
/// change delta_psi and the output angle change delta_phi (notes 002, eq. 3.6), one pair per
/// row, converted to radians. Throws io::DataError naming `source` when the table does not
/// have exactly two columns or has fewer than options.min_pairs rows. Cost O(m).
PrescribedPairs pairs_from_table(const io::Table& table, const std::string& source,
                                 const PairsFileOptions& options = {});

/// The same from the bytes of a pairs file (delimited text or .npy, see io::parse_table), and
/// from the file at `path` (see io::read_table). Throws io::DataError for anything io::parse_table
/// rejects (NaN and Inf included) and as pairs_from_table.
PrescribedPairs parse_pairs(std::string_view bytes, const std::string& source, const PairsFileOptions& options = {});
PrescribedPairs read_pairs(const std::string& path, const PairsFileOptions& options = {});

/// Weights for `pairs` pairs from a weights file: one row or one column of `pairs` positive
/// numbers. Throws io::DataError naming `path` otherwise (and for anything io::read_matrix
/// rejects).
Eigen::VectorXd weights_from_matrix(const Eigen::MatrixXd& W, Eigen::Index pairs, const std::string& source);
Eigen::VectorXd read_weights(const std::string& path, Eigen::Index pairs);

}  // namespace spdfit::linkage

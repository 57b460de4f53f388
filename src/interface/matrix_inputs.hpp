// What the commands' workflows share about their matrix inputs (MatrixInput: a file or values):
// reading one, refusing one of the wrong size by its file or option, and the pair rule that B is
// a file or columns of A's file.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "spdfit/io.hpp"
#include "spdfit/options.hpp"
#include "spdfit/outcome.hpp"

namespace spdfit::detail {

/// A matrix option's values: its file read (io::DataError naming it; the reader's warnings appended
/// to `warnings`) or the values given.
Eigen::MatrixXd values_of(const MatrixInput& input, const io::ReadOptions& read, std::vector<Warning>& warnings);

/// A size problem of `input`: io::DataError naming its file when it came from one, else InputError
/// naming `subject` (the option or argument); both Code::DataShape.
[[noreturn]] void shape_problem(const MatrixInput& input, const std::string& subject, const std::string& problem);

/// OptionError (Code::Argument) when B is not given (`b_given`) and no columns of A's file
/// were chosen for A and B (`a_cols`, `b_cols`).
void check_b_given(bool b_given, const std::string& a_cols, const std::string& b_cols);

}  // namespace spdfit::detail

// MATLAB arrays in and out: numeric arrays as users pass them read into Eigen matrices (with the
// checks a data file gets), option values read by their table type, and the library's JSON
// rendering of a result written as a struct with the JSON's field names.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <string>

#include "mex.h"
#include "spdfit/outcome.hpp"

namespace spdfit::matlab {

/// A wrong kind of argument (sparse, complex, not numeric, more than two dimensions): the gateway
/// raises it as 'spdfit:UsageError'.
struct UsageError : std::invalid_argument, Coded {
  explicit UsageError(const std::string& message, Code code = Code::Argument)
      : std::invalid_argument(message), Coded(code, {}) {}
};

/// Data that cannot be fitted (empty, NaN or Inf entries): raised as 'spdfit:DataError'.
struct DataError : std::runtime_error, Coded {
  explicit DataError(const std::string& message, Code code = Code::DataValue)
      : std::runtime_error(message), Coded(code, {}) {}
};

/// A numeric argument as a double matrix: double, single, any integer class and logical are
/// converted; sparse, complex, non-numeric and N-dimensional arrays are UsageError; an empty
/// matrix and NaN or Inf entries are DataError naming `name` and the entry ("A(3,2) is NaN").
Eigen::MatrixXd read_matrix(const mxArray* array, const std::string& name);

/// The text of a character vector (or a 1x1 cell of one); UsageError naming `what` otherwise.
std::string read_text(const mxArray* array, const std::string& what);

/// A double matrix with X's entries.
mxArray* write_matrix(const Eigen::MatrixXd& X);

/// The JSON document `json` as MATLAB values: an object is a struct (keys that are not valid
/// field names have their other characters replaced by '_'), an array of numbers a row vector
/// (null: NaN), an array of equally long arrays of numbers a matrix (one row per inner array), an
/// array of objects with the same keys a struct array, other arrays cells, a string a character
/// vector, a bool a logical, null [].
mxArray* write_json(const std::string& json);

}  // namespace spdfit::matlab

#include "mex_arrays.hpp"

#include "mex_pairs.hpp"

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>


namespace spdfit::matlab {

namespace {

using Json = nlohmann::json;

template <typename T>
void copy_entries(const mxArray* array, Eigen::MatrixXd& X) {
  const T* data = static_cast<const T*>(mxGetData(array));
  for (Eigen::Index k = 0; k < X.size(); ++k) X.data()[k] = static_cast<double>(data[k]);
}

std::string class_name(const mxArray* array) { return mxGetClassName(array); }

// MATLAB's 1-based "A(3,2)".
std::string entry_name(const std::string& name, Eigen::Index i, Eigen::Index j) {
  return name + "(" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ")";
}

bool numeric_or_logical(const mxArray* array) { return mxIsNumeric(array) || mxIsLogical(array); }

double scalar(const mxArray* array, const std::string& name, const std::string& expected) {
  if (!numeric_or_logical(array) || mxIsComplex(array) || mxIsSparse(array) || mxGetNumberOfElements(array) != 1) {
    throw UsageError("'" + name + "' must be " + expected + ", got a " + std::to_string(mxGetM(array)) + "x" +
                     std::to_string(mxGetN(array)) + " " + class_name(array));
  }
  return read_matrix(array, name)(0, 0);
}

std::string field_name(const std::string& key) {
  std::string out;
  for (char c : key) out += std::isalnum(static_cast<unsigned char>(c)) || c == '_' ? c : '_';
  if (out.empty() || !std::isalpha(static_cast<unsigned char>(out[0]))) out = "x" + out;
  return out.substr(0, 63);
}

bool is_number_or_null(const Json& v) { return v.is_number() || v.is_null(); }

double number(const Json& v) {
  return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
}

mxArray* to_mx(const Json& v);

mxArray* struct_of(const std::vector<const Json*>& objects) {
  std::vector<std::string> names;
  for (const auto& item : objects.front()->items()) names.push_back(field_name(item.key()));
  std::vector<const char*> pointers;
  for (const std::string& n : names) pointers.push_back(n.c_str());
  mxArray* out = mxCreateStructMatrix(1, objects.size(), static_cast<int>(pointers.size()), pointers.data());
  for (std::size_t k = 0; k < objects.size(); ++k) {
    int field = 0;
    for (const auto& item : objects[k]->items()) {
      mxSetFieldByNumber(out, static_cast<mwIndex>(k), field++, to_mx(item.value()));
    }
  }
  return out;
}

mxArray* array_of(const Json& v) {
  if (v.empty()) return mxCreateDoubleMatrix(0, 0, mxREAL);
  if (std::all_of(v.begin(), v.end(), is_number_or_null)) {
    mxArray* out = mxCreateDoubleMatrix(1, v.size(), mxREAL);
    double* data = static_cast<double*>(mxGetData(out));
    for (std::size_t k = 0; k < v.size(); ++k) data[k] = number(v[k]);
    return out;
  }
  const std::size_t columns = v.front().is_array() ? v.front().size() : 0;
  const bool matrix = columns > 0 && std::all_of(v.begin(), v.end(), [&](const Json& row) {
    return row.is_array() && row.size() == columns && std::all_of(row.begin(), row.end(), is_number_or_null);
  });
  if (matrix) {
    mxArray* out = mxCreateDoubleMatrix(v.size(), columns, mxREAL);
    double* data = static_cast<double*>(mxGetData(out));
    for (std::size_t i = 0; i < v.size(); ++i) {
      for (std::size_t j = 0; j < columns; ++j) data[i + j * v.size()] = number(v[i][j]);
    }
    return out;
  }
  const bool same_keys = v.front().is_object() && std::all_of(v.begin(), v.end(), [&](const Json& item) {
    if (!item.is_object() || item.size() != v.front().size()) return false;
    auto a = item.begin();
    for (auto b = v.front().begin(); b != v.front().end(); ++a, ++b) {
      if (a.key() != b.key()) return false;
    }
    return true;
  });
  if (same_keys) {
    std::vector<const Json*> objects;
    for (const Json& item : v) objects.push_back(&item);
    return struct_of(objects);
  }
  mxArray* out = mxCreateCellMatrix(1, v.size());
  for (std::size_t k = 0; k < v.size(); ++k) mxSetCell(out, static_cast<mwIndex>(k), to_mx(v[k]));
  return out;
}

mxArray* to_mx(const Json& v) {
  switch (v.type()) {
    case Json::value_t::object:
      if (v.empty()) return mxCreateStructMatrix(1, 1, 0, nullptr);
      return struct_of({&v});
    case Json::value_t::array: return array_of(v);
    case Json::value_t::string: return mxCreateString(v.get<std::string>().c_str());
    case Json::value_t::boolean: return mxCreateLogicalScalar(v.get<bool>());
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return mxCreateDoubleScalar(v.get<double>());
    default: return mxCreateDoubleMatrix(0, 0, mxREAL);
  }
}

}  // namespace

Eigen::MatrixXd read_matrix(const mxArray* array, const std::string& name) {
  if (mxIsSparse(array)) throw UsageError(name + " is sparse: give full(" + name + ")");
  if (mxIsComplex(array)) throw UsageError(name + " is complex: spdfit fits real matrices");
  if (!numeric_or_logical(array)) {
    throw UsageError(name + " must be a numeric or logical matrix, got a " + class_name(array));
  }
  if (mxGetNumberOfDimensions(array) > 2) {
    throw UsageError(name + " has " + std::to_string(mxGetNumberOfDimensions(array)) + " dimensions: give a matrix");
  }
  if (mxIsEmpty(array)) throw DataError(name + " is empty");
  Eigen::MatrixXd X(static_cast<Eigen::Index>(mxGetM(array)), static_cast<Eigen::Index>(mxGetN(array)));
  switch (mxGetClassID(array)) {
    case mxDOUBLE_CLASS: copy_entries<double>(array, X); break;
    case mxSINGLE_CLASS: copy_entries<float>(array, X); break;
    case mxINT8_CLASS: copy_entries<std::int8_t>(array, X); break;
    case mxUINT8_CLASS: copy_entries<std::uint8_t>(array, X); break;
    case mxINT16_CLASS: copy_entries<std::int16_t>(array, X); break;
    case mxUINT16_CLASS: copy_entries<std::uint16_t>(array, X); break;
    case mxINT32_CLASS: copy_entries<std::int32_t>(array, X); break;
    case mxUINT32_CLASS: copy_entries<std::uint32_t>(array, X); break;
    case mxINT64_CLASS: copy_entries<std::int64_t>(array, X); break;
    case mxUINT64_CLASS: copy_entries<std::uint64_t>(array, X); break;
    case mxLOGICAL_CLASS: copy_entries<mxLogical>(array, X); break;
    default: throw UsageError(name + " must be a numeric or logical matrix, got a " + class_name(array));
  }
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    for (Eigen::Index i = 0; i < X.rows(); ++i) {
      if (!std::isfinite(X(i, j))) {
        throw DataError(entry_name(name, i, j) + " is " + (std::isnan(X(i, j)) ? "NaN" : "Inf") +
                            ": every entry must be finite");
      }
    }
  }
  return X;
}

std::string read_text(const mxArray* array, const std::string& what) {
  if (mxIsCell(array) && mxGetNumberOfElements(array) == 1) array = mxGetCell(array, 0);
  if (array == nullptr || !mxIsChar(array) || (mxGetM(array) > 1)) {
    throw UsageError(what + " must be a character vector");
  }
  char* text = mxArrayToString(array);
  std::string out = text ? text : "";
  mxFree(text);
  return out;
}

std::optional<OptionValue> read_value(OptionType type, const std::string& name, const mxArray* value) {
  if (mxIsEmpty(value) && (mxIsDouble(value) || mxIsCell(value))) return std::nullopt;
  switch (type) {
    case OptionType::Flag:
    case OptionType::Boolean: {
      const double v = scalar(value, name, "true or false");
      if (v != 0.0 && v != 1.0) throw UsageError("'" + name + "' must be true or false, got " + value_text(v));
      return OptionValue{v != 0.0};
    }
    case OptionType::Integer: {
      const double v = scalar(value, name, "an integer");
      if (v != std::floor(v) || std::abs(v) > 9.0e15) {
        throw UsageError("'" + name + "' must be an integer, got " + value_text(v));
      }
      return OptionValue{static_cast<std::int64_t>(v)};
    }
    case OptionType::Real: return OptionValue{scalar(value, name, "a real number")};
    case OptionType::Names: {
      if (!mxIsCell(value)) return OptionValue{read_text(value, "'" + name + "'")};
      std::string names;
      for (std::size_t k = 0; k < mxGetNumberOfElements(value); ++k) {
        names += (k == 0 ? "" : ",") + read_text(mxGetCell(value, k), "each name of '" + name + "'");
      }
      return OptionValue{names};
    }
    case OptionType::Range: {
      // [lo hi], or the command line's text 'LO:HI'.
      if (mxIsChar(value)) return OptionValue{read_text(value, "'" + name + "'")};
      const Eigen::MatrixXd v = read_matrix(value, "'" + name + "'");
      if (v.size() != 2) throw UsageError("'" + name + "' must be [lo hi] (two numbers) or text 'LO:HI'");
      return OptionValue{range_text(v(0), v(1))};
    }
    case OptionType::Text:
    case OptionType::Choice:
    case OptionType::File:
    case OptionType::Columns:
    case OptionType::Rows:
    case OptionType::Geometry: return OptionValue{read_text(value, "'" + name + "'")};
    case OptionType::RealList:
    case OptionType::Vector: {
      const Eigen::MatrixXd v = read_matrix(value, "'" + name + "'");
      if (v.rows() != 1 && v.cols() != 1) throw UsageError("'" + name + "' must be a vector");
      return OptionValue{std::vector<double>(v.data(), v.data() + v.size())};
    }
    case OptionType::Matrix: {
      // A file's name, or the matrix itself.
      if (mxIsChar(value)) return OptionValue{read_text(value, "'" + name + "'")};
      MatrixInput input;
      input.values = read_matrix(value, "'" + name + "'");
      return OptionValue{std::move(input)};
    }
    case OptionType::Noise: break;
  }
  throw UsageError("'" + name + "' cannot be given from MATLAB");
}

mxArray* write_matrix(const Eigen::MatrixXd& X) {
  mxArray* out = mxCreateDoubleMatrix(static_cast<mwSize>(X.rows()), static_cast<mwSize>(X.cols()), mxREAL);
  std::copy(X.data(), X.data() + X.size(), static_cast<double*>(mxGetData(out)));
  return out;
}

mxArray* write_json(const std::string& json) { return to_mx(Json::parse(json)); }

}  // namespace spdfit::matlab

// MATLAB .mat files through libmatio: levels 5 and 7.3 read whole or (7.3) a block of rows at a
// time, after their structure is checked; one matrix written as level 5.
#include "containers.hpp"

#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "file_error.hpp"
#include "format_libraries.hpp"
#include "mat73_structure.hpp"
#include "mat_structure.hpp"
#include "npy_layout.hpp"
#include "parse.hpp"

namespace spdfit::io::detail {

// Named, not anonymous: MatRowBlocks::State (declared in a header) holds a MatMatrix.
namespace mat_file {

struct MatCloser {
  void operator()(mat_t* mat) const { loaded_matio().Mat_Close(mat); }
};
struct VarFreer {
  void operator()(matvar_t* var) const { loaded_matio().Mat_VarFree(var); }
};
using MatFile = std::unique_ptr<mat_t, MatCloser>;
using MatVar = std::unique_ptr<matvar_t, VarFreer>;

// libmatio prints its warnings and errors to standard error by default; spdfit reports its own.
void quiet_log(int, char*) {}

bool numeric_class(matio_classes c) { return c >= MAT_C_DOUBLE && c <= MAT_C_UINT64; }

// Refuses a variable whose header declares more values than the file could hold even compressed:
// libmatio allocates what the header says, so a damaged 200-byte file could ask for gigabytes.
void check_declared_size(const matvar_t& v, const std::string& file, const std::string& name) {
  std::uint64_t values = 1;
  for (int k = 0; k < v.rank; ++k) {
    const std::uint64_t d = v.dims[k];
    if (d != 0 && values > UINT64_MAX / d) {
      values = UINT64_MAX;
      break;
    }
    values *= d;
  }
  const std::uint64_t most = kMaxExpansion * (file_size(file) + 1024);
  if (values > most / 8) {
    std::string shape;
    for (int k = 0; k < v.rank && k < 8; ++k) shape += (k ? "x" : "") + std::to_string(v.dims[k]);
    throw DataError(name, 0, 0, "declares a " + shape + " array, more than the file can hold (a damaged .mat file?)");
  }
}

// Whether the variable (its header only) is a real 2-D numeric array: what read_mat returns.
bool is_candidate(const matvar_t& v) {
  return numeric_class(v.class_type) && v.isComplex == 0 && v.rank == 2 && v.dims[0] > 0 && v.dims[1] > 0;
}

// The variables of an open .mat file (headers only): all of them, and the real 2-D numeric
// arrays among them, the ones read_mat can return.
struct MatVariables {
  std::vector<std::string> all, candidates;
};

template <typename T>
void widen(const void* data, Eigen::MatrixXd& out) {
  const T* values = static_cast<const T*>(data);
  for (Eigen::Index k = 0; k < out.size(); ++k) out.data()[k] = static_cast<double>(values[k]);
}

// Checks a .mat file's structure before libmatio sees it: a level-5 file's elements, a 7.3 file's
// objects (through libhdf5).
void check_structure(const std::string& file) {
  const std::string head = first_bytes(file, 128);
  if (!is_mat(head)) return;  // Mat_Open reports it
  if (!is_level5(head)) return check_mat73_structure(file, file_size(file));
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(file.c_str(), "rb"), std::fclose);
  if (!in) return;  // Mat_Open reports it
  std::string bytes;
  char buffer[1 << 16];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, in.get())) > 0;) bytes.append(buffer, got);
  if (!is_level5(bytes)) return;  // the file changed since its first bytes were read
  check_level5_structure(file, bytes);
}

MatVariables list_variables(mat_t* mat) {
  MatVariables out;
  for (;;) {
    MatVar v(loaded_matio().Mat_VarReadNextInfo(mat));
    if (!v) break;
    const std::string name = v->name ? v->name : "";
    out.all.push_back(name);
    if (is_candidate(*v)) out.candidates.push_back(name);
  }
  return out;
}

// An open .mat file and the header (not yet the values) of its variable that read_mat returns,
// checked: a real 2-D numeric array no larger than the file can hold.
struct MatMatrix {
  MatFile file;
  MatVar header;
  std::string variable;  // the variable's name in the file
  std::string name;      // how messages name it: "file" or "file:variable"
};

MatMatrix open_matrix(const std::string& file, const std::string& variable) {
  const Matio& lib = matio(file);
  lib.Mat_LogInitFunc("spdfit", quiet_log);
  MatMatrix out{nullptr, nullptr, variable, variable.empty() ? file : file + ":" + variable};
  check_structure(file);
  out.file.reset(lib.Mat_Open(file.c_str(), MAT_ACC_RDONLY));
  if (!out.file) throw DataError(file, 0, 0, "is not a MATLAB .mat file libmatio can read (levels 5 and 7.3 are)");
  const auto its_variables = [](const MatVariables& found) {
    return found.all.empty() ? std::string() : "; its variables: " + listed_names(found.all);
  };
  if (variable.empty()) {
    const MatVariables found = list_variables(out.file.get());
    if (found.all.empty()) {
      throw DataError(file, 0, 0, "holds no variable libmatio can read (a damaged or truncated .mat file?)");
    }
    if (found.candidates.empty()) {
      throw DataError(file, 0, 0,
                      "holds no real 2-D numeric array" + its_variables(found) +
                          " (none is a real numeric matrix: save the data as a 2-D double array)");
    }
    if (found.candidates.size() > 1) {
      throw DataError(file, 0, 0,
                      "holds " + std::to_string(found.candidates.size()) + " 2-D numeric arrays (" +
                          listed_names(found.candidates) + ")" + its_variables(found) + ": name one as " + file + ":NAME");
    }
    out.variable = found.candidates.front();
  }
  out.header.reset(lib.Mat_VarReadInfo(out.file.get(), out.variable.c_str()));
  if (!out.header) {
    if (variable.empty()) throw DataError(out.name, 0, 0, "could not be read (a damaged .mat file?)");
    // Rewind by reopening: list what there is.
    const MatFile again(lib.Mat_Open(file.c_str(), MAT_ACC_RDONLY));
    const MatVariables there = again ? list_variables(again.get()) : MatVariables{};
    if (there.all.empty()) {
      throw DataError(file, 0, 0,
                      "has no variable '" + variable +
                          "' libmatio can read: it lists none at all (a damaged or truncated .mat file?)");
    }
    throw DataError(file, 0, 0, "has no variable '" + variable + "'" + its_variables(there));
  }
  const matvar_t& v = *out.header;
  check_declared_size(v, file, variable.empty() ? out.name : file + ":" + out.variable);
  const std::string& name = out.name;
  if (!numeric_class(v.class_type)) {
    if (v.class_type == MAT_C_EMPTY) {
      throw DataError(name, 0, 0, "has no MATLAB class libmatio knows (no MATLAB_class attribute?), so it is not read");
    }
    static const char* const kClasses[] = {"", "cell", "struct", "object", "char", "sparse"};
    const std::string what = v.class_type <= MAT_C_SPARSE ? kClasses[v.class_type] : "function or opaque";
    throw DataError(name, 0, 0, "is a " + what + " array, not a numeric matrix");
  }
  if (v.isComplex) throw DataError(name, 0, 0, "is complex; spdfit reads real arrays");
  if (v.rank != 2) throw DataError(name, 0, 0, "has " + std::to_string(v.rank) + " dimensions; save a 2-D array");
  if (v.dims[0] == 0 || v.dims[1] == 0) throw DataError(name, 0, 0, "is empty");
  return out;
}

// Values of a numeric class as libmatio reads them, column by column, converted to double.
void widen_class(matio_classes type, const void* data, Eigen::MatrixXd& out) {
  switch (type) {
    case MAT_C_DOUBLE: widen<double>(data, out); break;
    case MAT_C_SINGLE: widen<float>(data, out); break;
    case MAT_C_INT8: widen<std::int8_t>(data, out); break;
    case MAT_C_UINT8: widen<std::uint8_t>(data, out); break;
    case MAT_C_INT16: widen<std::int16_t>(data, out); break;
    case MAT_C_UINT16: widen<std::uint16_t>(data, out); break;
    case MAT_C_INT32: widen<std::int32_t>(data, out); break;
    case MAT_C_UINT32: widen<std::uint32_t>(data, out); break;
    case MAT_C_INT64: widen<std::int64_t>(data, out); break;
    default: widen<std::uint64_t>(data, out); break;
  }
}

}  // namespace mat_file

using namespace mat_file;

Table read_mat(const std::string& file, const std::string& variable, const ReadOptions& options) {
  const MatMatrix matrix = open_matrix(file, variable);
  const MatVar whole(loaded_matio().Mat_VarRead(matrix.file.get(), matrix.variable.c_str()));
  // As its header said (the file may have changed since, or libmatio read it otherwise).
  if (!whole || !whole->data || whole->class_type != matrix.header->class_type || whole->rank != 2 ||
      whole->isComplex || whole->dims[0] != matrix.header->dims[0] || whole->dims[1] != matrix.header->dims[1]) {
    throw DataError(matrix.name, 0, 0, "could not be read (a damaged .mat file?)");
  }
  Table table;
  // MATLAB stores arrays column by column, as Eigen does; a row vector stays a row.
  table.values.resize(static_cast<Eigen::Index>(whole->dims[0]), static_cast<Eigen::Index>(whole->dims[1]));
  widen_class(whole->class_type, whole->data, table.values);
  if (!options.allow_nonfinite) check_npy_finite(table.values, 0, matrix.name);
  return table;
}

struct MatRowBlocks::State {
  MatMatrix matrix;
  std::vector<unsigned char> buffer;
};

MatRowBlocks::MatRowBlocks(const FileSpec& spec) : state_(std::make_unique<State>()) {
  state_->matrix = open_matrix(spec.file, spec.variable);
  const matvar_t& v = *state_->matrix.header;
  // libmatio takes the hyperslab's corner and extent as int.
  if (v.dims[0] > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      v.dims[1] > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw DataError(state_->matrix.name, 0, 0,
                    "has more than 2^31 - 1 rows, more than libmatio reads in row ranges: save it as .npy");
  }
}

MatRowBlocks::~MatRowBlocks() = default;

std::uint64_t MatRowBlocks::rows() const { return state_->matrix.header->dims[0]; }
Eigen::Index MatRowBlocks::columns() const { return static_cast<Eigen::Index>(state_->matrix.header->dims[1]); }
const std::string& MatRowBlocks::name() const { return state_->matrix.name; }

void MatRowBlocks::read(std::uint64_t first, Eigen::Index count, Eigen::MatrixXd* out) {
  matvar_t& v = *state_->matrix.header;
  out->resize(count, columns());
  if (count == 0) return;
  state_->buffer.resize(static_cast<std::size_t>(out->size()) * loaded_matio().Mat_SizeOfClass(v.class_type));
  int start[2] = {static_cast<int>(first), 0};
  int stride[2] = {1, 1};
  int edge[2] = {static_cast<int>(count), static_cast<int>(columns())};
  if (loaded_matio().Mat_VarReadData(state_->matrix.file.get(), &v, state_->buffer.data(), start, stride, edge) != 0) {
    throw DataError(name(), 0, 0,
                    "rows " + std::to_string(first + 1) + " to " + std::to_string(first + count) +
                        " could not be read (a damaged .mat file?)");
  }
  widen_class(v.class_type, state_->buffer.data(), *out);
}

}  // namespace spdfit::io::detail

namespace spdfit::io {

void write_mat(const std::string& path, const Eigen::Ref<const Eigen::MatrixXd>& X, const std::string& name) {
  const detail::Matio& lib = detail::matio(path);
  detail::check_writable(path);  // libmatio says only that it failed, not why
  lib.Mat_LogInitFunc("spdfit", detail::quiet_log);
  detail::MatFile mat(lib.Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5));
  if (!mat) throw DataError(path, 0, 0, "cannot be written as a .mat file");
  Eigen::MatrixXd dense = X;  // columns one after another, as libmatio reads them
  std::size_t dims[2] = {static_cast<std::size_t>(X.rows()), static_cast<std::size_t>(X.cols())};
  detail::MatVar var(
      lib.Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, dense.data(), MAT_F_DONT_COPY_DATA));
  if (!var || lib.Mat_VarWrite(mat.get(), var.get(), MAT_COMPRESSION_NONE) != 0) {
    throw DataError(path, 0, 0, "cannot be written as a .mat file");
  }
}

}  // namespace spdfit::io

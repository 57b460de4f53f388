// MATLAB .mat files through libmatio and NumPy .npz files through libzip: both hold named arrays,
// read whole (a .npz entry is a .npy file, parsed by parse_npy).
#include "containers.hpp"

#include <matio.h>
#include <sys/stat.h>
#include <zip.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "npy_layout.hpp"
#include "parse.hpp"
#include "text_scan.hpp"

namespace spdfit::io::detail {

namespace {

bool exists(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t k = 0; k < names.size() && k < 20; ++k) out += (k ? ", " : "") + names[k];
  if (names.size() > 20) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

struct MatCloser {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct VarFreer {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};
using MatFile = std::unique_ptr<mat_t, MatCloser>;
using MatVar = std::unique_ptr<matvar_t, VarFreer>;

// libmatio prints its warnings and errors to standard error by default; spdfit reports its own.
void quiet_log(int, char*) {}

bool numeric_class(matio_classes c) { return c >= MAT_C_DOUBLE && c <= MAT_C_UINT64; }

// Deflate (level-5 compression, HDF5's filters) expands at most about 1032:1.
constexpr std::uint64_t kMaxExpansion = 1100;

std::uint64_t file_size(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 ? static_cast<std::uint64_t>(info.st_size) : 0;
}

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

template <typename T>
void widen(const void* data, Eigen::MatrixXd& out) {
  const T* values = static_cast<const T*>(data);
  for (Eigen::Index k = 0; k < out.size(); ++k) out.data()[k] = static_cast<double>(values[k]);
}

}  // namespace

FileSpec split_spec(const std::string& path) {
  if (path == "-" || exists(path)) return {path, ""};
  const std::size_t colon = path.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == path.size()) return {path, ""};
  const std::string file = path.substr(0, colon);
  if (!exists(file)) return {path, ""};
  return {file, path.substr(colon + 1)};
}

bool is_mat(std::string_view first) {
  // A 128-byte header (text, subsystem offset, version 0x0100 or 0x0200, endian "IM" or "MI").
  if (first.size() < 128 || first.substr(0, 7) != "MATLAB ") return false;
  const std::string_view endian = first.substr(126, 2);
  return endian == "IM" || endian == "MI";
}

bool is_zip(std::string_view first) { return first.substr(0, 4) == std::string_view("PK\x03\x04", 4); }

std::string first_bytes(const std::string& path, std::size_t count) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return "";
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) return "";
  std::string out(count, '\0');
  out.resize(std::fread(out.data(), 1, count, file.get()));
  return out;
}

std::string read_standard_input() {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const std::size_t got = std::fread(buffer, 1, sizeof buffer, stdin);
    bytes.append(buffer, got);
    if (got < sizeof buffer) break;
  }
  if (std::ferror(stdin)) throw DataError("<stdin>", 0, 0, "read error");
  if (bytes.empty()) throw DataError("<stdin>", 0, 0, "is empty");
  return bytes;
}

bool holds_npy(const std::string& path) {
  int error = 0;
  std::unique_ptr<zip_t, int (*)(zip_t*)> archive(zip_open(path.c_str(), ZIP_RDONLY, &error), zip_close);
  if (!archive) return false;
  const zip_int64_t entries = zip_get_num_entries(archive.get(), 0);
  for (zip_int64_t k = 0; k < entries; ++k) {
    const char* entry = zip_get_name(archive.get(), static_cast<zip_uint64_t>(k), 0);
    const std::string_view name = entry ? entry : "";
    if (name.size() > 4 && name.substr(name.size() - 4) == ".npy") return true;
  }
  return false;
}

namespace {
// The variable `variable` of the open file, its declared size checked before libmatio reads it;
// nothing when there is no such variable.
MatVar read_checked(mat_t* mat, const std::string& file, const std::string& variable, const std::string& name) {
  {
    MatVar info(Mat_VarReadInfo(mat, variable.c_str()));
    if (!info) return nullptr;
    check_declared_size(*info, file, variable.empty() ? name : file + ":" + variable);
  }
  return MatVar(Mat_VarRead(mat, variable.c_str()));
}
}  // namespace

Table read_mat(const std::string& file, const std::string& variable, const ReadOptions& options) {
  Mat_LogInitFunc("spdfit", quiet_log);
  const std::string name = variable.empty() ? file : file + ":" + variable;
  MatFile mat(Mat_Open(file.c_str(), MAT_ACC_RDONLY));
  if (!mat) throw DataError(file, 0, 0, "is not a MATLAB .mat file libmatio can read (levels 5 and 7.3 are)");
  std::vector<std::string> all, candidates;
  MatVar chosen;
  if (variable.empty()) {
    // Headers only, to find the one real 2-D numeric array.
    for (;;) {
      MatVar v(Mat_VarReadNextInfo(mat.get()));
      if (!v) break;
      const std::string v_name = v->name ? v->name : "";
      all.push_back(v_name);
      if (is_candidate(*v)) candidates.push_back(v_name);
    }
    if (candidates.size() != 1) {
      throw DataError(file, 0, 0,
                      (candidates.empty() ? "holds no real 2-D numeric array"
                                          : "holds " + std::to_string(candidates.size()) +
                                                " 2-D numeric arrays (" + joined(candidates) + ")") +
                          (all.empty() ? std::string() : "; its variables: " + joined(all)) +
                          ": name one as " + file + ":NAME");
    }
    chosen = read_checked(mat.get(), file, candidates.front(), name);
  } else {
    chosen = read_checked(mat.get(), file, variable, name);
    if (!chosen) {
      // Rewind by reopening: list what there is.
      MatFile again(Mat_Open(file.c_str(), MAT_ACC_RDONLY));
      while (again) {
        MatVar v{Mat_VarReadNextInfo(again.get())};
        if (!v) break;
        all.push_back(v->name ? v->name : "");
      }
      throw DataError(file, 0, 0, "has no variable '" + variable + "'" +
                                      (all.empty() ? std::string() : "; its variables: " + joined(all)));
    }
  }
  if (!chosen) throw DataError(name, 0, 0, "could not be read (a damaged .mat file?)");
  const matvar_t& v = *chosen;
  if (!numeric_class(v.class_type)) {
    static const char* const kClasses[] = {"empty", "cell", "struct", "object", "char", "sparse"};
    const std::string what = v.class_type <= MAT_C_SPARSE ? kClasses[v.class_type] : "function or opaque";
    throw DataError(name, 0, 0, "is a " + what + " array, not a numeric matrix");
  }
  if (v.isComplex) throw DataError(name, 0, 0, "is complex; spdfit reads real arrays");
  if (v.rank != 2) throw DataError(name, 0, 0, "has " + std::to_string(v.rank) + " dimensions; save a 2-D array");
  if (v.dims[0] == 0 || v.dims[1] == 0) throw DataError(name, 0, 0, "is empty");
  if (!v.data) throw DataError(name, 0, 0, "could not be read (a damaged .mat file?)");
  Table table;
  // MATLAB stores arrays column by column, as Eigen does; a row vector stays a row.
  table.values.resize(static_cast<Eigen::Index>(v.dims[0]), static_cast<Eigen::Index>(v.dims[1]));
  switch (v.class_type) {
    case MAT_C_DOUBLE: widen<double>(v.data, table.values); break;
    case MAT_C_SINGLE: widen<float>(v.data, table.values); break;
    case MAT_C_INT8: widen<std::int8_t>(v.data, table.values); break;
    case MAT_C_UINT8: widen<std::uint8_t>(v.data, table.values); break;
    case MAT_C_INT16: widen<std::int16_t>(v.data, table.values); break;
    case MAT_C_UINT16: widen<std::uint16_t>(v.data, table.values); break;
    case MAT_C_INT32: widen<std::int32_t>(v.data, table.values); break;
    case MAT_C_UINT32: widen<std::uint32_t>(v.data, table.values); break;
    case MAT_C_INT64: widen<std::int64_t>(v.data, table.values); break;
    default: widen<std::uint64_t>(v.data, table.values); break;
  }
  if (!options.allow_nonfinite) check_npy_finite(table.values, 0, name);
  return table;
}

Table read_npz(const std::string& file, const std::string& variable, const ReadOptions& options) {
  int error = 0;
  std::unique_ptr<zip_t, int (*)(zip_t*)> archive(zip_open(file.c_str(), ZIP_RDONLY, &error), zip_close);
  if (!archive) throw DataError(file, 0, 0, "is not a ZIP archive (.npz) libzip can read");
  const zip_int64_t entries = zip_get_num_entries(archive.get(), 0);
  std::vector<std::string> arrays;
  for (zip_int64_t k = 0; k < entries; ++k) {
    const char* entry = zip_get_name(archive.get(), static_cast<zip_uint64_t>(k), 0);
    const std::string entry_name = entry ? entry : "";
    if (entry_name.size() > 4 && entry_name.compare(entry_name.size() - 4, 4, ".npy") == 0) {
      arrays.push_back(entry_name.substr(0, entry_name.size() - 4));
    }
  }
  std::string key = variable;
  if (key.size() > 4 && key.compare(key.size() - 4, 4, ".npy") == 0) key.resize(key.size() - 4);
  if (key.empty()) {
    if (arrays.size() != 1) {
      throw DataError(file, 0, 0,
                      arrays.empty() ? "holds no .npy arrays (is it an .npz file?)"
                                     : "holds " + std::to_string(arrays.size()) + " arrays (" + joined(arrays) +
                                           "): name one as " + file + ":" + arrays.front());
    }
    key = arrays.front();
  }
  const std::string name = file + ":" + key;
  zip_stat_t info;
  zip_stat_init(&info);
  if (zip_stat(archive.get(), (key + ".npy").c_str(), 0, &info) != 0) {
    throw DataError(file, 0, 0, "has no array '" + key + "'; its arrays: " + joined(arrays));
  }
  // The declared size is checked against the archive before it is trusted with an allocation
  // (a ZIP entry that claims far more than deflate's ratio of its compressed size is damaged).
  if (!(info.valid & ZIP_STAT_SIZE) ||
      ((info.valid & ZIP_STAT_COMP_SIZE) && info.size > kMaxExpansion * (info.comp_size + 1024))) {
    throw DataError(name, 0, 0, "has a damaged size in the archive");
  }
  std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> entry(zip_fopen(archive.get(), (key + ".npy").c_str(), 0),
                                                          zip_fclose);
  if (!entry) throw DataError(name, 0, 0, "cannot be read from the archive");
  std::string bytes(static_cast<std::size_t>(info.size), '\0');
  std::size_t got = 0;
  while (got < bytes.size()) {
    const zip_int64_t n = zip_fread(entry.get(), bytes.data() + got, bytes.size() - got);
    if (n <= 0) throw DataError(name, 0, 0, "cannot be read from the archive (damaged or truncated)");
    got += static_cast<std::size_t>(n);
  }
  Table table;
  table.values = parse_npy(bytes, name, options);
  return table;
}

void write_mat(const std::string& file, const std::string& name, const Eigen::MatrixXd& X) {
  Mat_LogInitFunc("spdfit", quiet_log);
  MatFile mat(Mat_CreateVer(file.c_str(), nullptr, MAT_FT_MAT5));
  if (!mat) throw DataError(file, 0, 0, "cannot be written as a .mat file");
  std::size_t dims[2] = {static_cast<std::size_t>(X.rows()), static_cast<std::size_t>(X.cols())};
  MatVar var(Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, const_cast<double*>(X.data()),
                           MAT_F_DONT_COPY_DATA));
  if (!var || Mat_VarWrite(mat.get(), var.get(), MAT_COMPRESSION_NONE) != 0) {
    throw DataError(file, 0, 0, "cannot be written as a .mat file");
  }
}

}  // namespace spdfit::io::detail

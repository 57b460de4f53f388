// NumPy .npz files through libzip: a ZIP archive of .npy files, each parsed by parse_npy.
#include "containers.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "file_error.hpp"
#include "format_libraries.hpp"
#include "mat_structure.hpp"
#include "npy_layout.hpp"
#include "parse.hpp"

namespace spdfit::io::detail {

namespace {

bool ends_with_npy(std::string_view name) { return name.size() > 4 && name.substr(name.size() - 4) == ".npy"; }

using ZipArchive = std::unique_ptr<zip_t, int (*)(zip_t*)>;

ZipArchive open_zip(const std::string& path) {
  const Libzip& zip = libzip(path);
  int error = 0;
  return ZipArchive(zip.zip_open(path.c_str(), ZIP_RDONLY, &error), zip.zip_close);
}

// The arrays of a .npz archive: its entries that are .npy files, named without ".npy".
std::vector<std::string> npy_entries(zip_t* archive) {
  std::vector<std::string> arrays;
  const Libzip& zip = loaded_libzip();
  const zip_int64_t entries = zip.zip_get_num_entries(archive, 0);
  for (zip_int64_t k = 0; k < entries; ++k) {
    const char* entry = zip.zip_get_name(archive, static_cast<zip_uint64_t>(k), 0);
    const std::string_view name = entry ? entry : "";
    if (ends_with_npy(name)) arrays.emplace_back(name.substr(0, name.size() - 4));
  }
  return arrays;
}

}  // namespace

// Whether the ZIP archive holds .npy entries (a NumPy .npz, not an .xlsx workbook).
bool holds_npy(const std::string& path) {
  const ZipArchive archive = open_zip(path);
  return archive && !npy_entries(archive.get()).empty();
}

Table read_npz(const std::string& file, const std::string& variable, const ReadOptions& options) {
  const ZipArchive archive = open_zip(file);
  if (!archive) throw DataError(file, 0, 0, "is not a ZIP archive (.npz) libzip can read (damaged or truncated?)");
  const std::vector<std::string> arrays = npy_entries(archive.get());
  std::string key = variable;
  if (ends_with_npy(key)) key.resize(key.size() - 4);
  if (key.empty()) {
    if (arrays.size() != 1) {
      throw DataError(file, 0, 0,
                      arrays.empty() ? "holds no .npy arrays (is it an .npz file?)"
                                     : "holds " + std::to_string(arrays.size()) + " arrays (" + listed_names(arrays) +
                                           "): name one as " + file + ":" + arrays.front());
    }
    key = arrays.front();
  }
  const std::string name = file + ":" + key;
  zip_stat_t info;
  const Libzip& zip = loaded_libzip();
  zip.zip_stat_init(&info);
  if (zip.zip_stat(archive.get(), (key + ".npy").c_str(), 0, &info) != 0) {
    throw DataError(file, 0, 0, "has no array '" + key + "'; its arrays: " + listed_names(arrays));
  }
  // The declared size is checked against the archive before it is trusted with an allocation
  // (a ZIP entry that claims far more than deflate's ratio of its compressed size is damaged).
  if (!(info.valid & ZIP_STAT_SIZE) ||
      ((info.valid & ZIP_STAT_COMP_SIZE) && info.size > kMaxExpansion * (info.comp_size + 1024))) {
    throw DataError(name, 0, 0, "has a damaged size in the archive");
  }
  std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> entry(
      zip.zip_fopen(archive.get(), (key + ".npy").c_str(), 0), zip.zip_fclose);
  if (!entry) throw DataError(name, 0, 0, "cannot be read from the archive");
  std::string bytes(static_cast<std::size_t>(info.size), '\0');
  std::size_t got = 0;
  while (got < bytes.size()) {
    const zip_int64_t n = zip.zip_fread(entry.get(), bytes.data() + got, bytes.size() - got);
    if (n <= 0) throw DataError(name, 0, 0, "cannot be read from the archive (damaged or truncated)");
    got += static_cast<std::size_t>(n);
  }
  Table table;
  table.values = parse_npy(bytes, name, options);
  return table;
}

}  // namespace spdfit::io::detail

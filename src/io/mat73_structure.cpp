// Walks a 7.3 .mat file's objects through libhdf5 (libmatio's own) and bounds each declared
// shape by the file's size before libmatio allocates it.
#include "mat73_structure.hpp"

#include <algorithm>
#include <string>

#include "hdf5_library.hpp"
#include "mat_structure.hpp"
#include "spdfit/io.hpp"

namespace spdfit::io::detail {

namespace {

// What a walk of the file found: the first object that declares more than the file can hold.
struct Walk {
  const Hdf5* h5 = nullptr;
  std::uint64_t limit = 0;  // bytes
  std::string object;       // the object being visited, as a path from the root
  std::string finding;
};

// At least 16 bytes a point: a cell's pointer and reference in libmatio.
constexpr std::uint64_t kMinBytesPerPoint = 16;

bool too_big(std::uint64_t points, std::uint64_t size, std::uint64_t limit) {
  const std::uint64_t per_point = std::max(size, kMinBytesPerPoint);
  return size > limit || (points != 0 && per_point > limit / points);
}

std::string declares(std::uint64_t points, std::uint64_t size) {
  return "declares " + std::to_string(points) + (points == 1 ? " value" : " values") + " of " + std::to_string(size) +
         " bytes, more than the file can hold";
}

// The points of a dataspace and the size of a datatype (closing both); -1 points when unknown.
std::int64_t points_of(const Hdf5& h5, hid_t space, hid_t type, std::uint64_t* size) {
  const hssize_t points = space >= 0 ? h5.H5Sget_simple_extent_npoints(space) : -1;
  *size = type >= 0 ? h5.H5Tget_size(type) : 0;
  if (space >= 0) h5.H5Sclose(space);
  if (type >= 0) h5.H5Tclose(type);
  return points;
}

herr_t check_attribute(hid_t location, const char* name, const H5A_info_t*, void* data) {
  Walk& walk = *static_cast<Walk*>(data);
  const Hdf5& h5 = *walk.h5;
  const hid_t attribute = h5.H5Aopen(location, name, H5P_DEFAULT);
  if (attribute < 0) return 0;  // libmatio says what it cannot read
  std::uint64_t size = 0;
  const std::int64_t points = points_of(h5, h5.H5Aget_space(attribute), h5.H5Aget_type(attribute), &size);
  h5.H5Aclose(attribute);
  if (points >= 0 && too_big(static_cast<std::uint64_t>(points), size, walk.limit)) {
    walk.finding = "attribute '" + std::string(name) + "' of '/" + walk.object + "' " +
                   declares(static_cast<std::uint64_t>(points), size);
    return 1;  // stops the walk
  }
  return 0;
}

herr_t check_object(hid_t location, const char* name, const H5O_info_t* info, void* data) {
  Walk& walk = *static_cast<Walk*>(data);
  const Hdf5& h5 = *walk.h5;
  walk.object = std::string(name) == "." ? "" : name;
  const hid_t object = h5.H5Oopen(location, name, H5P_DEFAULT);
  if (object < 0) return 0;
  herr_t status = h5.H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, check_attribute, data);
  if (status == 0 && info->type == H5O_TYPE_DATASET) {
    std::uint64_t size = 0;
    const std::int64_t points = points_of(h5, h5.H5Dget_space(object), h5.H5Dget_type(object), &size);
    if (points >= 0 && too_big(static_cast<std::uint64_t>(points), size, walk.limit)) {
      walk.finding = "dataset '/" + walk.object + "' " + declares(static_cast<std::uint64_t>(points), size);
      status = 1;
    }
  }
  h5.H5Oclose(object);
  return status > 0 ? 1 : 0;
}

}  // namespace

void check_mat73_structure(const std::string& file, std::uint64_t file_size) {
  const Hdf5& h5 = hdf5(file);
  h5.H5open();
  // libhdf5 prints its errors' stacks on standard error by default; spdfit reports its own.
  H5E_auto2_t printer = nullptr;
  void* printer_data = nullptr;
  h5.H5Eget_auto2(H5E_DEFAULT, &printer, &printer_data);
  h5.H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  Walk walk;
  walk.h5 = &h5;
  walk.limit = std::uint64_t{kMaxExpansion} * (file_size + 1024);
  herr_t status = 0;
  const hid_t handle = h5.H5Fopen(file.c_str(), 0u /* H5F_ACC_RDONLY */, H5P_DEFAULT);
  if (handle >= 0) {
    status = h5.H5Ovisit2(handle, H5_INDEX_NAME, H5_ITER_NATIVE, check_object, &walk, H5O_INFO_BASIC);
    h5.H5Fclose(handle);
  }
  h5.H5Eset_auto2(H5E_DEFAULT, printer, printer_data);
  if (!walk.finding.empty()) throw DataError(file, 0, 0, "is a damaged .mat file (" + walk.finding + ")");
  if (status < 0) throw DataError(file, 0, 0, "is a damaged .mat file (libhdf5 cannot walk its objects)");
}

}  // namespace spdfit::io::detail

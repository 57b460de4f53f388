// Internal: the functions of libhdf5 that check a MATLAB 7.3 file before libmatio reads it, from
// the libhdf5 libmatio loaded (the same library, found through libmatio's dependencies). Apart
// from format_libraries.hpp because hdf5.h is not on every include path (only the library's).
#pragma once

#include <hdf5.h>

#include <string>

namespace spdfit::io::detail {

#define SPDFIT_HDF5_FUNCTIONS(F)                                                                   \
  F(H5open) F(H5Eget_auto2) F(H5Eset_auto2) F(H5Fopen) F(H5Fclose) F(H5Ovisit2) F(H5Oopen)         \
  F(H5Oclose) F(H5Aiterate2) F(H5Aopen) F(H5Aclose) F(H5Aget_space) F(H5Aget_type) F(H5Dget_space) \
  F(H5Dget_type) F(H5Sget_simple_extent_npoints) F(H5Sclose) F(H5Tget_size) F(H5Tclose)

#define SPDFIT_POINTER_TO(function) decltype(&::function) function = nullptr;
struct Hdf5 {
  SPDFIT_HDF5_FUNCTIONS(SPDFIT_POINTER_TO)
};
#undef SPDFIT_POINTER_TO

/// libhdf5's functions, loaded at the first call as matio(file) loads libmatio's. Throws
/// DataError naming `file` when they cannot be loaded.
const Hdf5& hdf5(const std::string& file);

}  // namespace spdfit::io::detail

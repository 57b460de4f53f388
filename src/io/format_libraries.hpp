// Internal: libmatio (.mat files) and libzip (.npz archives), opened at their first use instead
// of at every start of a program. Linked in, they and what they pull in (libhdf5, and through it
// curl, TLS, Kerberos and LDAP: most of the shared objects the command line loaded) took about
// half of its start, paid by every run, most of which read no .mat or .npz file
// (bench/startup_times.sh measures it; docs/performance.md has the numbers).
#pragma once

#include <matio.h>
#include <zip.h>

#include <cstddef>
#include <string>

namespace spdfit::io::detail {

// The functions spdfit calls, each a pointer of the type its header declares: the library's own
// declarations, so a signature cannot drift from the one compiled against.
#define SPDFIT_MATIO_FUNCTIONS(F)                                                                  \
  F(Mat_Close) F(Mat_CreateVer) F(Mat_LogInitFunc) F(Mat_Open) F(Mat_SizeOfClass) F(Mat_VarCreate) \
  F(Mat_VarFree) F(Mat_VarRead) F(Mat_VarReadData) F(Mat_VarReadInfo) F(Mat_VarReadNextInfo) F(Mat_VarWrite)
#define SPDFIT_LIBZIP_FUNCTIONS(F)                                                                 \
  F(zip_close) F(zip_fclose) F(zip_fopen) F(zip_fread) F(zip_get_name) F(zip_get_num_entries)      \
  F(zip_open) F(zip_stat) F(zip_stat_init)

#define SPDFIT_POINTER_TO(function) decltype(&::function) function = nullptr;
struct Matio {
  SPDFIT_MATIO_FUNCTIONS(SPDFIT_POINTER_TO)
};
struct Libzip {
  SPDFIT_LIBZIP_FUNCTIONS(SPDFIT_POINTER_TO)
};
#undef SPDFIT_POINTER_TO

/// libmatio's functions, the library loaded at the first call (thread-safe; once per process).
/// Throws DataError naming `file` ("reading it needs libmatio ...") when the library or one of
/// its functions cannot be loaded. Cost: the first call loads the libraries, later ones nothing.
const Matio& matio(const std::string& file);

/// libmatio's functions once matio(file) has returned them (for closing files and freeing
/// variables that came from it): a precondition, not checked again.
const Matio& loaded_matio();

/// libzip's functions, as matio(file).
const Libzip& libzip(const std::string& file);

/// libzip's functions once libzip(file) has returned them.
const Libzip& loaded_libzip();

/// Opens the shared library `soname` (kept open for the process) and writes the address of each
/// of `names` to `addresses` (in order): true, or false with the loader's reason in `*error`. The
/// libraries above are opened with it; declared here so that its failure can be tested.
bool open_library(const std::string& soname, const char* const* names, std::size_t count, void** addresses,
                  std::string* error);

}  // namespace spdfit::io::detail

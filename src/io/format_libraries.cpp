#include "format_libraries.hpp"
#include "hdf5_library.hpp"

#include <dlfcn.h>

#include <mutex>

#include "spdfit/io.hpp"

namespace spdfit::io::detail {

bool open_library(const std::string& soname, const char* const* names, std::size_t count, void** addresses,
                  std::string* error) {
  // dlerror's message is global state: read under one lock with the calls that set it.
  static std::mutex loader;
  const std::lock_guard<std::mutex> lock(loader);
  void* library = ::dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char* why = ::dlerror();
    *error = why ? why : "cannot be opened";
    return false;
  }
  for (std::size_t k = 0; k < count; ++k) {
    ::dlerror();
    addresses[k] = ::dlsym(library, names[k]);
    if (!addresses[k]) {
      const char* why = ::dlerror();
      *error = soname + " has no function " + names[k] + (why ? std::string(" (") + why + ")" : std::string());
      ::dlclose(library);
      return false;
    }
  }
  return true;  // never closed: the functions stay in use until the process ends
}

namespace {

// The loaded functions, or why they are not: decided once, at the first call.
template <typename Api>
struct Loaded {
  Api api;
  std::string error;
};

// Opens `soname` and hands the addresses of `names` to store(api, addresses).
template <typename Api, std::size_t N, typename Store>
Loaded<Api> load(const char* soname, const char* const (&names)[N], Store store) {
  void* addresses[N] = {};
  Loaded<Api> out;
  if (open_library(soname, names, N, addresses, &out.error)) store(out.api, addresses);
  return out;
}

#define SPDFIT_NAME_OF(function) #function,
#define SPDFIT_STORE(function) api.function = reinterpret_cast<decltype(api.function)>(addresses[k++]);

Loaded<Matio> load_matio() {
  static constexpr const char* kNames[] = {SPDFIT_MATIO_FUNCTIONS(SPDFIT_NAME_OF)};
  return load<Matio>(SPDFIT_MATIO_SONAME, kNames, [](Matio& api, void* const* addresses) {
    std::size_t k = 0;
    SPDFIT_MATIO_FUNCTIONS(SPDFIT_STORE)
  });
}

// dlsym on libmatio's handle finds the functions of the libraries it depends on: its libhdf5.
Loaded<Hdf5> load_hdf5() {
  static constexpr const char* kNames[] = {SPDFIT_HDF5_FUNCTIONS(SPDFIT_NAME_OF)};
  return load<Hdf5>(SPDFIT_MATIO_SONAME, kNames, [](Hdf5& api, void* const* addresses) {
    std::size_t k = 0;
    SPDFIT_HDF5_FUNCTIONS(SPDFIT_STORE)
  });
}

Loaded<Libzip> load_libzip() {
  static constexpr const char* kNames[] = {SPDFIT_LIBZIP_FUNCTIONS(SPDFIT_NAME_OF)};
  return load<Libzip>(SPDFIT_LIBZIP_SONAME, kNames, [](Libzip& api, void* const* addresses) {
    std::size_t k = 0;
    SPDFIT_LIBZIP_FUNCTIONS(SPDFIT_STORE)
  });
}

#undef SPDFIT_NAME_OF
#undef SPDFIT_STORE

const Loaded<Matio>& matio_once() {
  static const Loaded<Matio> loaded = load_matio();
  return loaded;
}

const Loaded<Hdf5>& hdf5_once() {
  static const Loaded<Hdf5> loaded = load_hdf5();
  return loaded;
}

const Loaded<Libzip>& libzip_once() {
  static const Loaded<Libzip> loaded = load_libzip();
  return loaded;
}

}  // namespace

const Matio& matio(const std::string& file) {
  const Loaded<Matio>& loaded = matio_once();
  if (!loaded.error.empty()) {
    throw DataError(file, 0, 0, "cannot be read or written: .mat files need libmatio, which did not load: " +
                                    loaded.error);
  }
  return loaded.api;
}

const Matio& loaded_matio() { return matio_once().api; }

const Hdf5& hdf5(const std::string& file) {
  const Loaded<Hdf5>& loaded = hdf5_once();
  if (!loaded.error.empty()) {
    throw DataError(file, 0, 0, "cannot be read: MATLAB 7.3 files need libhdf5 (through libmatio), which did not load: " +
                                    loaded.error);
  }
  return loaded.api;
}

const Libzip& libzip(const std::string& file) {
  const Loaded<Libzip>& loaded = libzip_once();
  if (!loaded.error.empty()) {
    throw DataError(file, 0, 0, "cannot be read: .npz archives need libzip, which did not load: " + loaded.error);
  }
  return loaded.api;
}

const Libzip& loaded_libzip() { return libzip_once().api; }

}  // namespace spdfit::io::detail

// MPI for the distributed fit: the world's setup, from the plugin spdfit-mpi.so (mpi_session.hpp)
// opened only under an MPI launcher.
#include "mpi_world.hpp"

#include <dlfcn.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "mpi_session.hpp"
#include "spdfit/blas.hpp"
#include "spdfit/version.hpp"

namespace spdfit::cli {

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

namespace {

#ifdef SPDFIT_HAVE_MPI

// The folder of this program's file (/proc/self/exe), with a trailing slash.
std::string program_folder() {
  std::vector<char> path(4096);
  const ssize_t length = ::readlink("/proc/self/exe", path.data(), path.size() - 1);
  if (length <= 0) return "";
  const std::string file(path.data(), static_cast<std::size_t>(length));
  return file.substr(0, file.rfind('/') + 1);
}

// The plugin beside the program (the build tree) or where the install puts it, relative to the
// program (SPDFIT_MPI_PLUGIN_DIR_FROM_BIN); kept open for the process.
std::unique_ptr<MpiSession> start_session() {
  const std::string folder = program_folder();
  std::string tried;
  for (const std::string& path :
       {folder + SPDFIT_MPI_PLUGIN, folder + SPDFIT_MPI_PLUGIN_DIR_FROM_BIN + SPDFIT_MPI_PLUGIN}) {
    void* plugin = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!plugin) {
      const char* why = ::dlerror();
      tried += "\n  " + (why ? std::string(why) : path);
      continue;
    }
    using Version = const char* (*)();
    using Start = MpiSession* (*)(std::string*);
    const auto version = reinterpret_cast<Version>(::dlsym(plugin, kMpiSessionVersion));
    const auto start = reinterpret_cast<Start>(::dlsym(plugin, kMpiSessionStart));
    if (!version || !start || std::strcmp(version(), kVersion) != 0) {
      throw std::runtime_error(path + " is not the MPI plugin of this spdfit (" + kVersion +
                               ", MPI session interface " + kMpiSessionStart +
                               "): reinstall or rebuild spdfit");
    }
    std::string error;
    std::unique_ptr<MpiSession> session(start(&error));
    if (!session) throw std::runtime_error(error);
    return session;
  }
  throw std::runtime_error("started by an MPI launcher, but MPI's part of spdfit (" +
                           std::string(SPDFIT_MPI_PLUGIN) + ") could not be loaded:" + tried);
}

#endif

}  // namespace

MpiWorld::MpiWorld() {
  if (!launched_by_mpi()) return;
#ifdef SPDFIT_HAVE_MPI
  session_ = start_session();
  active_ = true;
  rank_ = session_->rank();
  size_ = session_->size();
  // mpirun binds each process to cores of its own by default (to one core when K <= 2): more
  // threads than the cores it may run on would only take turns.
  const unsigned cores = std::max(1U, std::thread::hardware_concurrency());
  threads_ = std::max(1U, cores / static_cast<unsigned>(std::max(1, session_->processes_on_node())));
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) == 0) {
    threads_ = std::min(threads_, std::max(1U, static_cast<unsigned>(CPU_COUNT(&allowed))));
  }
  set_blas_threads(static_cast<int>(threads_));
#else
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (size == nullptr) size = std::getenv("PMI_SIZE");
  if (size != nullptr && std::atoi(size) > 1) {
    throw std::runtime_error(
        "this spdfit was built without MPI (SPDFIT_MPI off), so it cannot run under mpirun "
        "with several processes");
  }
#endif
}

MpiWorld::~MpiWorld() = default;  // the session, if any, ends MPI

Channel& MpiWorld::channel() {
  if (!session_) throw std::logic_error("MpiWorld::channel: MPI is not running");
  return session_->channel();
}

}  // namespace spdfit::cli

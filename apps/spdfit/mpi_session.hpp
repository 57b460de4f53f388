// The MPI side of `mpirun -n K spdfit fit --stream`: a plugin (spdfit-mpi.so, built from
// apps/mpi/) that the command line opens only when an MPI launcher started it. Linked into the
// command line, Open MPI's libraries (libmpi, libopen-rte, libopen-pal, hwloc, libevent) slowed
// every start, a run under mpirun or not (bench/startup_times.sh).
#pragma once

#include <string>

#include "spdfit/distributed.hpp"

namespace spdfit::cli {

/// MPI, initialized: the world's processes and the distributed fit's channel between them.
class MpiSession {
 public:
  virtual ~MpiSession() = default;  ///< frees the channel, then MPI_Finalize
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// The processes on this process's node (which share its cores).
  virtual int processes_on_node() const = 0;
  virtual Channel& channel() = 0;
};

}  // namespace spdfit::cli

/// The plugin's entry points, found with dlsym by the names below, so that a plugin left from
/// another build is refused instead of called through another interface.
/// spdfit_mpi_session_start_v1: MPI_Init_thread and the session (the caller deletes it to end
/// MPI), or nullptr with the reason in `*error`; the number is the interface's, raised whenever
/// MpiSession or Channel changes. spdfit_mpi_session_version: spdfit::kVersion as the plugin was
/// built, which the program checks against its own.
extern "C" spdfit::cli::MpiSession* spdfit_mpi_session_start_v1(std::string* error);
extern "C" const char* spdfit_mpi_session_version();

namespace spdfit::cli {
inline constexpr const char* kMpiSessionStart = "spdfit_mpi_session_start_v1";
inline constexpr const char* kMpiSessionVersion = "spdfit_mpi_session_version";
}  // namespace spdfit::cli

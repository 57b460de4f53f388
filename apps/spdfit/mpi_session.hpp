// The MPI side of `mpirun -n K spdfit fit --stream`: a plugin (spdfit-mpi.so, built from
// apps/mpi/) that the command line opens only when an MPI launcher started it. Linked into the
// command line, Open MPI's libraries (libmpi, libopen-rte, libopen-pal, hwloc, libevent) took
// about 2 ms of every start, a run under mpirun or not (issue 19).
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

/// The plugin's one entry point, named kMpiSessionStart for dlsym: MPI_Init_thread and the
/// session (the caller deletes it to end MPI), or nullptr with the reason in `*error`.
extern "C" spdfit::cli::MpiSession* spdfit_mpi_session_start(std::string* error);

namespace spdfit::cli {
inline constexpr const char* kMpiSessionStart = "spdfit_mpi_session_start";
}  // namespace spdfit::cli

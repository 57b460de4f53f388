// Running under an MPI launcher (mpirun): MPI is loaded (the plugin spdfit-mpi.so) and
// initialized only then, so that spdfit started alone pays nothing for it (MPI_Init takes about
// 0.3 s; loading Open MPI's libraries 1.5–2 ms).
#pragma once

#include <memory>
#include <string>

#include "spdfit/distributed.hpp"

namespace spdfit::cli {

class MpiSession;

/// The processes spdfit runs among when started by an MPI launcher: MPI_Init at construction
/// and MPI_Finalize at destruction.
class MpiWorld {
 public:
  /// Initializes MPI when the environment says an MPI launcher started this process (Open MPI's
  /// OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK, MPICH's PMI_RANK); otherwise one process, no MPI.
  /// Throws std::runtime_error when launched so but built without MPI (and more than one process),
  /// or when the plugin cannot be loaded or MPI not initialized.
  MpiWorld();
  ~MpiWorld();
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  bool active() const { return active_; }  ///< started by an MPI launcher, MPI initialized
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Threads each process should use: the cores divided among the processes on its node.
  unsigned threads_per_process() const { return threads_; }
  /// The channel of the distributed fit (valid while this lives); needs active().
  Channel& channel();

 private:
  bool active_ = false;
  int rank_ = 0;
  int size_ = 1;
  unsigned threads_ = 0;
  std::unique_ptr<MpiSession> session_;
};

/// Whether the environment says an MPI launcher started this process.
bool launched_by_mpi();

}  // namespace spdfit::cli

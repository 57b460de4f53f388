// The streaming fit on several processes (MPI ranks, or the workers of any engine): each process
// reads its own range of rows of A and B, and the processes' triangular factors are merged
// along a fixed binary tree (TSQR) into the factor of all the rows.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "spdfit/fit_options.hpp"
#include "spdfit/fit_request.hpp"
#include "spdfit/fit_result.hpp"
#include "spdfit/io.hpp"
#include "spdfit/method.hpp"
#include "spdfit/stream.hpp"

namespace spdfit {

/// How the processes of a distributed fit reach each other. The command line implements it with
/// MPI (under mpirun); an engine of one's own, or a test, implements it likewise. Every process
/// makes the same collective calls in the same order.
class Channel {
 public:
  virtual ~Channel() = default;
  virtual int rank() const = 0;  ///< this process, 0 .. size() - 1
  virtual int size() const = 0;  ///< the number of processes
  /// Every process's `mine`, in rank order (collective).
  virtual std::vector<std::string> all_gather(const std::string& mine) = 0;
  /// Sends bytes to process `to`, which receives them with receive(rank()).
  virtual void send(int to, const std::string& bytes) = 0;
  virtual std::string receive(int from) = 0;
  /// Tells the other processes that this one has failed, without waiting for them, so that they
  /// stop reading at their next block instead of reading to their end.
  virtual void announce_failure() = 0;
  /// Whether another process has announced a failure (without waiting).
  virtual bool failure_announced() = 0;
  /// Called on every process once all know the outcome, with the processes that announced a
  /// failure, in rank order: an implementation whose announcements are messages receives them here.
  virtual void settle(const std::vector<int>& announced) { static_cast<void>(announced); }
};

/// What a distributed fit gives.
struct DistributedFit {
  /// The estimate, on process 0; empty on the others.
  std::optional<FitResult> result;
  /// The rows each process read, in rank order (on every process).
  std::vector<std::uint64_t> rows_per_process;
};

/// fit_files(a_path, b_path, method, options, stream, read) with A and B split among the
/// channel's processes by rows: process k reads rows [m k / K, m (k + 1) / K) of both files
/// (rounded to whole groups of rows for the streaming bootstrap, options.bootstrap > 0), found
/// for text files by a counting pass (each process scans its K-th of each file's bytes for line
/// ends, minding blank lines, comments and the header), for .npy files from their headers. The
/// factors merge along a binary tree in rank order (for a given K the result is the same run to
/// run); the estimate is fit_files' with stream to rounding, and the same method choice for
/// auto. Other formats (.mat, .npz, standard input) cannot be split: a DataError when K > 1.
///
/// Every process is called alike. A failure on any process (bad data, an unreadable file) ends
/// every process at its next block: each throws the same exception, the first failure in rank
/// (that is, file) order, as io::DataError naming the file, line and column, or
/// std::invalid_argument on invalid options. Cost per process: O(m n^2 / K) plus a scan of
/// 2 / K of each text file's bytes, and log2 K merges of O((n + d)^3).
DistributedFit fit_files_distributed(const std::string& a_path, const std::string& b_path, Method method,
                                     const FitOptions& options, const StreamOptions& stream,
                                     const io::ReadOptions& read, Channel& channel);

/// The same, as the request says (its method, options, stream options and read options; the
/// request streams whether or not request.stream is set, as every distributed fit does).
DistributedFit fit_files_distributed(const std::string& a_path, const std::string& b_path,
                                     const FitRequest& request, Channel& channel);

}  // namespace spdfit

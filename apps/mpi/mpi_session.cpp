// The plugin spdfit-mpi.so: MPI's world and a Channel over MPI's C interface, for the command
// line's distributed fit (apps/spdfit/mpi_session.hpp says why it is a plugin).
#include "mpi_session.hpp"
#include "spdfit/version.hpp"

#include <mpi.h>

#include <cstdint>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace spdfit::cli {
namespace {

[[noreturn]] void mpi_failed(const char* call) { throw std::runtime_error(std::string("MPI: ") + call + " failed"); }

void check(int code, const char* call) {
  if (code != MPI_SUCCESS) mpi_failed(call);
}

constexpr int kDataTag = 1;
constexpr int kFailureTag = 2;

// Messages over MPI_COMM_WORLD for the data; failures are announced on a communicator of their
// own, so that polling for them never takes a data message.
class MpiChannel final : public Channel {
 public:
  MpiChannel(int rank, int size) : rank_(rank), size_(size) {
    check(MPI_Comm_dup(MPI_COMM_WORLD, &failures_), "MPI_Comm_dup");
  }
  ~MpiChannel() override { MPI_Comm_free(&failures_); }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<std::string> all_gather(const std::string& mine) override {
    const int bytes = as_count(mine.size());
    std::vector<int> sizes(static_cast<std::size_t>(size_));
    check(MPI_Allgather(&bytes, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
    std::vector<int> offsets(sizes.size());
    std::int64_t total = 0;
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      offsets[k] = as_count(static_cast<std::size_t>(total));
      total += sizes[k];
    }
    std::string all(static_cast<std::size_t>(total), '\0');
    check(MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE,
                         MPI_COMM_WORLD),
          "MPI_Allgatherv");
    std::vector<std::string> out;
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      out.push_back(all.substr(static_cast<std::size_t>(offsets[k]), static_cast<std::size_t>(sizes[k])));
    }
    return out;
  }

  void send(int to, const std::string& bytes) override {
    check(MPI_Send(bytes.data(), as_count(bytes.size()), MPI_BYTE, to, kDataTag, MPI_COMM_WORLD), "MPI_Send");
  }

  std::string receive(int from) override {
    MPI_Status status;
    check(MPI_Probe(from, kDataTag, MPI_COMM_WORLD, &status), "MPI_Probe");
    int bytes = 0;
    check(MPI_Get_count(&status, MPI_BYTE, &bytes), "MPI_Get_count");
    std::string out(static_cast<std::size_t>(bytes), '\0');
    check(MPI_Recv(out.data(), bytes, MPI_BYTE, from, kDataTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
    return out;
  }

  void announce_failure() override {
    for (int k = 0; k < size_; ++k) {
      if (k == rank_) continue;
      MPI_Request request;
      check(MPI_Isend(&kNotice, 1, MPI_BYTE, k, kFailureTag, failures_, &request), "MPI_Isend");
      announcements_.push_back(request);
    }
  }

  bool failure_announced() override {
    int flag = 0;
    check(MPI_Iprobe(MPI_ANY_SOURCE, kFailureTag, failures_, &flag, MPI_STATUS_IGNORE), "MPI_Iprobe");
    return flag != 0;
  }

  // Every announcement sent is received, so that none is left pending at MPI_Finalize.
  void settle(const std::vector<int>& announced) override {
    for (int k : announced) {
      if (k == rank_) continue;
      char notice = 0;
      check(MPI_Recv(&notice, 1, MPI_BYTE, k, kFailureTag, failures_, MPI_STATUS_IGNORE), "MPI_Recv");
    }
    if (!announcements_.empty()) {
      check(MPI_Waitall(static_cast<int>(announcements_.size()), announcements_.data(), MPI_STATUSES_IGNORE),
            "MPI_Waitall");
      announcements_.clear();
    }
  }

 private:
  static int as_count(std::size_t bytes) {
    if (bytes > static_cast<std::size_t>(INT32_MAX)) throw std::runtime_error("MPI: a message above 2 GiB");
    return static_cast<int>(bytes);
  }

  static constexpr char kNotice = 1;
  int rank_, size_;
  MPI_Comm failures_ = MPI_COMM_NULL;
  std::vector<MPI_Request> announcements_;
};

class WorldSession final : public MpiSession {
 public:
  WorldSession() {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    try {
      check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
      check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
      MPI_Comm node;
      check(MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node),
            "MPI_Comm_split_type");
      MPI_Comm_size(node, &on_node_);
      MPI_Comm_free(&node);
      channel_ = std::make_unique<MpiChannel>(rank_, size_);
    } catch (...) {
      MPI_Finalize();
      throw;
    }
  }
  ~WorldSession() override {
    channel_.reset();  // frees its communicator before MPI ends
    MPI_Finalize();
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int processes_on_node() const override { return on_node_; }
  Channel& channel() override { return *channel_; }

 private:
  int rank_ = 0, size_ = 1, on_node_ = 1;
  std::unique_ptr<MpiChannel> channel_;
};

}  // namespace
}  // namespace spdfit::cli

extern "C" const char* spdfit_mpi_session_version() { return spdfit::kVersion; }

extern "C" spdfit::cli::MpiSession* spdfit_mpi_session_start_v1(std::string* error) {
  try {
    return new spdfit::cli::WorldSession();
  } catch (const std::exception& e) {
    *error = e.what();
    return nullptr;
  }
}

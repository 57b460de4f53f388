// The streaming fit split among processes gives the single-process streaming fit's estimate to
// rounding (bitwise the same run to run for a given number of processes), reads each data row
// exactly once whatever the line ends, comments, blank lines and header, and ends every process
// with the same error, the first in the files' order. The processes here are threads joined by
// an in-process Channel; tests/cli/test_mpi.py runs the same through mpirun.
#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "file_test_support.hpp"
#include "io/split_file.hpp"
#include "spdfit/distributed.hpp"
#include "spdfit/fit_files.hpp"
#include "spdfit/io.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

// K "processes" as threads: gathers meet at a barrier, messages go through mailboxes.
class ThreadWorld {
 public:
  explicit ThreadWorld(int size) : size_(size), slots_(static_cast<std::size_t>(size)), flags_(size) {}

  class Endpoint final : public Channel {
   public:
    Endpoint(ThreadWorld& world, int rank) : world_(world), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return world_.size_; }
    std::vector<std::string> all_gather(const std::string& mine) override { return world_.gather(rank_, mine); }
    void send(int to, const std::string& bytes) override {
      const std::lock_guard<std::mutex> lock(world_.mutex_);
      world_.mail_[{rank_, to}].push_back(bytes);
      world_.changed_.notify_all();
    }
    std::string receive(int from) override {
      std::unique_lock<std::mutex> lock(world_.mutex_);
      auto& box = world_.mail_[{from, rank_}];
      world_.changed_.wait(lock, [&] { return !box.empty(); });
      std::string bytes = std::move(box.front());
      box.pop_front();
      return bytes;
    }
    void announce_failure() override {
      for (int k = 0; k < world_.size_; ++k) {
        if (k != rank_) world_.flags_[static_cast<std::size_t>(k)] = true;
      }
    }
    bool failure_announced() override { return world_.flags_[static_cast<std::size_t>(rank_)]; }

   private:
    ThreadWorld& world_;
    int rank_;
  };

 private:
  std::vector<std::string> gather(int rank, const std::string& mine) {
    std::unique_lock<std::mutex> lock(mutex_);
    slots_[static_cast<std::size_t>(rank)] = mine;
    const std::uint64_t generation = generation_;
    if (++arrived_ == size_) {
      gathered_ = slots_;
      arrived_ = 0;
      ++generation_;
      changed_.notify_all();
    } else {
      changed_.wait(lock, [&] { return generation_ != generation; });
    }
    return gathered_;
  }

  int size_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<std::string> slots_, gathered_;
  int arrived_ = 0;
  std::uint64_t generation_ = 0;
  std::map<std::pair<int, int>, std::deque<std::string>> mail_;
  std::vector<std::atomic<bool>> flags_;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// What one process ended with.
struct Outcome {
  std::optional<DistributedFit> fit;
  std::string error;  // the exception's what(), when it threw
  bool data_error = false;
  std::size_t line = 0, column = 0;
};

std::vector<Outcome> run_processes(int size, const std::string& a, const std::string& b, Method method,
                                   const FitOptions& options = {}, StreamOptions stream = {}) {
  ThreadWorld world(size);
  std::vector<Outcome> outcomes(static_cast<std::size_t>(size));
  std::vector<std::thread> threads;
  stream.threads = 1;
  for (int rank = 0; rank < size; ++rank) {
    threads.emplace_back([&, rank] {
      ThreadWorld::Endpoint channel(world, rank);
      Outcome& out = outcomes[static_cast<std::size_t>(rank)];
      try {
        out.fit = fit_files_distributed(a, b, method, options, stream, {}, channel);
      } catch (const io::DataError& e) {
        out.error = e.what();
        out.data_error = true;
        out.line = e.line();
        out.column = e.column();
      } catch (const std::exception& e) {
        out.error = e.what();
      }
    });
  }
  for (std::thread& t : threads) t.join();
  return outcomes;
}

// As in test_stream.cpp: a differently blocked QR moves R by a few eps relative.
constexpr double kTolerance = 1e-12;

class DistributedTest : public test::ScratchDirectory {
 protected:
  // Noisy data A X ~= B, m x n, A written as CSV with a header, comments, blank lines and CR LF
  // line ends, with long lines (17 digits); B as short lines (6 digits) with LF.
  void MakeData(Index m, Index n, unsigned seed) {
    test::Generator g(seed);
    const MatrixXd X = g.spd(n, 10.0);
    A_ = g.gaussian(m, n) * 3.0;
    B_ = A_ * X + 0.1 * g.gaussian(m, n);
    std::string a = "# accelerations\r\n\r\n";
    for (Index j = 0; j < n; ++j) a += (j ? "," : "") + std::string("a") + std::to_string(j);
    a += "\r\n";
    char value[64];
    for (Index i = 0; i < m; ++i) {
      if (i % 97 == 0) a += "  # a comment\r\n   \r\n";
      for (Index j = 0; j < n; ++j) {
        std::snprintf(value, sizeof value, "%s%.17g", j ? "," : "", A_(i, j));
        a += value;
      }
      a += "\r\n";
    }
    std::string b;
    for (Index i = 0; i < m; ++i) {
      for (Index j = 0; j < n; ++j) {
        std::snprintf(value, sizeof value, "%s%.6g", j ? " " : "", B_(i, j));
        b += value;
      }
      b += i % 5 == 0 ? "\n\n" : "\n";
    }
    a_path_ = Write("A.csv", a);
    b_path_ = Write("B.txt", b);
    // The values as the files hold them (B rounded to 6 digits).
    A_ = io::read_table(a_path_).values;
    B_ = io::read_table(b_path_).values;
  }

  FitResult SingleProcess(Method method, const FitOptions& options = {}) const {
    StreamOptions stream;
    stream.threads = 1;
    return fit_files(a_path_, b_path_, method, options, stream);
  }

  MatrixXd A_, B_;
  std::string a_path_, b_path_;
};

TEST_F(DistributedTest, EveryProcessCountGivesTheSingleProcessEstimate) {
  MakeData(2003, 4, 1);
  for (Method method : {Method::LeastSquares, Method::SymmetricProcrustes, Method::TotalLeastSquares,
                        Method::Spde, Method::Auto}) {
    const FitResult single = SingleProcess(method);
    ASSERT_TRUE(single.ok()) << single.message;
    for (int size : {1, 2, 3, 5, 8}) {
      const std::vector<Outcome> outcomes = run_processes(size, a_path_, b_path_, method);
      ASSERT_TRUE(outcomes[0].fit && outcomes[0].fit->result) << outcomes[0].error;
      const FitResult& result = *outcomes[0].fit->result;
      EXPECT_EQ(result.method, single.method) << size;
      EXPECT_LT(test::relative_error(result.X, single.X), kTolerance) << to_string(method) << ", " << size;
      EXPECT_EQ(result.diagnostics.m, 2003);
      EXPECT_EQ(result.row_names, single.row_names);  // process 0 read the header
      for (int k = 1; k < size; ++k) {
        EXPECT_FALSE(outcomes[static_cast<std::size_t>(k)].fit->result) << "only process 0 has the estimate";
      }
      // Every row read once, in nearly equal parts.
      const std::vector<std::uint64_t>& rows = outcomes[0].fit->rows_per_process;
      ASSERT_EQ(rows.size(), static_cast<std::size_t>(size));
      std::uint64_t total = 0;
      for (std::uint64_t r : rows) {
        total += r;
        EXPECT_LE(r, 2003 / static_cast<std::uint64_t>(size) + 1);
        EXPECT_GE(r, 2003 / static_cast<std::uint64_t>(size));
      }
      EXPECT_EQ(total, 2003U);
    }
  }
}

TEST_F(DistributedTest, TheIterativeMethodsAgreeToTheirTolerance) {
  MakeData(1501, 3, 2);
  for (Method method : {Method::SpdTotalLeastSquares, Method::PsdLeastSquares}) {
    const FitResult single = SingleProcess(method);
    ASSERT_TRUE(single.ok()) << single.message;
    const std::vector<Outcome> outcomes = run_processes(3, a_path_, b_path_, method);
    ASSERT_TRUE(outcomes[0].fit && outcomes[0].fit->result) << outcomes[0].error;
    EXPECT_LT(test::relative_error(outcomes[0].fit->result->X, single.X), 1e-8) << to_string(method);
  }
}

// The noise model reaches the fit on process 0 (the options are every process's own, not sent),
// and a model of another size is refused on every process alike.
TEST_F(DistributedTest, ANoiseModelIsTheSingleProcessFitsAndIsCheckedEverywhere) {
  MakeData(400, 3, 7);
  FitOptions options;
  options.noise = NoiseModel::from_std((Eigen::VectorXd(3) << 0.1, 0.2, 0.1).finished(), Eigen::VectorXd::Constant(1, 0.3));
  for (Method method : {Method::SpdTotalLeastSquares, Method::Auto, Method::TotalLeastSquares}) {
    const FitResult single = SingleProcess(method, options);
    ASSERT_TRUE(single.ok()) << single.message;
    ASSERT_TRUE(single.diagnostics.noise_model);
    const std::vector<Outcome> outcomes = run_processes(3, a_path_, b_path_, method, options);
    ASSERT_TRUE(outcomes[0].fit && outcomes[0].fit->result) << outcomes[0].error;
    EXPECT_LT(test::relative_error(outcomes[0].fit->result->X, single.X), 1e-8) << to_string(method);
    EXPECT_TRUE(outcomes[0].fit->result->diagnostics.noise_model);
  }
  options.noise = NoiseModel::from_std(Eigen::VectorXd::Constant(2, 0.1), Eigen::VectorXd::Constant(1, 0.3));
  const std::vector<Outcome> refused = run_processes(3, a_path_, b_path_, Method::SpdTotalLeastSquares, options);
  for (const Outcome& outcome : refused) {
    EXPECT_FALSE(outcome.fit);
    EXPECT_NE(outcome.error.find("`noise_std_a` has 2 values but A has 3 columns"), std::string::npos) << outcome.error;
  }
}

TEST_F(DistributedTest, AGivenProcessCountGivesTheSameBitsRunToRun) {
  MakeData(999, 3, 3);
  const std::vector<Outcome> first = run_processes(3, a_path_, b_path_, Method::Spde);
  const std::vector<Outcome> second = run_processes(3, a_path_, b_path_, Method::Spde);
  ASSERT_TRUE(first[0].fit->result && second[0].fit->result);
  EXPECT_EQ(first[0].fit->result->X, second[0].fit->result->X);
}

TEST_F(DistributedTest, MoreProcessesThanRowsLeavesSomeIdle) {
  MakeData(5, 2, 4);
  const FitResult single = SingleProcess(Method::LeastSquares);
  const std::vector<Outcome> outcomes = run_processes(7, a_path_, b_path_, Method::LeastSquares);
  ASSERT_TRUE(outcomes[0].fit && outcomes[0].fit->result) << outcomes[0].error;
  EXPECT_LT(test::relative_error(outcomes[0].fit->result->X, single.X), kTolerance);
  EXPECT_GT(outcomes[0].fit->rows_per_process[0], 0U);
}

TEST_F(DistributedTest, NpyFilesSplitByTheirHeaders) {
  MakeData(3001, 5, 5);
  const std::string a = Path("A.npy");
  const std::string b = Path("B.npy");
  io::write_npy(a, A_);
  io::write_npy(b, B_);
  const FitResult single = fit_files(a, b, Method::Spde, {}, StreamOptions{});
  for (int size : {2, 3}) {
    const std::vector<Outcome> outcomes = run_processes(size, a, b, Method::Spde);
    ASSERT_TRUE(outcomes[0].fit && outcomes[0].fit->result) << outcomes[0].error;
    EXPECT_LT(test::relative_error(outcomes[0].fit->result->X, single.X), kTolerance);
  }
  // A .npy A with a text B: each file splits its own way, rows still paired.
  const std::vector<Outcome> mixed = run_processes(3, a, b_path_, Method::Spde);
  ASSERT_TRUE(mixed[0].fit && mixed[0].fit->result) << mixed[0].error;
  EXPECT_LT(test::relative_error(mixed[0].fit->result->X, single.X), kTolerance);
}

TEST_F(DistributedTest, TheStreamingBootstrapOnTooFewRowsIsRefusedOnEveryProcess) {
  MakeData(30000, 2, 6);
  FitOptions options;
  options.bootstrap = 10;
  const std::vector<Outcome> outcomes = run_processes(2, a_path_, b_path_, Method::Spde, options);
  for (const Outcome& outcome : outcomes) {
    EXPECT_NE(outcome.error.find("needs about 100 groups (409600 rows)"), std::string::npos) << outcome.error;
    EXPECT_NE(outcome.error.find("30000 rows (8 groups)"), std::string::npos) << outcome.error;
  }
}

TEST_F(DistributedTest, TheStreamingBootstrapIsTheSingleProcessOne) {
  // The Poisson bootstrap needs about 100 groups of 4096 rows.
  MakeData(100 * 4096 + 5, 2, 6);
  FitOptions options;
  options.bootstrap = 20;
  options.seed = 9;
  const FitResult single = SingleProcess(Method::Spde, options);
  ASSERT_TRUE(single.bootstrap);
  for (int size : {2, 3}) {
    const std::vector<Outcome> outcomes = run_processes(size, a_path_, b_path_, Method::Spde, options);
    ASSERT_TRUE(outcomes[0].fit && outcomes[0].fit->result) << outcomes[0].error;
    const FitResult& result = *outcomes[0].fit->result;
    ASSERT_TRUE(result.bootstrap);
    EXPECT_EQ(result.bootstrap->groups, single.bootstrap->groups);
    // Parts start at whole groups of rows, so each replicate resamples the same groups.
    const std::vector<std::uint64_t>& rows = outcomes[0].fit->rows_per_process;
    for (std::size_t k = 0; k + 1 < rows.size(); ++k) EXPECT_EQ(rows[k] % 4096, 0U) << k;
    EXPECT_LT(test::relative_error(result.bootstrap->standard_errors, single.bootstrap->standard_errors), 1e-10);
  }
}

// Splitting alone: the parts' rows, read one after another, are the file's rows, for every
// kind of line end and blank or comment lines anywhere, including at the parts' edges.
TEST_F(DistributedTest, PartsReadEveryRowOnceWhateverTheLineEnds) {
  const std::vector<std::string> texts = {
      "x,y\n1,2\n3,4\n\n5,6\n# c\n7,8\n9,10",         // LF, no final line end
      "\xEF\xBB\xBFx,y\r\n1,2\r\n3,4\r\n\r\n5,6\r\n",  // byte-order mark, CR LF
      "1 2\r3 4\r\r5 6\r7 8\r",                        // lone CR (old Mac)
      "% m\n  \n1;2\n\t\n3;4\n5;6\n#\n7;8\n9;10\n11;12\n",
  };
  for (const std::string& text : texts) {
    const std::string path = Write("t.csv", text);
    const MatrixXd whole = io::read_table(path).values;
    for (int parts = 1; parts <= 9; ++parts) {
      std::vector<io::detail::SplitFile> files;
      std::vector<std::vector<std::uint64_t>> counts;
      for (int k = 0; k < parts; ++k) {
        files.emplace_back(path, io::ReadOptions{}, k, parts);
        counts.push_back(files.back().count());
      }
      MatrixXd rows(0, whole.cols());
      for (int k = 0; k < parts; ++k) {
        io::detail::SplitFile& f = files[static_cast<std::size_t>(k)];
        f.set_counts(counts);
        ASSERT_EQ(f.rows(), static_cast<std::uint64_t>(whole.rows()));
        const std::uint64_t first = f.rows() * static_cast<std::uint64_t>(k) / static_cast<std::uint64_t>(parts);
        const std::uint64_t last = f.rows() * static_cast<std::uint64_t>(k + 1) / static_cast<std::uint64_t>(parts);
        if (last == first) continue;
        io::RowReader reader = f.open(first, last - first, f.locate(first), f.locate(last));
        MatrixXd part;
        const Index got = reader.read(1000, &part);
        ASSERT_EQ(got, static_cast<Index>(last - first)) << text << ", part " << k << " of " << parts;
        rows.conservativeResize(rows.rows() + got, Eigen::NoChange);
        rows.bottomRows(got) = part;
      }
      EXPECT_EQ(rows, whole) << text << ", " << parts << " parts";
    }
  }
}

TEST_F(DistributedTest, ABadRowInTheLastPartEndsEveryProcessWithItsLine) {
  MakeData(3000, 3, 7);
  std::string text = slurp(b_path_);
  const std::size_t late = text.rfind('\n', text.size() - 200);
  text.insert(late + 1, "1 2 oops\n");
  const std::string bad = Write("Bbad.txt", text);
  io::DataError expected("", 0, 0, "");
  try {
    fit_files(a_path_, bad, Method::Spde, {}, StreamOptions{});
    FAIL() << "no error";
  } catch (const io::DataError& e) {
    expected = e;
  }
  for (int size : {2, 4}) {
    const std::vector<Outcome> outcomes = run_processes(size, a_path_, bad, Method::Spde);
    for (const Outcome& out : outcomes) {
      ASSERT_TRUE(out.data_error) << out.error;
      EXPECT_EQ(out.error, expected.what());
      EXPECT_EQ(out.line, expected.line());
    }
  }
}

TEST_F(DistributedTest, TheFirstFailureInTheFilesOrderIsReported) {
  MakeData(3000, 3, 8);
  std::string text = slurp(b_path_);
  text.insert(text.rfind('\n', text.size() - 200) + 1, "1 2 late\n");
  text.insert(text.find('\n', 3000) + 1, "1 2 early\n");
  const std::string bad = Write("Bbad.txt", text);
  const std::vector<Outcome> outcomes = run_processes(3, a_path_, bad, Method::Spde);
  for (const Outcome& out : outcomes) EXPECT_NE(out.error.find("'early'"), std::string::npos) << out.error;
}

TEST_F(DistributedTest, FilesThatCannotBeSplitOrPairedAreRefusedOnEveryProcess) {
  MakeData(300, 3, 9);
  // Rows differ: the counting pass knows both counts.
  std::string text = slurp(b_path_);
  text += "1 2 3\n";
  const std::string longer = Write("Blong.txt", text);
  for (const Outcome& out : run_processes(2, a_path_, longer, Method::Spde)) {
    ASSERT_TRUE(out.data_error) << out.error;
    EXPECT_NE(out.error.find("B has 301 rows but A"), std::string::npos) << out.error;
  }
  // A missing file.
  for (const Outcome& out : run_processes(3, a_path_, Path("missing.csv"), Method::Spde)) {
    ASSERT_TRUE(out.data_error) << out.error;
    EXPECT_NE(out.error.find("missing.csv"), std::string::npos) << out.error;
  }
  // A .mat file is not split among processes.
  const std::string mat = Path("B.mat");
  io::write_mat(mat, B_, "B");
  for (const Outcome& out : run_processes(2, a_path_, mat, Method::Spde)) {
    ASSERT_TRUE(out.data_error) << out.error;
    EXPECT_NE(out.error.find("cannot be split among processes"), std::string::npos) << out.error;
  }
  // ... but one process reads it as fit_files does.
  const std::vector<Outcome> one = run_processes(1, a_path_, mat, Method::Spde);
  ASSERT_TRUE(one[0].fit && one[0].fit->result) << one[0].error;
}

}  // namespace
}  // namespace spdfit

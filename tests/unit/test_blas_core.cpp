// The BLAS-core rule (numerics/blas_core.hpp) on its own: which OpenBLAS cores count as generic,
// and what check_blas_core() suggests for each setting of the environment. The restart and the
// warning that act on it are tested through the CLI and the module (tests/cli, tests/python).
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "numerics/blas_core.hpp"

namespace spdfit {
namespace {

// Sets (or, with nullopt, removes) an environment variable for one scope, then restores it.
class ScopedVariable {
 public:
  ScopedVariable(const char* name, const std::optional<std::string>& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) {
      ::setenv(name, value->c_str(), 1);
    } else {
      ::unsetenv(name);
    }
  }
  ~ScopedVariable() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedVariable(const ScopedVariable&) = delete;
  ScopedVariable& operator=(const ScopedVariable&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// The core spdfit should suggest on this CPU for a generic one.
std::string core_for(const std::string& cpu) {
  if (cpu == "AVX-512") return "SkylakeX";
  if (cpu == "AVX2") return "Haswell";
  return "";
}

TEST(BlasCore, GenericCoresAreThoseWithoutAvx2Kernels) {
  for (const char* core : {"Prescott", "Katmai", "Core2", "Nehalem", "Barcelona", "Atom", "Sandybridge",
                           "Opteron_SSE3", "Steamroller", "prescott", "NEHALEM"}) {
    EXPECT_TRUE(detail::is_generic_blas_core(core)) << core;
  }
  // AVX2 cores, OpenBLAS's name for a core it could not place, names a newer OpenBLAS may add,
  // and strings that only resemble a core.
  for (const char* core : {"Haswell", "Zen", "SkylakeX", "Cooperlake", "SapphireRapids", "Excavator",
                           "Unknown", "", " Prescott", "Prescott ", "Prescott2", "Presc"}) {
    EXPECT_FALSE(detail::is_generic_blas_core(core)) << '"' << core << '"';
  }
}

TEST(BlasCore, ReportsOpenBlasOwnCore) {
  const ScopedVariable no_switch(detail::kTestBlasCoreVariable, std::nullopt);
  const detail::BlasCoreCheck check = detail::check_blas_core();
  EXPECT_EQ(check.reported, detail::blas_core_name());  // empty when the BLAS is not OpenBLAS
  EXPECT_FALSE(check.from_test_switch);
}

TEST(BlasCore, SuggestsTheCpusCoreForAGenericOne) {
  if (detail::blas_core_name().empty()) GTEST_SKIP() << "the BLAS linked is not OpenBLAS";
  const ScopedVariable generic(detail::kTestBlasCoreVariable, "Prescott");
  const ScopedVariable unset(detail::kOpenBlasCoreVariable, std::nullopt);
  const detail::BlasCoreCheck check = detail::check_blas_core();
  EXPECT_EQ(check.reported, "Prescott");
  EXPECT_TRUE(check.from_test_switch);
  EXPECT_EQ(check.user_coretype, "");
  EXPECT_EQ(check.suggested, core_for(check.cpu));
  {
    // OpenBLAS ignores an empty OPENBLAS_CORETYPE, and so does the rule.
    const ScopedVariable empty(detail::kOpenBlasCoreVariable, "");
    EXPECT_EQ(detail::check_blas_core().suggested, core_for(check.cpu));
  }
}

TEST(BlasCore, KeepsTheUsersCoreAndModernOnes) {
  if (detail::blas_core_name().empty()) GTEST_SKIP() << "the BLAS linked is not OpenBLAS";
  {
    const ScopedVariable generic(detail::kTestBlasCoreVariable, "Prescott");
    const ScopedVariable chosen(detail::kOpenBlasCoreVariable, "Nehalem");
    const detail::BlasCoreCheck check = detail::check_blas_core();
    EXPECT_EQ(check.user_coretype, "Nehalem");
    EXPECT_EQ(check.suggested, "");
  }
  const ScopedVariable unset(detail::kOpenBlasCoreVariable, std::nullopt);
  for (const char* core : {"Haswell", "SkylakeX", "Zen", "NoSuchCore", "x:y"}) {
    const ScopedVariable modern(detail::kTestBlasCoreVariable, core);
    EXPECT_EQ(detail::check_blas_core().suggested, "") << core;
  }
}

}  // namespace
}  // namespace spdfit

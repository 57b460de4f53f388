// TriangularFactor as a value: merged, serialize and deserialize (the layout is documented in
// triangular_factor.hpp). Written byte by byte in little-endian order, so the bytes are the same
// on every machine.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "spdfit/triangular_factor.hpp"

namespace spdfit {

namespace {

constexpr char kMagic[8] = {'s', 'p', 'd', 'f', 'i', 't', 'R', '\0'};
// Layout 1: a square factor (d = n), as every factor was written before non-square ones existed;
// layout 2 adds d after n.
constexpr std::uint32_t kSquareLayout = 1;
constexpr std::uint32_t kRectangularLayout = 2;
// Layout 3: a factor of [1 A B] (TriangularFactor::intercept): d always, and the column means.
constexpr std::uint32_t kInterceptLayout = 3;
// Columns a factor can have: far beyond what memory holds, small enough that sizes cannot overflow.
constexpr std::uint64_t kMaxColumns = std::uint64_t{1} << 28;
// Binary exponents a factor of finite data can carry: the doubles' range, denormals included.
constexpr int kMaxExponent = 1100;

void put(std::string& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  std::uint64_t take(int bytes, const char* what) {
    if (bytes_.size() - at_ < static_cast<std::size_t>(bytes)) {
      throw std::invalid_argument(std::string("TriangularFactor::deserialize: the bytes end inside ") + what);
    }
    std::uint64_t value = 0;
    for (int i = 0; i < bytes; ++i) value |= std::uint64_t{static_cast<unsigned char>(bytes_[at_ + i])} << (8 * i);
    at_ += static_cast<std::size_t>(bytes);
    return value;
  }
  std::size_t left() const { return bytes_.size() - at_; }
  std::string_view rest(std::size_t count) {
    const std::string_view out = bytes_.substr(at_, count);
    at_ += count;
    return out;
  }

 private:
  std::string_view bytes_;
  std::size_t at_ = 0;
};

[[noreturn]] void bad(const std::string& why) {
  throw std::invalid_argument("TriangularFactor::deserialize: " + why);
}

}  // namespace

TriangularFactor TriangularFactor::merged(const TriangularFactor& a, const TriangularFactor& b) {
  TriangularFactor out = a;
  out.merge(b);
  return out;
}

std::string TriangularFactor::serialize() const {
  const Eigen::Index size = n_ + d_;
  std::string out(kMagic, sizeof kMagic);
  const std::uint32_t layout = intercept_ ? kInterceptLayout : d_ == n_ ? kSquareLayout : kRectangularLayout;
  put(out, layout, 4);
  put(out, static_cast<std::uint64_t>(n_), 8);
  if (layout != kSquareLayout) put(out, static_cast<std::uint64_t>(d_), 8);
  put(out, static_cast<std::uint64_t>(rows_), 8);
  for (const std::optional<int>& e : {exponent_a_, exponent_b_}) {
    put(out, e ? 1 : 0, 1);
    put(out, static_cast<std::uint32_t>(static_cast<std::int32_t>(e.value_or(0))), 4);
  }
  if (intercept_) {
    std::uint64_t mass_bits = 0;
    std::memcpy(&mass_bits, &mass_, sizeof mass_bits);
    put(out, mass_bits, 8);
    for (Eigen::Index j = 0; j < size; ++j) {
      std::uint64_t bits = 0;
      const double value = rows_ > 0 ? means_(j) : 0.0;
      std::memcpy(&bits, &value, sizeof bits);
      put(out, bits, 8);
    }
  }
  for (Eigen::Index j = 0; j < size; ++j) {
    for (Eigen::Index i = 0; i <= j; ++i) {
      std::uint64_t bits = 0;
      const double value = R_(i, j);
      std::memcpy(&bits, &value, sizeof bits);
      put(out, bits, 8);
    }
  }
  return out;
}

TriangularFactor TriangularFactor::deserialize(std::string_view bytes) {
  Reader in(bytes);
  if (bytes.size() < sizeof kMagic || bytes.substr(0, sizeof kMagic) != std::string_view(kMagic, sizeof kMagic)) {
    bad("not a serialized triangular factor (wrong magic bytes)");
  }
  in.rest(sizeof kMagic);
  const std::uint64_t version = in.take(4, "the layout version");
  if (version != kSquareLayout && version != kRectangularLayout && version != kInterceptLayout) {
    bad("layout version " + std::to_string(version) + " is not 1, 2 or 3");
  }
  const auto n = static_cast<std::int64_t>(in.take(8, "n"));
  const auto d = version == kSquareLayout ? n : static_cast<std::int64_t>(in.take(8, "d"));
  const std::uint64_t rows = in.take(8, "the row count");
  for (auto [name, value] : {std::pair{"n", n}, std::pair{"d", d}}) {
    if (value < 1) bad(std::string(name) + " = " + std::to_string(value) + " is not at least 1");
    // The size must match before anything of size O((n + d)^2) is allocated.
    if (static_cast<std::uint64_t>(value) > kMaxColumns) {
      bad(std::string(name) + " = " + std::to_string(value) + " is out of range");
    }
  }
  if (version == kRectangularLayout && d == n) bad("layout 2 with d = n (a square factor is layout 1)");
  if (rows > static_cast<std::uint64_t>(INT64_MAX)) bad("the row count is out of range");
  const auto size = static_cast<std::uint64_t>(n + d);
  std::optional<int> exponents[2];
  for (std::optional<int>& e : exponents) {
    const std::uint64_t flag = in.take(1, "an exponent flag");
    const auto value = static_cast<std::int32_t>(static_cast<std::uint32_t>(in.take(4, "an exponent")));
    if (flag > 1) bad("an exponent flag is " + std::to_string(flag) + ", not 0 or 1");
    if (value < -kMaxExponent || value > kMaxExponent) bad("exponent " + std::to_string(value) + " is out of range");
    if (flag == 1) e = value;
  }
  const bool intercept = version == kInterceptLayout;
  Eigen::VectorXd means;
  double mass = 0.0;
  if (intercept) {
    const std::uint64_t mass_bits = in.take(8, "the rows' weight");
    std::memcpy(&mass, &mass_bits, sizeof mass);
    if (!std::isfinite(mass) || mass < 0.0) bad("the rows' weight is not a finite number >= 0");
    if (in.left() < size * 8) bad("the bytes end inside the column means");
    means.resize(static_cast<Eigen::Index>(size));
    for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(size); ++j) {
      const std::uint64_t bits = in.take(8, "the column means");
      std::memcpy(&means(j), &bits, sizeof bits);
      if (!std::isfinite(means(j))) bad("column mean " + std::to_string(j) + " is not finite");
    }
  }
  const std::uint64_t entries = size * (size + 1) / 2;
  if (in.left() != entries * 8) {
    bad(std::to_string(in.left()) + " bytes of R where n = " + std::to_string(n) + ", d = " + std::to_string(d) +
        " needs " + std::to_string(entries * 8));
  }
  TriangularFactor out(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(d), intercept);
  out.rows_ = static_cast<Eigen::Index>(rows);
  if (intercept && rows > 0) out.means_ = means;
  out.mass_ = mass;
  out.exponent_a_ = exponents[0];
  out.exponent_b_ = exponents[1];
  for (Eigen::Index j = 0; j < static_cast<Eigen::Index>(size); ++j) {
    for (Eigen::Index i = 0; i <= j; ++i) {
      const std::uint64_t bits = in.take(8, "R");
      double value = 0.0;
      std::memcpy(&value, &bits, sizeof value);
      if (!std::isfinite(value)) bad("R(" + std::to_string(i) + ", " + std::to_string(j) + ") is not finite");
      // (A factor of centred rows absorbs one row more per chunk: the rows beyond are not checked.)
      if (!intercept && static_cast<std::uint64_t>(i) >= rows && value != 0.0) {
        bad("R has a nonzero entry in row " + std::to_string(i) + " beyond the " + std::to_string(rows) +
            " rows accumulated");
      }
      out.R_(i, j) = value;
    }
  }
  // A block whose data were all zero has no exponent and only zero columns in R.
  if (!out.exponent_a_ && !out.R_.leftCols(n).isZero(0.0)) bad("A's columns of R are nonzero but A has no exponent");
  if (!out.exponent_b_ && !out.R_.rightCols(d).isZero(0.0)) bad("B's columns of R are nonzero but B has no exponent");
  return out;
}

}  // namespace spdfit

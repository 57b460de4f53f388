// Fuzzes hexapod::parse_geometry, the reader of hexapod geometry files (JSON). Properties: the text
// gives a valid geometry or an io::DataError; a geometry it accepts has a finite, symmetric
// positive definite M_p (thesis eq. 2.12) and survives geometry_json and back bit for bit.
#include <cstddef>
#include <cstdint>
#include <string>

#include <Eigen/Cholesky>

#include "fuzz_check.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/hexapod/model.hpp"
#include "spdfit/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  spdfit::hexapod::Geometry g;
  try {
    g = spdfit::hexapod::parse_geometry(text, "fuzz.json");
  } catch (const spdfit::io::DataError& e) {
    SPDFIT_FUZZ_CHECK(!e.problem().empty());
    return 0;
  }
  SPDFIT_FUZZ_CHECK(g.is_valid());
  const spdfit::hexapod::Matrix6d M = spdfit::hexapod::joint_space_mass_matrix(g);
  SPDFIT_FUZZ_CHECK(M.allFinite());
  SPDFIT_FUZZ_CHECK(M == M.transpose());
  SPDFIT_FUZZ_CHECK(Eigen::LLT<spdfit::hexapod::Matrix6d>(M).info() == Eigen::Success);

  const spdfit::hexapod::Geometry back = spdfit::hexapod::parse_geometry(spdfit::hexapod::geometry_json(g), "back.json");
  SPDFIT_FUZZ_CHECK(back.base_points == g.base_points && back.payload_points == g.payload_points);
  SPDFIT_FUZZ_CHECK(back.payload_origin == g.payload_origin && back.payload_rotation == g.payload_rotation);
  SPDFIT_FUZZ_CHECK(back.payload_mass == g.payload_mass && back.payload_inertia == g.payload_inertia);
  SPDFIT_FUZZ_CHECK(back.strut_mass == g.strut_mass && back.strut_stiffness == g.strut_stiffness &&
                    back.strut_damping == g.strut_damping);
  return 0;
}

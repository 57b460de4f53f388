// Hexapod geometries: the validity checks (each names the key to fix) and the geometry file
// reader, including hostile files.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "hexapod_support.hpp"
#include "spdfit/hexapod/geometry.hpp"
#include "spdfit/io.hpp"
#include "test_support.hpp"

namespace spdfit {
namespace {

using hexapod::Geometry;

// Whether `text` contains `part`, with both in the failure message.
::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\"" << text << "\"\n  does not contain \"" << part << "\"";
}

std::string problem_with(const Geometry& geometry) {
  std::string error;
  EXPECT_FALSE(geometry.is_valid(&error));
  return error;
}

TEST(HexapodGeometry, BuiltInAndRandomGeometriesAreValid) {
  std::string error;
  EXPECT_TRUE(hexapod::cubic_geometry().is_valid(&error)) << error;
  test::Generator g(401);
  for (int repeat = 0; repeat < 20; ++repeat) EXPECT_TRUE(test::random_geometry(g).is_valid(&error)) << error;
}

TEST(HexapodGeometry, RejectsNegativeAndZeroPayloadMass) {
  Geometry geometry = hexapod::cubic_geometry();
  geometry.payload_mass = -2.0;
  EXPECT_TRUE(Contains(problem_with(geometry), "payload_mass must be positive"));
  geometry.payload_mass = 0.0;
  EXPECT_TRUE(Contains(problem_with(geometry), "payload_mass"));
}

TEST(HexapodGeometry, RejectsNegativeStrutProperties) {
  Geometry geometry = hexapod::cubic_geometry();
  geometry.strut_mass(3) = -0.1;
  EXPECT_TRUE(Contains(problem_with(geometry), "strut_mass: strut 4 has a negative value"));
  geometry = hexapod::cubic_geometry();
  geometry.strut_stiffness(0) = -1.0;
  EXPECT_TRUE(Contains(problem_with(geometry), "strut_stiffness"));
  geometry = hexapod::cubic_geometry();
  geometry.strut_damping(5) = -1.0;
  EXPECT_TRUE(Contains(problem_with(geometry), "strut_damping"));
}

TEST(HexapodGeometry, RejectsNonFiniteValuesNamingTheKey) {
  Geometry geometry = hexapod::cubic_geometry();
  geometry.payload_points(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(Contains(problem_with(geometry), "payload_points: every value must be a finite number"));
  geometry = hexapod::cubic_geometry();
  geometry.payload_origin(0) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(Contains(problem_with(geometry), "payload_origin"));
}

TEST(HexapodGeometry, RejectsInertiaThatIsNotSymmetricPositiveDefiniteOrNotPhysical) {
  Geometry geometry = hexapod::cubic_geometry();
  geometry.payload_inertia(0, 1) = 0.01;
  EXPECT_TRUE(Contains(problem_with(geometry), "payload_inertia is not symmetric"));
  geometry = hexapod::cubic_geometry();
  geometry.payload_inertia(2, 2) = -0.1;
  EXPECT_TRUE(Contains(problem_with(geometry), "payload_inertia is not positive definite"));
  geometry = hexapod::cubic_geometry();
  geometry.payload_inertia = Eigen::Vector3d(0.1, 0.1, 0.3).asDiagonal();  // 0.3 > 0.1 + 0.1
  EXPECT_TRUE(Contains(problem_with(geometry), "payload_inertia is not physically realizable"));
  // A flat plate sits on the boundary (I_zz = I_xx + I_yy) and is accepted.
  geometry.payload_inertia = Eigen::Vector3d(0.1, 0.2, 0.3).asDiagonal();
  EXPECT_TRUE(geometry.is_valid());
}

TEST(HexapodGeometry, RejectsARotationThatIsNotOne) {
  Geometry geometry = hexapod::cubic_geometry();
  geometry.payload_rotation(0, 0) = 1.1;
  EXPECT_TRUE(Contains(problem_with(geometry), "payload_rotation is not a rotation matrix"));
  geometry.payload_rotation = -Eigen::Matrix3d::Identity();  // orthogonal, but a reflection
  EXPECT_TRUE(Contains(problem_with(geometry), "det R = -1"));
  // A rotation typed to 8 digits is accepted.
  geometry.payload_rotation << 0.70710678, -0.70710678, 0, 0.70710678, 0.70710678, 0, 0, 0, 1;
  std::string error;
  EXPECT_TRUE(geometry.is_valid(&error)) << error;
}

TEST(HexapodGeometry, RejectsCoincidentJoints) {
  Geometry geometry = hexapod::cubic_geometry();
  // Put payload joint 3 exactly on base joint 3.
  geometry.payload_points.col(2) =
      geometry.payload_rotation.transpose() * (geometry.base_points.col(2) - geometry.payload_origin);
  EXPECT_TRUE(Contains(problem_with(geometry), "strut 3 has zero length"));
  EXPECT_TRUE(Contains(problem_with(geometry), "base_points[2] and payload_points[2]"));
}

TEST(HexapodGeometry, RejectsTwoStrutsOnOneLine) {
  Geometry geometry = hexapod::cubic_geometry();
  // Strut 5 moved onto strut 2's line (its joints slid along that line).
  const Eigen::Vector3d q = geometry.base_points.col(1);
  const Eigen::Vector3d p = geometry.payload_points.col(1);
  const Eigen::Vector3d u = (geometry.payload_origin + p - q).normalized();
  geometry.base_points.col(4) = q - 0.01 * u;
  geometry.payload_points.col(4) = p + 0.01 * u;
  EXPECT_TRUE(Contains(problem_with(geometry), "struts 2 and 5 lie on the same line"));
}

TEST(HexapodGeometry, RejectsASingularJacobian) {
  // All six struts vertical: the payload can translate sideways and turn about z freely.
  Geometry geometry = hexapod::cubic_geometry();
  for (int i = 0; i < 6; ++i) {
    const double angle = i * 1.0471975511965976;
    geometry.base_points.col(i) = Eigen::Vector3d(0.1 * std::cos(angle), 0.1 * std::sin(angle), 0.0);
    geometry.payload_points.col(i) = Eigen::Vector3d(0.1 * std::cos(angle), 0.1 * std::sin(angle), 0.0);
  }
  geometry.payload_origin = Eigen::Vector3d(0, 0, 0.2);
  EXPECT_TRUE(Contains(problem_with(geometry), "the Jacobian is singular"));
  EXPECT_TRUE(Contains(problem_with(geometry), "move freely"));
}

TEST(HexapodGeometry, CubicGeometryRejectsBadParameters) {
  hexapod::CubicGeometryParameters parameters;
  parameters.edge = -1.0;
  EXPECT_THROW(hexapod::cubic_geometry(parameters), std::invalid_argument);
  parameters = {};
  parameters.payload_mass = -1.0;
  EXPECT_THROW(hexapod::cubic_geometry(parameters), std::invalid_argument);
}

// ---- the geometry file --------------------------------------------------------------------

std::string valid_text() { return hexapod::geometry_json(hexapod::cubic_geometry()); }

// The reader's message for `text`, which must be rejected.
std::string read_error(const std::string& text) {
  try {
    hexapod::parse_geometry(text, "G.json");
  } catch (const io::DataError& e) {
    EXPECT_EQ(e.source(), "G.json");
    return e.what();
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return "";
}

// `text` with the value of `key` replaced by `value` (the key must be in the text).
std::string with_value(const std::string& key, const std::string& value) {
  std::string text = valid_text();
  const std::size_t start = text.find("\"" + key + "\": ");
  EXPECT_NE(start, std::string::npos) << key;
  std::size_t begin = start + key.size() + 4, depth = 0, end = begin;
  for (; end < text.size(); ++end) {
    const char c = text[end];
    if (c == '[') ++depth;
    if (c == ']') --depth;
    if (depth == 0 && (c == ',' || c == '\n')) break;
  }
  if (text[end] == ']') ++end;
  return text.substr(0, begin) + value + text.substr(end);
}

TEST(HexapodGeometryFile, RoundTripsExactly) {
  test::Generator g(402);
  for (int repeat = 0; repeat < 5; ++repeat) {
    const Geometry geometry = repeat == 0 ? hexapod::cubic_geometry() : test::random_geometry(g);
    const Geometry back = hexapod::parse_geometry(hexapod::geometry_json(geometry), "round-trip");
    EXPECT_TRUE(back.base_points == geometry.base_points);
    EXPECT_TRUE(back.payload_points == geometry.payload_points);
    EXPECT_TRUE(back.payload_origin == geometry.payload_origin);
    EXPECT_TRUE(back.payload_rotation == geometry.payload_rotation);
    EXPECT_EQ(back.payload_mass, geometry.payload_mass);
    EXPECT_TRUE(back.payload_inertia == geometry.payload_inertia);
    EXPECT_TRUE(back.strut_mass == geometry.strut_mass);
    EXPECT_TRUE(back.strut_stiffness == geometry.strut_stiffness);
    EXPECT_TRUE(back.strut_damping == geometry.strut_damping);
  }
}

TEST(HexapodGeometryFile, AcceptsScalarStrutPropertiesOptionalKeysAndComments) {
  std::string text = with_value("strut_mass", "0.25");
  text = text.substr(0, text.find("  \"payload_rotation\"")) + text.substr(text.find("  \"payload_mass\""));
  text.insert(2, "\"_comment\": \"made by hand\",\n  ");
  const Geometry geometry = hexapod::parse_geometry(text, "G.json");
  EXPECT_TRUE(geometry.strut_mass == hexapod::Vector6d::Constant(0.25));
  EXPECT_TRUE(geometry.payload_rotation == Eigen::Matrix3d::Identity());
}

TEST(HexapodGeometryFile, ErrorsNameTheKey) {
  EXPECT_TRUE(
      Contains(read_error(with_value("payload_mass", "-3")), "G.json: payload_mass must be positive"));
  EXPECT_TRUE(Contains(read_error(with_value("payload_mass", "\"heavy\"")),
                       "payload_mass must be a number, found the string \"heavy\""));
  EXPECT_TRUE(Contains(read_error(with_value("base_points", "[[0, 0, 0], [1, 0, 0]]")),
                       "base_points must be an array of 6 points"));
  EXPECT_TRUE(Contains(read_error(with_value("payload_origin", "[0, 0]")),
                       "payload_origin must be [x, y, z] (3 numbers), found an array of 2 entries"));
  EXPECT_TRUE(Contains(read_error(with_value("payload_inertia", "[[1, 0, 0], [0, 1, 0]]")),
                       "payload_inertia must be a 3x3 matrix"));
  EXPECT_TRUE(Contains(read_error(with_value("payload_inertia", "[[1, 0, 0], [0, 1, 0], [0, 0, -1]]")),
                       "payload_inertia is not positive definite"));
  EXPECT_TRUE(
      Contains(read_error(with_value("strut_stiffness", "[1, 2, 3]")),
               "strut_stiffness must be a number (the same for every strut) or an array of 6 numbers"));
  EXPECT_TRUE(Contains(read_error(with_value("strut_mass", "[1, 2, 3, 4, 5, null]")),
                       "strut_mass[5] must be a number, found null"));
}

TEST(HexapodGeometryFile, RejectsMissingAndUnknownKeys) {
  std::string text = valid_text();
  const std::size_t start = text.find("  \"payload_mass\"");
  text.erase(start, text.find('\n', start) - start + 1);
  EXPECT_TRUE(Contains(read_error(text), "missing key \"payload_mass\" (the payload's mass in kg)"));
  std::string misspelt = valid_text();
  misspelt.replace(misspelt.find("strut_damping"), 13, "strut_dampng");
  EXPECT_TRUE(Contains(read_error(misspelt), "unknown key \"strut_dampng\""));
}

TEST(HexapodGeometryFile, RejectsMalformedJsonWithLineAndColumn) {
  const std::string text = "{\n  \"payload_mass\": 1,\n  oops\n}";
  const std::string error = read_error(text);
  EXPECT_TRUE(Contains(error, "G.json:3:"));
  EXPECT_TRUE(Contains(error, "not valid JSON"));
  EXPECT_TRUE(Contains(read_error(""), "not valid JSON"));
  EXPECT_TRUE(Contains(read_error("[1, 2, 3]"), "must hold a JSON object"));
}

TEST(HexapodGeometryFile, ReadsAFileAndNamesAMissingOne) {
  const std::string path = ::testing::TempDir() + "spdfit_geometry_test.json";
  {
    std::ofstream file(path);
    file << valid_text();
  }
  EXPECT_NO_THROW(hexapod::read_geometry(path));
  try {
    hexapod::read_geometry(path + ".missing");
    ADD_FAILURE() << "a missing file was read";
  } catch (const io::DataError& e) {
    EXPECT_TRUE(Contains(std::string(e.what()), "spdfit_geometry_test.json.missing: no such file"));
  }
}

}  // namespace
}  // namespace spdfit

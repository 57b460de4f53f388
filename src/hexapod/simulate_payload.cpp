// Simulated measurements of a hexapod whose true payload is not the geometry's nominal one.
#include "spdfit/hexapod/model.hpp"
#include "spdfit/hexapod/simulate.hpp"

namespace spdfit::hexapod {

Measurements simulate(const Geometry& geometry, const RigidBodyInertia& payload, const SimulationOptions& options,
                      std::uint64_t seed) {
  return simulate(Eigen::MatrixXd(joint_space_mass_matrix(geometry, payload)), options, seed);
}

}  // namespace spdfit::hexapod

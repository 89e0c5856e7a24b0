#include "algorithms/evolution/velocity.hpp"

#include "algorithms/evolution/velocities/velocities.hpp"

namespace dtsl {

double mean_curvature(const Vec3& gradient, const Mat3& hessian) {
  const double g2 = gradient.squaredNorm();
  if (!(g2 > 0.0)) return 0.0;
  const double g = std::sqrt(g2);
  // div(grad f / |grad f|) = tr H / |grad f| - grad f^T H grad f / |grad f|^3.
  return (hessian.trace() - gradient.dot(hessian * gradient) / g2) / g;
}

Registry<Velocity>& velocities() {
  static Registry<Velocity> registry("velocity");
  return registry;
}

void register_velocities() {
  static bool done = false;
  if (done) return;
  done = true;
  add_distance_velocity(velocities());
  add_geodesic_velocity(velocities());
  add_distance_balloon_velocity(velocities());
}

}  // namespace dtsl

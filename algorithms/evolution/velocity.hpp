// Normal velocities of the level-set evolution (docs/design.md §1; paper §2.1: "prescribed, data-driven
// normal velocities ... motivated by earlier work in the field of image processing [9]"). The zero
// level set moves with normal speed v, v < 0 inward (f is negative inside):
//
//     df/dt + v |grad f| = 0 .
//
// A velocity is a plugin: a name in velocities(), an options struct, and a pure function of what is
// known at one point of the zero set (VelocitySample). The evolution samples the zero set, fills the
// samples and asks the plugin for v; nothing else about the data reaches a velocity.
#pragma once

#include <memory>
#include <string>

#include "framework/config/options.hpp"
#include "framework/core/implicit.hpp"
#include "framework/registry/registry.hpp"

namespace dtsl {

/// What a velocity may read at a point x of the current zero set.
struct VelocitySample {
  Vec3 position = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();    ///< n = grad f / |grad f| (outward)
  double curvature = 0.0;         ///< kappa = div n (sum of principal curvatures; 2/r on a sphere of radius r)
  double distance = 0.0;          ///< d(x): distance to the nearest data point
  Vec3 distance_gradient = Vec3::Zero();  ///< grad d: unit direction away from that point (0 if d = 0)
  double cell_size = 0.0;         ///< side of the T-mesh leaf holding x (the local resolution)
  /// Only for velocities whose wants_support() is true, and only where their speed without it is
  /// slower inward than kStalledSpeed: the zero set spans empty space here (support.hpp), e.g. a
  /// membrane over a through-hole or across the gap between two objects.
  bool unsupported = false;
  /// Only with the above: the local sampling spacing h at the nearest data point (support.hpp).
  double spacing = 0.0;
};

/// Inward speeds slower than this (in units of the far-field speed 1 of `geodesic`) count as stalled:
/// only there is the support test (support.hpp, a ray per point) worth its cost.
constexpr double kStalledSpeed = 0.5;

class Velocity {
 public:
  virtual ~Velocity() = default;
  virtual Options& options() = 0;
  virtual const Options& options() const = 0;
  /// A copy with the same options (EvolutionOptions is a value type).
  virtual std::unique_ptr<Velocity> clone() const = 0;
  /// The normal speed v at the sample; v < 0 moves the surface inward.
  virtual double speed(const VelocitySample& s) const = 0;
  /// Whether speed() reads VelocitySample::unsupported; the evolution then tests support where the
  /// speed without it is stalled and asks again with the answer.
  virtual bool wants_support() const { return false; }
};

/// kappa = div (grad f / |grad f|) = (tr H - n^T H n) / |grad f| from the gradient and Hessian of f;
/// 0 where grad f vanishes (no normal). Positive where the surface is convex seen from outside.
double mean_curvature(const Vec3& gradient, const Mat3& hessian);

Registry<Velocity>& velocities();

/// Adds `distance`, `geodesic` and `distance_balloon` to velocities(). Idempotent.
void register_velocities();

}  // namespace dtsl

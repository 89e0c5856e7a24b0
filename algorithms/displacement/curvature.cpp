// Paper §3.2: curvature radii from the implicit function, and the flipped-triangle test.
#include "algorithms/displacement/curvature.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace dtsl {

double PrincipalCurvatures::min_radius() const {
  const double k = std::max(std::abs(k1), std::abs(k2));
  return valid && k > 0 ? 1.0 / k : std::numeric_limits<double>::infinity();
}

PrincipalCurvatures principal_curvatures(const Vec3& g, const Mat3& H) {
  PrincipalCurvatures c;
  const double gn = g.norm();
  if (!(gn > 1e-300) || !H.allFinite() || !g.allFinite()) return c;
  const Vec3 n = g / gn;
  const Mat3 P = Mat3::Identity() - n * n.transpose();
  Mat3 S = P * H * P / gn;
  S = 0.5 * (S + S.transpose());
  Eigen::SelfAdjointEigenSolver<Mat3> es(S);
  // One eigenvector is n (eigenvalue 0); the other two span the tangent plane.
  int normal_index = 0;
  double best = -1;
  for (int i = 0; i < 3; ++i) {
    const double a = std::abs(es.eigenvectors().col(i).dot(n));
    if (a > best) best = a, normal_index = i;
  }
  double k[2];
  for (int i = 0, j = 0; i < 3; ++i)
    if (i != normal_index) k[j++] = es.eigenvalues()[i];
  if (std::abs(k[1]) > std::abs(k[0])) std::swap(k[0], k[1]);
  // With f < 0 inside, a sphere has H = positive: the convex sign convention is positive.
  c.k1 = k[0];
  c.k2 = k[1];
  c.valid = std::isfinite(c.k1) && std::isfinite(c.k2);
  return c;
}

PrincipalCurvatures principal_curvatures(const ImplicitFunction& f, const Vec3& x) {
  Vec3 g;
  Mat3 H;
  f.evaluate(x, &g, &H);
  return principal_curvatures(g, H);
}

std::vector<int> flipped_faces(const TriangleMesh& before, const std::vector<Vec3>& after, const std::vector<int>* candidates) {
  std::vector<int> out;
  auto test = [&](int fi) {
    const Face& f = before.faces[fi];
    const Vec3 n0 = (before.vertices[f[1]] - before.vertices[f[0]]).cross(before.vertices[f[2]] - before.vertices[f[0]]);
    const Vec3 n1 = (after[f[1]] - after[f[0]]).cross(after[f[2]] - after[f[0]]);
    if (!(n1.norm() > 1e-14 * std::max(1.0, n0.norm())) || n0.dot(n1) <= 0) out.push_back(fi);
  };
  if (candidates)
    for (int fi : *candidates) test(fi);
  else
    for (int fi = 0; fi < static_cast<int>(before.faces.size()); ++fi) test(fi);
  return out;
}

}  // namespace dtsl

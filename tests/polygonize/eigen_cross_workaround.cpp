// WORKAROUND, to delete once framework/core/sampling.cpp includes <Eigen/Geometry>: that file calls
// Vec3 differences' cross() with only <Eigen/Core> included, so the template is declared but never
// defined there and test_polygonize (which uses sample_surface) fails to link. This explicit
// instantiation supplies the definition (a weak symbol, harmless once sampling.cpp is fixed).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace {
using Diff = Eigen::CwiseBinaryOp<Eigen::internal::scalar_difference_op<double, double>, const Eigen::Vector3d,
                                  const Eigen::Vector3d>;
}
template Eigen::MatrixBase<Diff>::cross_product_return_type<Diff>::type Eigen::MatrixBase<Diff>::cross<Diff>(
    const Eigen::MatrixBase<Diff>&) const;

// `eigen_ldlt`: the normal equations A^T W A X = A^T W B of the decoupled problem (one matrix, three
// right-hand sides: x, y, z), factored once by Eigen's SimplicialLDLT. Every sharp vertex carries its
// own bilateral row (Eq. 7, weight w > 0), so A^T W A is positive definite.
#include <Eigen/Sparse>
#include <string>

#include "algorithms/sharpen/sharpen_solver.hpp"
#include "framework/core/error.hpp"

namespace dtsl::sharpen {

namespace {

struct EigenLdltOptions final : Options {
  double regularization = 0.0;

  void visit(FieldVisitor& v) override {
    v.field("regularization", regularization, "added to the normal matrix's diagonal (0: none)");
  }
  void check() const override { check_non_negative("regularization", regularization); }
};

class EigenLdlt final : public SharpenSolver {
 public:
  Options& options() override { return o_; }
  Eigen::MatrixX3d solve(const LinearLeastSquares& p) override {
    o_.check();
    const int n = p.unknowns;
    Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(n, 3);
    std::vector<Eigen::Triplet<double>> trip;
    for (const auto& r : p.rows)
      for (int a = 0; a < r.count; ++a) {
        rhs.row(r.unknowns[a]) += r.weight * r.coeffs[a] * r.rhs.transpose();
        for (int b = 0; b < r.count; ++b)
          trip.emplace_back(r.unknowns[a], r.unknowns[b], r.weight * r.coeffs[a] * r.coeffs[b]);
      }
    for (int i = 0; i < n && o_.regularization > 0.0; ++i) trip.emplace_back(i, i, o_.regularization);
    Eigen::SparseMatrix<double> N(n, n);
    N.setFromTriplets(trip.begin(), trip.end());  // duplicates are summed
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(N);
    if (ldlt.info() != Eigen::Success)
      throw AlgorithmError("sharpen solver eigen_ldlt: factorisation of the " + std::to_string(n) +
                           " x " + std::to_string(n) + " normal matrix failed (singular problem)");
    Eigen::MatrixX3d x = ldlt.solve(rhs);
    if (ldlt.info() != Eigen::Success || !x.allFinite())
      throw AlgorithmError("sharpen solver eigen_ldlt: solve failed (non-finite solution)");
    return x;
  }

 private:
  EigenLdltOptions o_;
};

}  // namespace

void add_eigen_ldlt_sharpen_solver(Registry<SharpenSolver>& registry) {
  registry.add("eigen_ldlt", "sparse normal equations factored by Eigen's SimplicialLDLT (x, y, z at once)",
               [] { return std::make_unique<EigenLdlt>(); });
}

}  // namespace dtsl::sharpen

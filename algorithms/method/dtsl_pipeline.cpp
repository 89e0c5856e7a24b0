#include "algorithms/method/dtsl_pipeline.hpp"

#include <cmath>

#include "algorithms/displacement/displacement.hpp"
#include "algorithms/evolution/evolution.hpp"
#include "algorithms/polygonize/polygonizer.hpp"
#include "algorithms/sharpen/bilateral_evolution.hpp"
#include "algorithms/sharpen/sharpen_solver.hpp"
#include "framework/config/prefixed_visitor.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"
#include "framework/pipeline/reconstructor.hpp"

namespace dtsl {

namespace {

constexpr int kMaxStepHalvings = 3;

struct DtslOptions final : Options {
  EvolutionOptions evolution;
  std::string polygonizer = "marching_triangulation";
  double step_factor = 0.2;  // delta = step_factor x l_T (paper §2.2: 0.2)
  double min_step = 0.008;
  bool displacement = true;
  DisplacementOptions displace;
  bool sharpen = true;
  sharpen::BilateralEvolutionOptions bilateral;

  void visit(FieldVisitor& v) override {
    PrefixedVisitor e(v, "evolution_");
    evolution.visit(e);
    v.field("polygonizer", polygonizer, "initial mesh: marching_triangulation (paper §2.2) or marching_cubes");
    v.field("step_factor", step_factor,
            "marching step delta = step_factor x l_T, l_T the diameter of the finest T-mesh cells (paper: 0.2)");
    v.field("min_step", min_step, "lower bound of delta (frame units): keeps the initial mesh's size bounded");
    v.field("displacement", displacement, "run Phase 2, the displacement mapping (paper §3); false: MD = MI");
    PrefixedVisitor d(v, "displace_");
    displace.visit(d);
    v.field("sharpen", sharpen, "run Phase 3, the data-driven bilateral evolution (paper §4); false: MS = MD");
    PrefixedVisitor b(v, "bilateral_");
    bilateral.visit(b);
  }
  void check() const override {
    checked_with_prefix("evolution_", [&] { evolution.check(); });
    check_range("step_factor", step_factor, 0.01, 2.0);
    check_range("min_step", min_step, 1e-4, 0.5);
    require(polygonizers().contains(polygonizer), "polygonizer",
            "unknown polygonizer '" + polygonizer + "' (see `dtsl list polygonizer`)");
    checked_with_prefix("displace_", [&] { displace.check(); });
    checked_with_prefix("bilateral_", [&] { bilateral.check(); });
  }
};

class DtslPipeline final : public Reconstructor {
 public:
  Options& options() override { return options_; }

  ReconstructionResult reconstruct(const PointCloud& cloud, const RunContext& /*context*/) override {
    if (cloud.size() < 4)
      throw AlgorithmError("dtsl: needs at least 4 points, got " + std::to_string(cloud.size()));
    check_finite(cloud, "dtsl input");
    const std::vector<Vec3>& points = cloud.points;
    ReconstructionResult result;

    // TL: Phase 1, the T-spline level set (paper §2.1).
    Stopwatch clock;
    LevelSetResult level = compute_level_set(points, options_.evolution);
    StageRecord tl{"TL", clock.seconds(), std::nullopt, "", level.summary};
    tl.summary["control_points"] = level.level_set.basis().size();
    tl.summary["iterations"] = level.history.size();
    tl.summary["stop_reason"] = level.stop_reason;
    result.stages.push_back(tl);
    result.summary["nt"] = level.level_set.basis().size();
    const TSpline& f = level.level_set;

    // MT: the initial mesh MI (paper §2.2), step 0.2 l_T.
    const Octree& tree = f.tmesh();
    const double finest = tree.unit() * std::pow(2.0, tree.max_depth() - tree.finest_leaf_level());  // finest cell side
    const double delta = std::max(options_.min_step, options_.step_factor * std::sqrt(3.0) * finest);
    clock.restart();
    // A step too large for the level set's curvature somewhere is reported by the polygonizer; the
    // remedy it names is a smaller step, so halve it (a bounded number of times) rather than fail.
    double step = delta;
    int retries = 0;
    std::optional<PolygonizeResult> mi;
    for (;;) {
      auto polygonizer = polygonizers().create(options_.polygonizer, "polygonizer");
      apply_assignment(polygonizer->options(), "step", std::to_string(step), "polygonizer");
      try {
        mi = polygonizer->polygonize(f, points);
        break;
      } catch (const AlgorithmError&) {
        if (++retries > kMaxStepHalvings || step / 2 < options_.min_step) throw;
        step /= 2;
      }
    }
    StageRecord mt{"MT", clock.seconds(), mi->mesh, "MI", to_json(mi->summary)};
    mt.summary["step"] = step;
    mt.summary["step_halvings"] = retries;
    result.stages.push_back(mt);
    result.summary["delta"] = step;

    // D-Map: displacement along grad f (paper §3).
    TriangleMesh md = mi->mesh;
    if (options_.displacement) {
      clock.restart();
      DisplacementResult dr = displace_mesh(f, mi->mesh, points, options_.displace);
      md = dr.mesh;
      result.stages.push_back({"D-Map", clock.seconds(), md, "MD", dr.summary});
    }

    // B-Evl: sharp features (paper §4), filter widths from the marching step.
    TriangleMesh ms = md;
    if (options_.sharpen) {
      clock.restart();
      sharpen::BilateralEvolutionOptions b = options_.bilateral;
      b.delta = step;
      sharpen::BilateralEvolutionResult br = sharpen::bilateral_evolution(md, points, b);
      ms = br.mesh;
      result.stages.push_back({"B-Evl", clock.seconds(), ms, "MS", br.summary});
    }
    result.mesh = ms;
    return result;
  }

 private:
  DtslOptions options_;
};

}  // namespace

void register_dtsl_pipeline() {
  static bool done = false;
  if (done) return;
  done = true;
  register_velocities();
  register_level_set_solvers();
  register_polygonizers();
  register_displacers();
  sharpen::register_sharpen_solvers();
  reconstructors().add("dtsl", "the paper's method: T-spline level set, marching triangulation, displacement, bilateral evolution",
                       [] { return std::make_unique<DtslPipeline>(); });
}

}  // namespace dtsl

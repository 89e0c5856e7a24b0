#include "algorithms/method/dtsl_pipeline.hpp"

#include <cmath>

#include "algorithms/displacement/displacement.hpp"
#include "algorithms/evolution/data_fit.hpp"
#include "algorithms/evolution/evolution.hpp"
#include "algorithms/method/dtsl_presets.hpp"
#include "algorithms/method/refine_on_flip.hpp"
#include "algorithms/method/refinement_guard.hpp"
#include "algorithms/method/stage_checks.hpp"
#include "algorithms/method/tmesh_lines.hpp"
#include "algorithms/polygonize/polygonizer.hpp"
#include "algorithms/sharpen/bilateral_evolution.hpp"
#include "algorithms/sharpen/sharpen_solver.hpp"
#include "framework/config/prefixed_visitor.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"
#include "framework/metrics/metrics.hpp"
#include "framework/pipeline/reconstructor.hpp"

namespace dtsl {

namespace {

constexpr int kMaxStepHalvings = 3;

struct DtslOptions final : Options {
  EvolutionOptions evolution;
  std::string polygonizer = "marching_triangulation";
  /// When the polygonizer fails even at the halved steps (marching triangulation on a part thinner than its
  /// step), mesh with this one at the first step instead, and say so in the MT record ('none': fail).
  std::string polygonizer_fallback = "marching_cubes";
  double step_factor = 0.2;  // delta = step_factor x l_T (paper §2.2: 0.2)
  /// Lower bound of delta, 1/500 of the [-1,1] box's side: keeps the initial mesh's size bounded.
  double min_step = 0.004;
  bool displacement = true;
  DisplacementOptions displace;
  int flip_refinements = 2;
  bool refinement_guard = true;
  /// Marching-cubes step of the mesh of the level set halfway through the evolution (stage mesh 'LS', the
  /// paper's Fig. 1(b), for figures; not timed), 3/200 of the box's side; 0: none.
  double midway_step = 0.03;
  bool sharpen = true;
  sharpen::BilateralEvolutionOptions bilateral;

  // The level set approaches the data with `geodesic` (unit speed until it meets the data, so it
  // reaches into concavities before they close over: no membranes between limbs) and settles in the
  // coarse-to-fine rounds with `distance_balloon` (a push that grows with the distance to the data:
  // it opens through-holes and draws back out of holes in the data). Measured against each velocity
  // alone in configs/ablation_velocity.yaml: neither alone keeps both the block's genus and the
  // armadillo's concavities.
  DtslOptions() {
    evolution.velocity = "geodesic";
    evolution.fine_velocity = "distance_balloon";
  }

  void visit(FieldVisitor& v) override {
    PrefixedVisitor e(v, "evolution_");
    evolution.visit(e);
    v.field("polygonizer", polygonizer, "initial mesh: marching_triangulation (paper §2.2) or marching_cubes");
    v.field("step_factor", step_factor,
            "marching step delta = step_factor x l_T, l_T the diameter of the finest T-mesh cells (paper: 0.2)");
    v.field("refinement_guard", refinement_guard,
            "keep the final refinement's fit only where it adds no components or handles to the evolved zero set "
            "(refinement_guard.hpp: a fit across a part thinner than two cells severs it); else scale it back "
            "(alpha = 1/2, 1/4, 0); the TL record says what was kept");
    v.field("displacement", displacement, "run Phase 2, the displacement mapping (paper §3); false: MD = MI");
    PrefixedVisitor d(v, "displace_");
    displace.visit(d);
    v.field("flip_refinements", flip_refinements,
            "paper §3.2: when displacement flips triangles, refine the level set one level near the flips "
            "(final refinement with the flips as focus), re-triangulate and displace again, at most this many "
            "times; the result with the fewest flips is kept (0: never)");
    v.field("sharpen", sharpen, "run Phase 3, the data-driven bilateral evolution (paper §4); false: MS = MD");
    PrefixedVisitor b(v, "bilateral_");
    bilateral.visit(b);
  }
  void check() const override {
    checked_with_prefix("evolution_", [&] { evolution.check(); });
    check_range("step_factor", step_factor, 0.01, 2.0);
    check_range("min_step", min_step, 1e-4, 0.5);
    check_range("flip_refinements", flip_refinements, 0, 10);
    require(midway_step == 0.0 || (midway_step >= 0.005 && midway_step <= 0.5), "midway_step",
            "must be 0 (none) or in [0.005, 0.5], got " + std::to_string(midway_step));
    require(polygonizers().contains(polygonizer), "polygonizer",
            "unknown polygonizer '" + polygonizer + "' (see `dtsl list polygonizer`)");
    require(polygonizer_fallback == "none" || polygonizers().contains(polygonizer_fallback), "polygonizer_fallback",
            "unknown polygonizer '" + polygonizer_fallback + "' (see `dtsl list polygonizer`; 'none' to fail)");
    checked_with_prefix("displace_", [&] { displace.check(); });
    checked_with_prefix("bilateral_", [&] { bilateral.check(); });
  }
};

class DtslPipeline final : public Reconstructor {
 public:
  Options& options() override { return options_; }

  ReconstructionResult reconstruct(const PointCloud& cloud, const RunContext& context) override {
    if (cloud.size() < 4)
      throw AlgorithmError("dtsl: needs at least 4 points, got " + std::to_string(cloud.size()));
    check_finite(cloud, "dtsl input");
    const std::vector<Vec3>& points = cloud.points;
    // The level-set stage's data (evolution_max_points, thin_points.hpp); also the polygonizers' seeds,
    // which need a point near every component, not a million of them (22 s of marching-cubes seeding
    // on 1M points before).
    const std::vector<Vec3> level_set_points = level_set_data(points, options_.evolution);
    ReconstructionResult result;

    // TL: Phase 1, the T-spline level set (paper §2.1).
    context.stage_started("TL", "evolving the T-spline level set");
    Stopwatch clock;
    LevelSetResult level = compute_level_set(points, options_.evolution);
    StageRecord tl{"TL", clock.seconds(), std::nullopt, "", level.summary, std::nullopt};
    tl.summary["control_points"] = level.level_set.basis().size();
    tl.summary["iterations"] = int(level.history.size()) - 1;
    // Per-step record without the solver details (convergence plots, `dtsl report`).
    nlohmann::json history = nlohmann::json::array();
    for (const IterationRecord& r : level.history) {
      nlohmann::json j = to_json(r);
      j.erase("solve");
      history.push_back(std::move(j));
    }
    tl.summary["history"] = std::move(history);
    tl.summary["stop_reason"] = level.stop_reason;
    // The intermediate level set of the paper's Fig. 1(b), outside the timed phases.
    if (options_.midway_step > 0.0 && level.midway) {
      try {
        auto cubes = polygonizers().create("marching_cubes", "polygonizer");
        apply_assignment(cubes->options(), "step", std::to_string(options_.midway_step), "polygonizer");
        tl.mesh = cubes->polygonize(*level.midway, level_set_points).mesh;
        tl.mesh_label = "LS";
      } catch (const AlgorithmError&) {
        // A figure only: a level set the cubes cannot mesh leaves the stage without it.
      }
    }
    TSpline f = level.level_set;

    // MT's marching step, 0.2 l_T (paper §2.2), from the finest cells of the level set's T-mesh.
    const Octree& tree = f.tmesh();
    const double finest = tree.unit() * std::pow(2.0, tree.max_depth() - tree.finest_leaf_level());  // finest cell side
    const double delta = std::max(options_.min_step, options_.step_factor * std::sqrt(3.0) * finest);

    // The final refinement may not add components or handles (refinement_guard.hpp). The topology is
    // that of marching cubes at half the finest cell side: it meshes any level set (marching
    // triangulation may need halved steps on the coarser evolved one: 3 s on the holed bunny), resolves
    // parts of two cells, and is cheaper than cubes at MT's step. Timed as TL.
    if (options_.refinement_guard && !level.transferred.empty()) {
      Stopwatch guard_clock;
      const double cube = std::max(delta, 0.5 * finest);
      const TopologyOf topology_of = [&](const TSpline& candidate, double) -> std::optional<ZeroSetTopology> {
        auto cubes = polygonizers().create("marching_cubes", "polygonizer");
        apply_assignment(cubes->options(), "step", std::to_string(cube), "polygonizer");
        try {
          const MeshStats s = mesh_stats(cubes->polygonize(candidate, level_set_points).mesh);
          return ZeroSetTopology{int(s.components), s.genus};
        } catch (const AlgorithmError&) {
          return std::nullopt;
        }
      };
      GuardedRefinement guarded = guard_refinement_topology(level.evolved, f, level.transferred, topology_of);
      f = std::move(guarded.level_set);
      // The refinement record's distances describe the whole fit; these, the level set kept.
      const DataFit kept = data_fit(f, level_set_points);
      guarded.summary["mean_distance_kept"] = kept.mean;
      guarded.summary["max_distance_kept"] = kept.max;
      const double guard_seconds = guard_clock.seconds();
      tl.seconds += guard_seconds;
      tl.summary["refinement_guard"] = std::move(guarded.summary);
      tl.summary["refinement_guard"]["seconds"] = guard_seconds;
      tl.summary["refinement_guard"]["cube_side"] = cube;
    }
    result.stages.push_back(tl);
    result.summary["nt"] = f.basis().size();

    // MT: the initial mesh MI (paper §2.2).
    context.stage_started("MT", "triangulating the level set");
    clock.restart();
    int retries = 0;
    double step = delta;
    std::string fallback;
    std::optional<PolygonizeResult> mi = polygonize(f, level_set_points, step, retries, fallback);
    const StageBounds bounds = stage_bounds(points);
    const StageCheck mi_check = check_stage_mesh("MT", mi->mesh, bounds);
    StageRecord mt{"MT", clock.seconds(), mi->mesh, "MI", to_json(mi->summary), std::nullopt};
    mt.summary["output_check"] = mi_check.to_json();
    mt.summary["step"] = step;
    mt.summary["step_halvings"] = retries;
    if (!fallback.empty()) mt.summary["fallback"] = {{"polygonizer", options_.polygonizer_fallback}, {"reason", fallback}};
    result.stages.push_back(mt);
    result.summary["delta"] = step;

    // D-Map: displacement along grad f (paper §3), with the refinement fallback on flipped triangles.
    TriangleMesh md = mi->mesh;
    if (options_.displacement) {
      context.stage_started("D-Map", "displacing the mesh onto the data");
      clock.restart();
      MeshedLevelSet current{std::move(f), std::move(*mi), step, retries, fallback};
      FlipRefinement how;
      how.rounds = options_.flip_refinements;
      how.refine = options_.evolution.refinement;
      how.solver = &options_.evolution.solver_plugin();
      how.triangulate = [&](MeshedLevelSet& m) {  // at m.step, with the polygonizer that made MI
        const std::string& name = m.fallback.empty() ? options_.polygonizer : options_.polygonizer_fallback;
        auto polygonizer = polygonizers().create(name, "polygonizer");
        apply_assignment(polygonizer->options(), "step", std::to_string(m.step), "polygonizer");
        m.mi = polygonizer->polygonize(m.f, level_set_points);
      };
      how.check = [&](TriangleMesh& mesh) { check_stage_mesh("MT (refined near flips)", mesh, bounds); };
      DisplacementResult dr = displace_refining_on_flips(current, points, level_set_points, options_.displace, how);
      f = std::move(current.f);
      mi = std::move(current.mi);
      step = current.step;
      retries = current.halvings;
      fallback = current.fallback;
      dr.summary["control_points"] = f.basis().size();
      result.stages[1].mesh = mi->mesh;  // MI: the base mesh the kept displacement started from
      // ... and MT's record describes that mesh (after an accepted round: the refined level set's).
      nlohmann::json& mt_summary = result.stages[1].summary;
      mt_summary = to_json(mi->summary);
      mt_summary["output_check"] = check_stage_mesh("MT", mi->mesh, bounds).to_json();
      mt_summary["step"] = step;
      mt_summary["step_halvings"] = retries;
      if (!fallback.empty()) mt_summary["fallback"] = {{"polygonizer", options_.polygonizer_fallback}, {"reason", fallback}};
      result.summary["delta"] = step;
      result.summary["nt"] = f.basis().size();
      md = dr.mesh;
      dr.summary["output_check"] = check_moving_stage("D-Map", md, bounds, mi->mesh).to_json();
      result.stages.push_back({"D-Map", clock.seconds(), md, "MD", dr.summary, std::nullopt});
    }

    // The T-mesh of the final level set (after any refinement near flips) for the figure of points +
    // T-mesh (the paper's Fig. 1a), outside the timed phases: the leaves holding data (where the octree
    // was refined for them) or a vertex of MI (where the zero set crosses, holes included; the two
    // differ where Phase 1 misses the data). tmesh_lines.hpp says why not all leaves.
    std::vector<Vec3> held = level_set_points;
    held.insert(held.end(), mi->mesh.vertices.begin(), mi->mesh.vertices.end());
    result.stages.front().lines = StageLines{"tmesh", "T-mesh", tmesh_edges_around(f.tmesh(), held)};
    result.summary["tmesh_leaves"] = f.tmesh().leaf_count();

    // B-Evl: sharp features (paper §4), filter widths from the marching step.
    TriangleMesh ms = md;
    if (options_.sharpen) {
      context.stage_started("B-Evl", "recovering sharp features");
      clock.restart();
      sharpen::BilateralEvolutionOptions b = options_.bilateral;
      b.delta = step;
      sharpen::BilateralEvolutionResult br = sharpen::bilateral_evolution(md, points, b);
      ms = br.mesh;
      br.summary["output_check"] = check_moving_stage("B-Evl", ms, bounds, md).to_json();
      result.stages.push_back({"B-Evl", clock.seconds(), ms, "MS", br.summary, std::nullopt});
    }
    result.mesh = ms;
    return result;
  }

 private:
  /// The mesh of f = 0 at marching step `step`. A step too large for the level set's curvature somewhere
  /// is reported by the polygonizer; the remedy it names is a smaller step, so halve it (at most
  /// kMaxStepHalvings times, never below min_step); when it still fails, polygonizer_fallback at the
  /// first step, with the failure's message in `fallback`. `step` and `halvings` return what was used
  /// (halvings: the attempts that failed). Both errors, by name, when nothing meshes.
  std::optional<PolygonizeResult> polygonize(const TSpline& f, const std::vector<Vec3>& points, double& step,
                                             int& halvings, std::string& fallback) const {
    const double first_step = step;
    for (;;) {
      auto polygonizer = polygonizers().create(options_.polygonizer, "polygonizer");
      apply_assignment(polygonizer->options(), "step", std::to_string(step), "polygonizer");
      try {
        return polygonizer->polygonize(f, points);
      } catch (const AlgorithmError& e) {
        if (++halvings > kMaxStepHalvings || step / 2 < options_.min_step) {
          if (options_.polygonizer_fallback == "none" || options_.polygonizer_fallback == options_.polygonizer) throw;
          fallback = e.what();
          step = first_step;
          auto backup = polygonizers().create(options_.polygonizer_fallback, "polygonizer_fallback");
          apply_assignment(backup->options(), "step", std::to_string(step), "polygonizer_fallback");
          try {
            return backup->polygonize(f, points);
          } catch (const AlgorithmError& again) {
            throw AlgorithmError(fallback + "; then the fallback " + again.what());
          }
        }
        step /= 2;
      }
    }
  }

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
  register_dtsl_presets();
}

}  // namespace dtsl

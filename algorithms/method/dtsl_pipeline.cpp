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
  //
  // The level set starts from the data's carving united with its wrap (data_carving.hpp), so the data
  // decide the topology, on a T-mesh refined toward them; the one evolution then runs with the rounds'
  // `distance_balloon`, and the final refinement is off (it added handles the evolution had not:
  // results/suite_dev/wrap_x, 13 vs 12 of 24 inputs with the truth's topology). Dev half of the topology
  // suite (results/suite_dev/carve_x, docs/experiments.md): the truth's topology on 15 of 24 inputs, the
  // sphere on 7.
  DtslOptions() {
    evolution.velocity = "geodesic";
    evolution.fine_velocity = "distance_balloon";
    evolution.initial = "carve";
    evolution.wrap_alpha = 2.5;
    evolution.final_refinement = false;
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

/// The step a polygonizer is given: `step` to 6 decimals in the [-1,1]^3 frame (1e-6 of the box's
/// half-width), the precision every committed result was made with. Marching triangulation's mesh
/// depends on the step's last digits (a step 4e-7 smaller meshes fandisk with a second, overlapping
/// component or needs a halved step on the bunny: docs/robustness.md), so the step it sees is fixed to
/// these digits; the stages after MT take the step itself.
double polygonizer_step(double step) { return std::round(step * 1e6) / 1e6; }

/// The side of the finest cells of f's T-mesh (their diameter is l_T of paper §2.2).
double finest_cell_side(const TSpline& f) {
  const Octree& tree = f.tmesh();
  return tree.unit() * std::pow(2.0, tree.max_depth() - tree.finest_leaf_level());
}

/// TL's record: the level-set stage's summary, its per-step history without the solver details
/// (convergence plots, `dtsl report`), counts and stop reason.
StageRecord level_set_record(const LevelSetResult& level, double seconds) {
  StageRecord tl{"TL", seconds, std::nullopt, "", level.summary, std::nullopt};
  tl.summary["control_points"] = level.level_set.basis().size();
  tl.summary["iterations"] = int(level.history.size()) - 1;
  nlohmann::json history = nlohmann::json::array();
  for (const IterationRecord& r : level.history) {
    nlohmann::json j = to_json(r);
    j.erase("solve");
    history.push_back(std::move(j));
  }
  tl.summary["history"] = std::move(history);
  tl.summary["stop_reason"] = level.stop_reason;
  return tl;
}

/// The intermediate level set of the paper's Fig. 1(b) as TL's mesh 'LS', outside the timed phases;
/// a figure only, so a level set the cubes cannot mesh leaves the stage without it.
void add_midway_mesh(StageRecord& tl, const LevelSetResult& level, const std::vector<Vec3>& seeds, double step) {
  if (step <= 0.0 || !level.midway) return;
  try {
    tl.mesh = polygonizers().create("marching_cubes", "polygonizer")->polygonize(*level.midway, seeds, polygonizer_step(step)).mesh;
    tl.mesh_label = "LS";
  } catch (const AlgorithmError&) {
  }
}

/// The final refinement may not add components or handles (refinement_guard.hpp): returns the level set
/// kept, and records the choice in TL (timed as TL). The topology is that of marching cubes at
/// `cube` (half the finest cell side, at least the marching step): it meshes any level set (marching
/// triangulation may need halved steps on the coarser evolved one), resolves parts of two cells, and
/// is cheaper than cubes at MT's step.
TSpline guard_refinement(const LevelSetResult& level, const std::vector<Vec3>& level_set_points, double cube,
                         StageRecord& tl) {
  Stopwatch clock;
  const TopologyOf topology_of = [&](const TSpline& candidate, double) -> std::optional<ZeroSetTopology> {
    auto cubes = polygonizers().create("marching_cubes", "polygonizer");
    try {
      const MeshStats s = mesh_stats(cubes->polygonize(candidate, level_set_points, polygonizer_step(cube)).mesh);
      return ZeroSetTopology{int(s.components), s.genus};
    } catch (const AlgorithmError&) {
      return std::nullopt;
    }
  };
  GuardedRefinement guarded = guard_refinement_topology(level.evolved, level.level_set, level.transferred, topology_of);
  // The refinement record's distances describe the whole fit; these, the level set kept.
  const DataFit kept = data_fit(guarded.level_set, level_set_points);
  guarded.summary["mean_distance_kept"] = kept.mean;
  guarded.summary["max_distance_kept"] = kept.max;
  const double seconds = clock.seconds();
  tl.seconds += seconds;
  tl.summary["refinement_guard"] = std::move(guarded.summary);
  tl.summary["refinement_guard"]["seconds"] = seconds;
  tl.summary["refinement_guard"]["cube_side"] = cube;
  return std::move(guarded.level_set);
}

class DtslPipeline final : public Reconstructor {
 public:
  Options& options() override { return options_; }

  ReconstructionResult reconstruct(const PointCloud& cloud, const RunContext& context) override {
    if (cloud.size() < 4)
      throw AlgorithmError("dtsl: needs at least 4 points, got " + std::to_string(cloud.size()));
    check_finite(cloud, "dtsl input");
    const std::vector<Vec3>& points = cloud.points;
    // The level-set stage's data (evolution_max_points, thin_points.hpp); also the polygonizers' seeds,
    // which need a point near every component, not a million of them.
    const std::vector<Vec3> level_set_points = level_set_data(points, options_.evolution);
    const StageBounds bounds = stage_bounds(points);
    ReconstructionResult result;
    MeshedLevelSet base = level_set_and_mesh(points, level_set_points, bounds, context, result);
    TriangleMesh md = base.mi.mesh;
    if (options_.displacement) md = displacement_stage(base, points, level_set_points, bounds, context, result);

    // The T-mesh of the final level set (after any refinement near flips) for the figure of points +
    // T-mesh (the paper's Fig. 1a), outside the timed phases: the leaves holding data (where the octree
    // was refined for them) or a vertex of MI (where the zero set crosses, holes included; the two
    // differ where Phase 1 misses the data). tmesh_lines.hpp says why not all leaves.
    std::vector<Vec3> held = level_set_points;
    held.insert(held.end(), base.mi.mesh.vertices.begin(), base.mi.mesh.vertices.end());
    stage(result, "TL").lines = StageLines{"tmesh", "T-mesh", tmesh_edges_around(base.f.tmesh(), held)};
    result.summary["tmesh_leaves"] = base.f.tmesh().leaf_count();

    result.mesh = options_.sharpen ? sharpening_stage(md, points, base.step, bounds, context, result) : md;
    return result;
  }

 private:
  /// TL (Phase 1, the T-spline level set, paper §2.1) and MT (the initial mesh MI, paper §2.2), their
  /// records appended to `result`. The marching step is step_factor x l_T (paper §2.2: 0.2), at least
  /// min_step.
  MeshedLevelSet level_set_and_mesh(const std::vector<Vec3>& points, const std::vector<Vec3>& level_set_points,
                                    const StageBounds& bounds, const RunContext& context,
                                    ReconstructionResult& result) const {
    context.stage_started("TL", "evolving the T-spline level set");
    Stopwatch clock;
    const LevelSetResult level = compute_level_set(points, options_.evolution);
    StageRecord tl = level_set_record(level, clock.seconds());
    add_midway_mesh(tl, level, level_set_points, options_.midway_step);
    const double finest = finest_cell_side(level.level_set);
    const double delta = std::max(options_.min_step, options_.step_factor * std::sqrt(3.0) * finest);
    TSpline f = options_.refinement_guard && !level.transferred.empty()
                    ? guard_refinement(level, level_set_points, std::max(delta, 0.5 * finest), tl)
                    : level.level_set;
    result.stages.push_back(std::move(tl));
    result.summary["nt"] = f.basis().size();

    context.stage_started("MT", "triangulating the level set");
    clock.restart();
    MeshedLevelSet base{std::move(f), {}, delta, 0, "", {}};
    triangulate(base, level_set_points);
    StageRecord mt{"MT", 0.0, std::nullopt, "MI", nlohmann::json::object(), std::nullopt};
    record_mesh(mt, base, bounds);
    mt.seconds = clock.seconds();
    result.stages.push_back(std::move(mt));
    result.summary["delta"] = base.step;
    return base;
  }

  /// MT's mesh and record from `base`: MI, its check (AlgorithmError on a violation), step, halvings
  /// and any fallback.
  void record_mesh(StageRecord& mt, MeshedLevelSet& base, const StageBounds& bounds) const {
    const StageCheck check = check_stage_mesh("MT", base.mi.mesh, bounds);
    mt.mesh = base.mi.mesh;
    mt.summary = to_json(base.mi.summary);
    mt.summary["output_check"] = check.to_json();
    mt.summary["step"] = base.step;
    mt.summary["step_halvings"] = base.halvings;
    if (!base.halving_reasons.empty()) mt.summary["step_halving_reasons"] = base.halving_reasons;
    if (!base.fallback.empty())
      mt.summary["fallback"] = {{"polygonizer", options_.polygonizer_fallback}, {"reason", base.fallback}};
  }

  /// D-Map: displacement along grad f (paper §3) with the refinement fallback on flipped triangles
  /// (§3.2, refine_on_flip.hpp). `base` ends as the level set and MI the kept displacement started
  /// from, and MT's record describes them. Returns MD.
  TriangleMesh displacement_stage(MeshedLevelSet& base, const std::vector<Vec3>& points,
                                  const std::vector<Vec3>& level_set_points, const StageBounds& bounds,
                                  const RunContext& context, ReconstructionResult& result) const {
    context.stage_started("D-Map", "displacing the mesh onto the data");
    Stopwatch clock;
    FlipRefinement how;
    how.rounds = options_.flip_refinements;
    how.refine = options_.evolution.refinement;
    how.solver = options_.evolution.solver;
    how.triangulate = [&](MeshedLevelSet& m) {  // at m.step, with the polygonizer that made MI
      const std::string& name = m.fallback.empty() ? options_.polygonizer : options_.polygonizer_fallback;
      m.mi = polygonizers().create(name, "polygonizer")->polygonize(m.f, level_set_points, polygonizer_step(m.step));
    };
    how.check = [&](TriangleMesh& mesh) { check_stage_mesh("MT (refined near flips)", mesh, bounds); };
    DisplacementResult dr = displace_refining_on_flips(base, points, level_set_points, options_.displace, how);
    dr.summary["control_points"] = base.f.basis().size();
    record_mesh(stage(result, "MT"), base, bounds);  // after an accepted round: the refined level set's
    result.summary["delta"] = base.step;
    result.summary["nt"] = base.f.basis().size();
    TriangleMesh md = dr.mesh;
    dr.summary["output_check"] = check_moving_stage("D-Map", md, bounds, base.mi.mesh).to_json();
    result.stages.push_back({"D-Map", clock.seconds(), md, "MD", dr.summary, std::nullopt});
    return md;
  }

  /// B-Evl: sharp features (paper §4), filter widths from the marching step `delta`. Returns MS.
  TriangleMesh sharpening_stage(const TriangleMesh& md, const std::vector<Vec3>& points, double delta,
                                const StageBounds& bounds, const RunContext& context,
                                ReconstructionResult& result) const {
    context.stage_started("B-Evl", "recovering sharp features");
    Stopwatch clock;
    sharpen::BilateralEvolutionOptions b = options_.bilateral;
    b.delta = delta;
    sharpen::BilateralEvolutionResult br = sharpen::bilateral_evolution(md, points, b);
    TriangleMesh ms = br.mesh;
    br.summary["output_check"] = check_moving_stage("B-Evl", ms, bounds, md).to_json();
    result.stages.push_back({"B-Evl", clock.seconds(), ms, "MS", br.summary, std::nullopt});
    return ms;
  }

  /// m.mi := the mesh of m.f = 0, starting at marching step m.step. A step too large for the level set's
  /// curvature somewhere is reported by the polygonizer; the remedy it names is a smaller step, so
  /// halve it (at most kMaxStepHalvings times, never below min_step); when it still fails,
  /// polygonizer_fallback at the first step, with the failure's message in m.fallback. m.step and
  /// m.halvings say what was used (halvings: the attempts that failed). Both errors, by name, when
  /// nothing meshes.
  void triangulate(MeshedLevelSet& m, const std::vector<Vec3>& points) const {
    const double first_step = m.step;
    m.halvings = 0;
    m.halving_reasons.clear();
    m.fallback.clear();
    for (;;) {
      try {
        m.mi = polygonizers().create(options_.polygonizer, "polygonizer")->polygonize(m.f, points, polygonizer_step(m.step));
        return;
      } catch (const AlgorithmError& e) {
        m.halving_reasons.emplace_back(e.what());
        if (++m.halvings > kMaxStepHalvings || m.step / 2 < options_.min_step) {
          if (options_.polygonizer_fallback == "none" || options_.polygonizer_fallback == options_.polygonizer) throw;
          m.fallback = e.what();
          m.step = first_step;
          auto backup = polygonizers().create(options_.polygonizer_fallback, "polygonizer_fallback");
          try {
            m.mi = backup->polygonize(m.f, points, polygonizer_step(m.step));
            return;
          } catch (const AlgorithmError& again) {
            throw AlgorithmError(m.fallback + "; then the fallback " + again.what());
          }
        }
        m.step /= 2;
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

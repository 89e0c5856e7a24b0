// Charts made from the metrics records of runs (metrics.json), independent of files: convergence of
// the iterative stages, phase timings, and metric-versus-parameter curves of sweeps.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "framework/render/chart.hpp"

namespace dtsl::report {

/// Convergence of a run's iterative stages: the level-set evolution's history (stages[TL].summary.
/// history: iteration, mean_distance, max_distance, mean_surface_distance, mean_speed, max_speed) and
/// every numeric list "<name>_per_iteration" of a stage's summary (e.g. B-Evl's e_avr_per_iteration).
/// Empty if the record has none.
std::vector<render::LineChart> convergence_charts(const nlohmann::json& record);

/// Whether the record's TL stage carries the per-iteration history (else the report says so).
bool has_evolution_history(const nlohmann::json& record);

/// Seconds per stage of one run, with the evolution's own breakdown (TL summary's evolution_timings)
/// as indented rows. No rows if the record has no stages.
render::BarChart stage_time_chart(const nlohmann::json& record);

/// Every run's time as one stacked bar, segments = stage names in order of appearance.
render::BarChart time_overview_chart(const std::vector<nlohmann::json>& records, const std::string& title);

/// The metrics a sweep plot can show: name, header and the record path.
struct SweepMetric {
  std::string name, label;
  std::vector<std::string> path;
  double scale = 1.0;
  bool log = false;
};
const std::vector<SweepMetric>& sweep_metrics();

/// For sweep axis `key` (as in record["sweep"]) and one metric: one series per (dataset, pipeline,
/// other sweep values), x = the axis' values (numeric if all are numbers, else categories in the
/// order `values` gives). Records without the key are left out; failed runs give gaps.
render::LineChart sweep_chart(const std::vector<nlohmann::json>& records, const std::string& key,
                              const std::vector<std::string>& values, const SweepMetric& metric);

}  // namespace dtsl::report

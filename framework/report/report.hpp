// `dtsl report DIR`: the figures of a result directory (renders of every run's input points and stage
// meshes, convergence and timing charts, metric-versus-parameter charts of sweeps) under DIR/figures/,
// and DIR/report.md showing them together with the experiment's table.
#pragma once

#include <string>
#include <vector>

#include "framework/report/report_options.hpp"

namespace dtsl::report {

struct ReportSummary {
  std::string report_path;
  std::size_t runs = 0, figures = 0;
};

/// FileError if `result_dir` is not a result directory (config.yaml, runs/ with at least one
/// metrics.json). Figures are made in a temporary folder that replaces DIR/figures only when all are
/// written; report.md is written atomically. Plugins must be registered (the config is re-validated).
ReportSummary write_report(const std::string& result_dir, const ReportOptions& options);

/// Lays images out in a grid of `columns`, white background (for several charts in one figure).
render::Image compose(const std::vector<render::Image>& images, int columns);

}  // namespace dtsl::report

// The pictures of meshes a report shows, read from a result directory: one run's ground truth, input
// points and stage meshes, and every run's final mesh on one dataset.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "framework/render/image.hpp"
#include "framework/report/report_options.hpp"

namespace dtsl::report {

/// Ground truth, input points (datasets/<dataset_key>/), the points with the line set a stage left (the
/// file its record's "lines_file" names: the T-mesh of dtsl runs, hidden behind the run's last mesh),
/// then each stage mesh of the run (the files its record's stages name), else its final.ply; each mesh
/// labelled with its e_avr. Empty if none exists. FileError for an unreadable mesh or line file.
render::Image run_renders(const std::filesystem::path& result_dir, const nlohmann::json& record,
                          const std::string& dataset_key, const ReportOptions& options);

/// The points of dataset `dataset_key` and the final mesh of each of `runs` (up to 8), labelled by
/// pipeline and sweep values. Empty if fewer than two meshes exist.
render::Image dataset_comparison(const std::filesystem::path& result_dir, const std::string& dataset_key,
                                 const std::vector<const nlohmann::json*>& runs, const ReportOptions& options);

}  // namespace dtsl::report

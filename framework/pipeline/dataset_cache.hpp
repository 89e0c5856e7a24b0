// A result directory keeps every dataset it used as files (points.ply with normals, ground_truth.ply,
// dataset.json): runs read them instead of rebuilding, and users can open them.
#pragma once

#include <string>

#include "framework/datasets/dataset.hpp"

namespace dtsl {

/// Writes `dataset` into folder `dir` (created); dataset.json last, so its presence means complete.
void write_dataset(const std::string& dir, const Dataset& dataset);

/// Reads a folder written by write_dataset; FileError if incomplete.
Dataset read_dataset(const std::string& dir);

bool dataset_complete(const std::string& dir);

}  // namespace dtsl

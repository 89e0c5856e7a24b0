// A result directory keeps every dataset it used as files (points.ply with normals, ground_truth.ply,
// dataset.json): runs read them instead of rebuilding, and users can open them.
#pragma once

#include <string>

#include "framework/datasets/dataset.hpp"

namespace dtsl {

/// Writes `dataset` into folder `dir` (created) in `frame`, which dataset.json records ("files_frame");
/// in the input's frame also the [-1,1]^3 points and truth the runs read, under normalised/. dataset.json
/// last, so its presence means complete.
void write_dataset(const std::string& dir, const Dataset& dataset, FilesFrame frame);

/// Reads a folder written by write_dataset, back in the [-1,1]^3 frame whatever its files' frame, with
/// its normalisation; FileError if incomplete or if dataset.json's frame is malformed.
Dataset read_dataset(const std::string& dir);

/// Whether `dir` holds a completely written dataset whose files are in `frame`.
bool dataset_complete(const std::string& dir, FilesFrame frame);

}  // namespace dtsl

// An experiment's dataset files in the input's units or the [-1,1]^3 frame (dataset_cache.hpp): the
// runs read back exactly the points they were given, whatever the files' frame.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "framework/core/error.hpp"
#include "framework/io/io.hpp"
#include "framework/pipeline/dataset_cache.hpp"

using namespace dtsl;
namespace fs = std::filesystem;

namespace {

Dataset scaled_dataset() {
  Dataset d;
  d.name = "frames";
  for (int i = 0; i < 50; ++i) d.points.points.push_back(Vec3(std::sin(0.3 * i), std::cos(0.7 * i), 0.02 * i - 0.5));
  TriangleMesh truth;
  truth.vertices = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0.3)};
  truth.faces = {Face{0, 1, 2}};
  d.ground_truth = truth;
  d.normalisation = Similarity{Vec3(250.0, -40.0, 7.0), 0.01};  // input units: a part 200 wide far from 0
  d.description = nlohmann::json::object();
  d.description["normalisation"] = {{"input_to_points", to_json(d.normalisation)}};
  return d;
}

}  // namespace

TEST_CASE("dataset files in the input's units read back exactly in [-1,1]^3", "[frames]") {
  const fs::path dir = fs::temp_directory_path() / ("dtsl_frames_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Dataset d = scaled_dataset();
  for (const FilesFrame frame : {FilesFrame::input, FilesFrame::normalised}) {
    INFO((frame == FilesFrame::input ? "input" : "normalised"));
    const std::string sub = (dir / (frame == FilesFrame::input ? "in" : "norm")).string();
    write_dataset(sub, d, frame);
    CHECK(dataset_complete(sub, frame));
    CHECK_FALSE(dataset_complete(sub, frame == FilesFrame::input ? FilesFrame::normalised : FilesFrame::input));
    // What a user opens: the input's units, or the [-1,1]^3 frame.
    const PointCloud file = read_points(sub + "/points.ply");
    REQUIRE(file.size() == d.points.size());
    for (std::size_t i = 0; i < file.size(); ++i) {
      const Vec3 expected = frame == FilesFrame::input ? d.normalisation.invert(d.points.points[i]) : d.points.points[i];
      CHECK((file.points[i] - expected).norm() < 1e-9 * (1.0 + expected.norm()));
    }
    // What the runs read: the very same coordinates.
    const Dataset back = read_dataset(sub);
    REQUIRE(back.points.size() == d.points.size());
    for (std::size_t i = 0; i < back.points.size(); ++i) CHECK(back.points.points[i] == d.points.points[i]);
    REQUIRE(back.ground_truth);
    CHECK(back.ground_truth->vertices == d.ground_truth->vertices);
    CHECK(back.normalisation.scale == d.normalisation.scale);
    CHECK(back.normalisation.center == d.normalisation.center);
  }
  // A corrupted frame is named.
  const std::string meta = (dir / "in" / "dataset.json").string();
  nlohmann::json j = nlohmann::json::parse(std::ifstream(meta));
  j["files_frame"] = "sideways";
  std::ofstream(meta) << j.dump();
  CHECK_THROWS_WITH(read_dataset((dir / "in").string()), Catch::Contains("files_frame") && Catch::Contains("sideways"));
  fs::remove_all(dir);
}

TEST_CASE("similarities compose and invert", "[frames]") {
  const Similarity a{Vec3(1, 2, 3), 0.5}, b{Vec3(-4, 0, 1), 3.0};
  const Vec3 x(0.3, -7, 2);
  CHECK((a.then(b).apply(x) - b.apply(a.apply(x))).norm() < 1e-12);
  CHECK((a.inverse().apply(a.apply(x)) - x).norm() < 1e-12);
}

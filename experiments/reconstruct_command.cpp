// dtsl reconstruct IN OUT: one point file to one mesh file, in the input's own coordinates.
#include <filesystem>
#include <iostream>

#include "experiments/cli.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/config/yaml_path.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"
#include "framework/io/io.hpp"
#include "framework/pipeline/reconstructor.hpp"

namespace dtsl::cli {

/// The pipeline `dtsl reconstruct` uses when none is named: the paper's method.
constexpr const char* kDefaultPipeline = "dtsl";

int reconstruct_command(Args& args) {
  const std::string name = args.value("pipeline", kDefaultPipeline);
  const std::vector<std::string> sets = args.values("set");
  const std::vector<std::string> rest = args.positionals();
  if (rest.size() != 2) throw UsageError{"reconstruct: expected IN and OUT files"};
  const std::string in = rest[0], out = rest[1];
  const std::string ext = file_extension(out);
  if (ext != "ply" && ext != "obj" && ext != "off")
    throw UsageError{"reconstruct: OUT must end in .ply, .obj or .off, got '" + out + "'"};

  auto pipeline = reconstructors().create(name, "--pipeline");
  for (const std::string& s : sets) {
    const auto [key, value] = split_assignment(s);
    apply_assignment(pipeline->options(), key, value, "--set");
  }
  PointCloud cloud = read_points(in);
  check_finite(cloud, in);
  // Methods work in the paper's [-1,1]^3 frame; the mesh is mapped back to the input's frame.
  const Similarity frame = unit_cube_normalisation(cloud.points, in);
  transform(cloud, frame);
  Stopwatch clock;
  ReconstructionResult result = pipeline->reconstruct(cloud, RunContext{});
  for (Vec3& v : result.mesh.vertices) v = frame.invert(v);
  write_mesh(out, result.mesh);
  std::cerr << name << ": " << cloud.size() << " points -> " << result.mesh.vertices.size() << " vertices, "
            << result.mesh.faces.size() << " triangles in " << clock.seconds() << " s; wrote " << out << "\n";
  return 0;
}

}  // namespace dtsl::cli

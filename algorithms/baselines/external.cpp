// external: any command-line reconstructor as a pipeline, e.g. a reference implementation of another
// paper (iPSR) measured on the same data as the others. The points go to a file in a fresh temporary
// directory, the command runs through /bin/sh with {in} and {out} replaced by the files' paths, and the
// mesh it wrote is read back; the directory is removed however the run ends. The runner times
// reconstruct() as for every pipeline, so the time includes writing and reading the files.
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "algorithms/baselines/baseline.hpp"
#include "algorithms/baselines/shell_command.hpp"
#include "framework/core/error.hpp"
#include "framework/io/io.hpp"

namespace dtsl::baselines {
namespace {

namespace fs = std::filesystem;

struct ExternalOptions final : Options {
  std::string command;
  std::string input_format = "ply";
  bool normals = false;
  std::string output = "ply";
  double timeout_seconds = 600.0;

  void visit(FieldVisitor& v) override {
    v.field("command", command,
            "command line run by /bin/sh, with {in} (the point file) and {out} (the mesh file it must "
            "write) replaced by shell-quoted paths, e.g. \"/tmp/dtsl-yardsticks/ipsr --in {in} --out {out}\"; "
            "required");
    v.field("input_format", input_format,
            "format of {in}: ply (binary little-endian, double x y z), ply_ascii or xyz; points in the "
            "[-1,1]^3 frame");
    v.field("normals", normals, "also write the cloud's normals (nx ny nz); the cloud must have them");
    v.field("output", output, "format of {out}, by its extension: ply, obj or off");
    v.field("timeout_seconds", timeout_seconds, "the command is killed (and the run fails) after this long");
  }

  void check() const override {
    require(!command.empty(), "command", "must be set to a command line containing {in} and {out}");
    require(command.find("{in}") != std::string::npos, "command",
            "must contain the placeholder {in} (the point file), got '" + command + "'");
    require(command.find("{out}") != std::string::npos, "command",
            "must contain the placeholder {out} (the mesh file to write), got '" + command + "'");
    check_one_of("input_format", input_format, {"ply", "ply_ascii", "xyz"});
    check_one_of("output", output_extension(), {"ply", "obj", "off"});
    check_range("timeout_seconds", timeout_seconds, 1e-3, 1e7);
  }

  /// `output` without a leading dot (".ply" is accepted too).
  std::string output_extension() const { return !output.empty() && output[0] == '.' ? output.substr(1) : output; }
};

std::string replace_all(std::string text, const std::string& placeholder, const std::string& value) {
  for (std::size_t at = text.find(placeholder); at != std::string::npos; at = text.find(placeholder, at + value.size()))
    text.replace(at, placeholder.size(), value);
  return text;
}

/// A fresh directory under the system's temporary directory, removed with everything in it when the
/// object goes.
class TemporaryDirectory {
 public:
  explicit TemporaryDirectory(const std::string& method) {
    std::string pattern = (fs::temp_directory_path() / "dtsl-external-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
      throw AlgorithmError(method + ": cannot create a temporary directory like " + pattern);
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

class ExternalReconstructor final : public PointsBaseline {
 public:
  ExternalReconstructor() : PointsBaseline("external") {}
  Options& options() override { return options_; }

 protected:
  InputRequirements requirements() const override { return {10, false}; }
  std::string normals_source() const override { return options_.normals ? "ground_truth" : "none"; }

  TriangleMesh run(const PointCloud& cloud, const RunContext&, nlohmann::json& summary) override {
    const ExternalOptions& o = options_;
    const std::string program = command_program(o.command);
    if (!program_available(program)) {
      const bool present = program.find('/') != std::string::npos && fs::exists(program);
      throw AlgorithmError("skipped: external reconstructor '" + program + "' " +
                           (present ? "is not executable" : "not found") + " (command: " + o.command + ")");
    }
    if (o.normals && !cloud.has_normals())
      throw AlgorithmError(name() + ": normals = true but the cloud has no normals");

    TemporaryDirectory dir(name());
    const std::string in = dir.path() + "/points." + (o.input_format == "xyz" ? "xyz" : "ply");
    const std::string out = dir.path() + "/mesh." + o.output_extension();
    PointCloud written;
    written.points = cloud.points;
    if (o.normals) written.normals = cloud.normals;
    WriteOptions format;
    format.binary = o.input_format == "ply";
    write_points(in, written, format);

    const std::string command =
        replace_all(replace_all(o.command, "{in}", shell_quote(in)), "{out}", shell_quote(out));
    const CommandOutcome outcome = run_shell_command(command, dir.path(), o.timeout_seconds);
    const std::string said = outcome.output_tail.empty() ? "" : "; its output ends with:\n" + outcome.output_tail;
    if (!outcome.succeeded())
      throw AlgorithmError(name() + ": command '" + o.command + "' failed: " + outcome.describe() + said);
    if (!fs::exists(out))
      throw AlgorithmError(name() + ": command '" + o.command + "' ended with exit status 0 but wrote no {out} file (" +
                           o.output_extension() + ")" + said);
    TriangleMesh raw;
    try {
      raw = read_mesh(out);
    } catch (const FileError& e) {
      throw AlgorithmError(name() + ": command '" + o.command + "' wrote a mesh that cannot be read: " + e.what());
    }

    PolygonSoup soup;
    soup.vertices = std::move(raw.vertices);
    soup.polygons.reserve(raw.faces.size());
    for (const Face& f : raw.faces) soup.polygons.push_back({f[0], f[1], f[2]});
    CleanupCounts counts;
    TriangleMesh mesh = soup_to_mesh(soup, 0.0, false, &counts);
    summary["command"] = o.command;
    summary["exit_status"] = outcome.exit_status;
    summary["command_seconds"] = outcome.seconds;
    summary["command_peak_memory_mib"] = outcome.peak_memory_mib;
    summary["cleanup"] = counts.to_json();
    return mesh;
  }

  std::string empty_hint() const override {
    return "the command '" + options_.command + "' wrote a mesh without triangles";
  }

 private:
  ExternalOptions options_;
};

}  // namespace

std::unique_ptr<Reconstructor> make_external() { return std::make_unique<ExternalReconstructor>(); }

}  // namespace dtsl::baselines

// dtsl reconstruct IN OUT: one point file to one mesh file, in the input's own coordinates. Checks all it
// can before the reconstruction (which takes seconds to minutes), shows each stage as it starts, and on
// request keeps the stage meshes and a metrics record.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <thread>

#include "experiments/cli.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/config/yaml_path.hpp"
#include "framework/core/atomic_file.hpp"
#include "framework/core/cores.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"
#include "framework/io/io.hpp"
#include "framework/pipeline/preset.hpp"
#include "framework/pipeline/reconstructor.hpp"
#include "framework/pipeline/run_one.hpp"

namespace dtsl::cli {

namespace fs = std::filesystem;

namespace {

/// The pipeline `dtsl reconstruct` uses when none is named: the paper's method.
constexpr const char* kDefaultPipeline = "dtsl";

/// A UsageError unless `dir` (empty: the working folder) is an existing folder we may write into.
void require_writable_folder(const std::string& dir, const std::string& what) {
  const std::string d = dir.empty() ? "." : dir;
  std::error_code ec;
  if (!fs::is_directory(d, ec)) throw UsageError{what + ": folder '" + d + "' does not exist"};
  if (::access(d.c_str(), W_OK | X_OK) != 0) throw UsageError{what + ": folder '" + d + "' is not writable"};
}

/// A file we are to write: its folder exists and is writable, and it is not itself a folder.
void require_writable_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw UsageError{what + ": '" + path + "' is a folder, not a file"};
  require_writable_folder(fs::path(path).parent_path().string(), what);
}

/// Progress on stderr: on a terminal one line rewritten in place with a ticking clock, otherwise a plain
/// line per stage (logs, CI). Silent when quiet.
class StageProgress {
 public:
  StageProgress(bool quiet, std::string pipeline)
      : quiet_(quiet), tty_(::isatty(STDERR_FILENO) == 1), pipeline_(std::move(pipeline)) {
    if (!quiet_ && tty_) ticker_ = std::thread([this] { tick(); });
  }
  ~StageProgress() { finish(); }

  void stage(const std::string& name, const std::string& what) {
    if (quiet_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    ++count_;
    stage_ = name + ": " + what;
    stage_clock_.restart();
    if (tty_) draw();
    else std::fprintf(stderr, "%s: [stage %d] %s (at %.1f s)\n", pipeline_.c_str(), count_, stage_.c_str(), total_.seconds());
  }

  /// Ends the display (the ticking line gets its newline); idempotent.
  void finish() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (done_) return;
      done_ = true;
    }
    wake_.notify_all();
    if (ticker_.joinable()) ticker_.join();
    if (!quiet_ && tty_ && count_ > 0) std::fputs("\n", stderr);
  }

 private:
  void draw() {  // under mutex_
    constexpr int kBar = 20;
    const double secs = stage_clock_.seconds();
    const int filled = int(secs * 2) % (kBar + 1);  // an activity bar: the stages' lengths are not known
    std::string bar(kBar, ' ');
    for (int i = 0; i < filled; ++i) bar[i] = '=';
    std::fprintf(stderr, "\r\033[K%s [%s] stage %d, %s  %.1f s", pipeline_.c_str(), bar.c_str(), count_, stage_.c_str(),
                 total_.seconds());
    std::fflush(stderr);
  }
  void tick() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done_) {
      wake_.wait_for(lock, std::chrono::milliseconds(500));
      if (!done_ && count_ > 0) draw();
    }
  }

  const bool quiet_, tty_;
  const std::string pipeline_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  int count_ = 0;
  std::string stage_;
  Stopwatch total_, stage_clock_;
  std::thread ticker_;
};

}  // namespace

int reconstruct_command(Args& args) {
  const std::string name = args.value("pipeline", kDefaultPipeline);
  const std::string preset = args.value("preset", "default");
  const std::vector<std::string> sets = args.values("set");
  const std::string stages_dir = args.value("stages");
  const std::string metrics_file = args.value("metrics");
  const std::string truth_file = args.value("truth");
  const std::string threads_text = args.value("threads");
  const bool normalised = args.flag("normalised");
  const bool quiet = args.flag("quiet");
  const std::vector<std::string> rest = args.positionals();
  if (rest.size() != 2) throw UsageError{"reconstruct: expected IN and OUT files"};
  const std::string in = rest[0], out = rest[1];

  // Everything that can be wrong with the command is found before the (long) reconstruction.
  const std::string ext = file_extension(out);
  if (ext != "ply" && ext != "obj" && ext != "off")
    throw UsageError{"reconstruct: OUT must end in .ply, .obj or .off, got '" + out + "'"};
  require_writable_file(out, "OUT");
  if (!metrics_file.empty()) {
    if (file_extension(metrics_file) != "json")
      throw UsageError{"--metrics: the file must end in .json, got '" + metrics_file + "'"};
    require_writable_file(metrics_file, "--metrics");
  }
  if (!stages_dir.empty()) {
    std::error_code ec;
    if (fs::exists(stages_dir, ec)) require_writable_folder(stages_dir, "--stages");
    else require_writable_folder(fs::path(stages_dir).parent_path().string(), "--stages");
  }
  if (!truth_file.empty() && metrics_file.empty())
    throw UsageError{"--truth: the errors against the truth go into --metrics FILE; give one"};
  const int threads = threads_text.empty() ? free_cores() : Args::integer("threads", threads_text, 1, 1024);

  auto pipeline = reconstructors().create(name, "--pipeline");
  apply_preset(*pipeline, name, preset, "--preset");
  for (const std::string& s : sets) {
    const auto [key, value] = split_assignment(s);
    apply_assignment(pipeline->options(), key, value, "--set");
  }
  PointCloud cloud = read_points(in);
  check_finite(cloud, in);
  if (cloud.size() < pipeline->minimum_points())
    throw AlgorithmError(in + ": has " + std::to_string(cloud.size()) + (cloud.size() == 1 ? " point" : " points") +
                         "; the " + name + " pipeline needs at least " + std::to_string(pipeline->minimum_points()));
  std::optional<TriangleMesh> truth;
  if (!truth_file.empty()) truth = read_mesh(truth_file);

  // Methods work in the paper's [-1,1]^3 frame (its errors are in that frame); meshes are written in
  // the input's frame unless --normalised.
  const Similarity frame = unit_cube_normalisation(cloud.points, in);
  transform(cloud, frame);
  if (truth) transform(*truth, frame);
  set_threads(threads);
  RunContext context;
  context.threads = threads;
  StageProgress progress(quiet, name);
  context.on_stage = [&progress](const std::string& stage, const std::string& what) { progress.stage(stage, what); };
  Stopwatch clock;
  ReconstructionResult result = pipeline->reconstruct(cloud, context);
  const double seconds = clock.seconds();
  progress.finish();

  nlohmann::json record;
  if (!metrics_file.empty()) {
    Dataset data{in, cloud, truth, nlohmann::json::object(), frame};
    const MetricsOptions metrics;
    record = {{"input", in},
              {"points", cloud.size()},
              {"pipeline", name},
              {"preset", preset},
              {"options", to_json(pipeline->options())},
              {"threads", threads},
              {"time_total", seconds},
              {"peak_memory_mib", peak_memory_mib()},
              {"summary", result.summary},
              {"frame", {{"center", {frame.center.x(), frame.center.y(), frame.center.z()}}, {"scale", frame.scale}}},
              {"errors_frame", "[-1,1]^3 of the input's bounding box (the paper's); x 1/scale for input units"}};
    nlohmann::json stages = nlohmann::json::array();
    for (const StageRecord& s : result.stages) {
      nlohmann::json js = {{"name", s.name}, {"seconds", s.seconds}, {"summary", s.summary}};
      if (s.mesh) js["measures"] = measure_mesh(*s.mesh, data, truth ? &metrics : nullptr, 1);
      stages.push_back(js);
    }
    record["stages"] = stages;
    record["final"] = measure_mesh(result.mesh, data, truth ? &metrics : nullptr, 1);
  }

  if (!normalised) transform(result, frame.inverse());
  if (!stages_dir.empty()) {
    fs::create_directories(stages_dir);
    const nlohmann::json files = write_stage_files(result, stages_dir);
    for (std::size_t i = 0; i < files.size() && record.contains("stages"); ++i)
      for (const char* key : {"file", "lines_file"})
        if (files[i].contains(key)) record["stages"][i][key] = files[i][key];
  }
  write_mesh(out, result.mesh);
  if (!metrics_file.empty()) write_file_atomically(metrics_file, [&record](std::ostream& o) { o << record.dump(2) << "\n"; });
  if (!quiet)
    std::cerr << name << ": " << cloud.size() << " points -> " << result.mesh.vertices.size() << " vertices, "
              << result.mesh.faces.size() << " triangles in " << seconds << " s; wrote " << out << "\n";
  return 0;
}

}  // namespace dtsl::cli

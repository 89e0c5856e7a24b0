// dtsl report DIR: see framework/report/report.hpp.
#include <iostream>

#include "experiments/cli.hpp"
#include "framework/core/error.hpp"
#include "framework/report/report.hpp"

namespace dtsl::cli {

int report_command(Args& args) {
  report::ReportOptions options;
  const std::string views = args.value("views", "2"), size = args.value("size", "360"), up = args.value("up", "y");
  const std::string closeup = args.value("closeup", "1");
  options.renders = !args.flag("no-renders");
  options.progress = !args.flag("quiet");
  const std::vector<std::string> rest = args.positionals();
  if (rest.size() != 1) throw UsageError{"report: expected one result directory"};
  auto number = [](const std::string& name, const std::string& text) {
    try {
      std::size_t used = 0;
      const double v = std::stod(text, &used);
      if (used != text.size()) throw std::invalid_argument(text);
      return v;
    } catch (const std::exception&) {
      throw UsageError{"--" + name + ": expected a number, got '" + text + "'"};
    }
  };
  options.views = static_cast<int>(number("views", views));
  options.panel_size = static_cast<int>(number("size", size));
  options.closeup = number("closeup", closeup);
  if (up.size() != 1) throw UsageError{"--up: expected x, y or z, got '" + up + "'"};
  options.up = up[0];
  try {
    options.check();
  } catch (const ConfigError& e) {
    throw UsageError{e.what()};
  }
  const report::ReportSummary s = report::write_report(rest[0], options);
  std::cerr << "report: " << s.runs << " runs, " << s.figures << " figures; " << s.report_path << "\n";
  return 0;
}

}  // namespace dtsl::cli

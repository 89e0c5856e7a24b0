// Result tables (Markdown, CSV, LaTeX) built from the per-run metrics JSON, so `dtsl table DIR` can
// regenerate them at any time. Columns are named; "e_avr@MI" reads the errors of the stage mesh
// labelled MI and "time@TL" the time of stage TL, which is how the paper's Table 1 is laid out.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace dtsl {

struct Table {
  std::vector<std::string> headers;
  std::vector<std::vector<std::string>> rows;
};

/// The default columns, used when an experiment's `table.columns` is empty.
std::vector<std::string> default_columns();

/// Every column name understood (for `dtsl list` and error messages).
std::string describe_columns();

/// Throws ConfigError naming an unknown column.
void check_columns(const std::vector<std::string>& columns);

/// Rows in the order given; one extra column per sweep key found in the records, after "pipeline".
Table make_table(const std::vector<nlohmann::json>& records, const std::vector<std::string>& columns);

std::string to_markdown(const Table& t);
std::string to_csv(const Table& t);
std::string to_latex(const Table& t, const std::string& caption);

/// Reads every runs/*/metrics.json of a result directory, in the experiment's run order.
std::vector<nlohmann::json> load_run_records(const std::string& result_dir);

/// Writes table.md, table.csv and table.tex into `result_dir` (atomically); returns the Markdown.
std::string write_tables(const std::string& result_dir, const std::vector<std::string>& columns,
                         const std::string& title);

}  // namespace dtsl

// Charts made from metrics records: which series and rows they hold, from synthetic records (the
// fields are those execute_run writes; see framework/pipeline/run_one.hpp).
#include <catch2/catch.hpp>

#include "framework/core/error.hpp"
#include "framework/pipeline/shard.hpp"
#include "framework/report/metric_charts.hpp"
#include "framework/report/report.hpp"

using namespace dtsl;
using namespace dtsl::report;
using json = nlohmann::json;

namespace {

json dtsl_record() {
  json history = json::array();
  for (int i = 0; i < 5; ++i)
    history.push_back({{"iteration", i}, {"mean_distance", 0.1 / (i + 1)}, {"max_distance", 0.5 / (i + 1)},
                       {"mean_speed", 0.05 / (i + 1)}});
  return {{"run", "fandisk__dtsl"},
          {"type", "dtsl"},
          {"status", "ok"},
          {"time_total", 3.0},
          {"stages",
           {{{"name", "TL"}, {"seconds", 2.0},
             {"summary", {{"history", history}, {"evolution_timings", {{"solve", 0.8}, {"rows", 0.5}}}}}},
            {{"name", "MT"}, {"seconds", 0.1}, {"mesh_label", "MI"}, {"file", "stage_MI.ply"}, {"summary", json::object()}},
            {{"name", "B-Evl"}, {"seconds", 0.9}, {"mesh_label", "MS"},
             {"summary", {{"e_avr_per_iteration", {0.01, 0.005, 0.004}}, {"sharp_vertices_per_iteration", {10, 12, 11}}}}}}}};
}

json sweep_record(const std::string& dataset, const std::string& value, double e_avr, const std::string& status = "ok") {
  return {{"run", dataset + "__dtsl__v=" + value}, {"dataset", dataset}, {"pipeline", "dtsl"}, {"status", status},
          {"sweep", {{"pipelines.dtsl.options.v", value}}},
          {"final", {{"point_errors", {{"e_avr", e_avr}}}}}, {"time_total", 1.0}};
}

}  // namespace

TEST_CASE("convergence charts: the evolution's history and every *_per_iteration list") {
  const json r = dtsl_record();
  CHECK(has_evolution_history(r));
  const auto charts = convergence_charts(r);
  REQUIRE(charts.size() == 3);  // TL history, e_avr, sharp_vertices
  CHECK(charts[0].log_y);
  CHECK(charts[0].series.size() == 3);  // the fields present: mean/max distance, mean speed
  CHECK(charts[0].series[0].x.size() == 5);
  json no_history = r;
  no_history["stages"][0]["summary"].erase("history");
  CHECK(!has_evolution_history(no_history));
  CHECK(convergence_charts(no_history).size() == 2);
  CHECK(convergence_charts(json{{"run", "x"}}).empty());
}

TEST_CASE("timing charts: a row per stage plus the evolution's breakdown and the total") {
  const render::BarChart c = stage_time_chart(dtsl_record());
  CHECK(c.rows.size() == 3 + 2 + 1);
  CHECK(c.values.size() == c.rows.size());
  CHECK(c.rows.back() == "total");
  const render::BarChart o = time_overview_chart({dtsl_record(), json{{"run", "poisson"}, {"time_total", 0.5}}}, "t");
  CHECK(o.rows.size() == 2);
  CHECK(o.segments.size() == 3);
  CHECK(o.values[1][0] == 0.5);  // a run without stages shows its total
}

TEST_CASE("sweep charts: one series per dataset, x from the axis values, failures as gaps") {
  const std::vector<json> records = {sweep_record("a", "4", 0.002), sweep_record("a", "6", 0.001),
                                     sweep_record("b", "4", 0.003), sweep_record("b", "5", 0.0, "failed"),
                                     json{{"run", "other"}, {"sweep", json::object()}}};
  const SweepMetric& e_avr = sweep_metrics().front();
  const render::LineChart c = sweep_chart(records, "pipelines.dtsl.options.v", {"4", "5", "6"}, e_avr);
  REQUIRE(c.series.size() == 2);
  CHECK(c.x_categories.empty());  // numeric axis
  CHECK(c.series[0].x == std::vector<double>{4, 6});
  CHECK(c.series[0].y[0] == Approx(2.0));  // x 1e3
  CHECK(std::isnan(c.series[1].y[1]));
  const render::LineChart cat = sweep_chart({sweep_record("a", "ceres", 0.001), sweep_record("a", "eigen_cg", 0.002)},
                                            "pipelines.dtsl.options.v", {"eigen_cg", "ceres"}, e_avr);
  CHECK(cat.x_categories.size() == 2);
  CHECK(cat.series[0].x == std::vector<double>{0, 1});  // ordered as the axis lists them
  CHECK(cat.series[0].y[0] == Approx(2.0));
}

TEST_CASE("compose lays images out in a grid") {
  const render::Image a(10, 20), b(30, 5);
  const render::Image g = compose({a, b, a}, 2);
  CHECK(g.width() == 40);
  CHECK(g.height() == 40);
  CHECK(compose({}, 2).width() == 0);
}

TEST_CASE("report options are checked") {
  ReportOptions o;
  CHECK_NOTHROW(o.check());
  CHECK(o.scene().views.size() == 2);
  o.closeup = 3;
  CHECK(o.scene().views.size() == 3);
  o.views = 0;
  CHECK_THROWS_AS(o.check(), ConfigError);
  o = ReportOptions{};
  o.up = 'w';
  CHECK_THROWS_AS(o.check(), ConfigError);
}

TEST_CASE("shards partition the run list: disjoint, covering, balanced") {
  for (int n : {1, 2, 3, 7}) {
    std::vector<int> owner(20, 0);
    for (int i = 1; i <= n; ++i) {
      const auto mine = shard_runs(20, parse_shard(std::to_string(i) + "/" + std::to_string(n)));
      CHECK(static_cast<int>(mine.size()) >= 20 / n);
      CHECK(static_cast<int>(mine.size()) <= 20 / n + 1);
      for (std::size_t k : mine) ++owner[k];
    }
    for (int o : owner) CHECK(o == 1);
  }
  for (const char* bad : {"0/3", "4/3", "3", "x/3", "1/", "/3", "1/3/3", " 1/3", "1/1000000"})
    CHECK_THROWS_AS(parse_shard(bad), ConfigError);
  CHECK(parse_shard("2/5").str() == "2/5");
}

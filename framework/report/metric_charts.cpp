#include "framework/report/metric_charts.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace dtsl::report {

using json = nlohmann::json;

namespace {

const json* stage(const json& record, const std::string& name) {
  if (!record.contains("stages") || !record["stages"].is_array()) return nullptr;
  for (const json& s : record["stages"])
    if (s.is_object() && s.value("name", std::string()) == name) return &s;
  return nullptr;
}

double number_or_nan(const json& j) { return j.is_number() ? j.get<double>() : std::nan(""); }

std::string run_name(const json& record) { return record.value("run", std::string("run")); }

bool parse_number(const std::string& s, double& out) {
  try {
    std::size_t used = 0;
    out = std::stod(s, &used);
    return used == s.size() && std::isfinite(out);
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

bool has_evolution_history(const json& record) {
  const json* tl = stage(record, "TL");
  return tl && tl->contains("summary") && (*tl)["summary"].contains("history") &&
         (*tl)["summary"]["history"].is_array() && !(*tl)["summary"]["history"].empty();
}

std::vector<render::LineChart> convergence_charts(const json& record) {
  std::vector<render::LineChart> out;
  if (has_evolution_history(record)) {
    const json& h = (*stage(record, "TL"))["summary"]["history"];
    render::LineChart c;
    c.title = "level-set evolution (TL)";
    c.x_label = "iteration";
    c.y_label = "distance / speed";
    c.log_y = true;
    c.integer_x = true;
    for (const char* key : {"mean_distance", "max_distance", "mean_surface_distance", "mean_speed", "max_speed"}) {
      render::Series s;
      s.name = key;
      s.markers = h.size() <= 60;
      for (std::size_t i = 0; i < h.size(); ++i) {
        if (!h[i].is_object() || !h[i].contains(key)) continue;
        s.x.push_back(h[i].contains("iteration") ? number_or_nan(h[i]["iteration"]) : static_cast<double>(i));
        s.y.push_back(number_or_nan(h[i][key]));
      }
      if (!s.x.empty()) c.series.push_back(std::move(s));
    }
    if (!c.series.empty()) out.push_back(std::move(c));
  }
  if (record.contains("stages") && record["stages"].is_array())
    for (const json& st : record["stages"]) {
      if (!st.is_object() || !st.contains("summary") || !st["summary"].is_object()) continue;
      const std::string name = st.value("name", std::string("?"));
      const std::string suffix = "_per_iteration";
      for (auto it = st["summary"].begin(); it != st["summary"].end(); ++it) {
        const std::string& key = it.key();
        if (key.size() <= suffix.size() || key.compare(key.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
        if (!it->is_array() || it->empty() || !(*it)[0].is_number()) continue;
        const std::string quantity = key.substr(0, key.size() - suffix.size());
        render::LineChart c;
        c.title = quantity + " per iteration (" + name + ")";
        c.x_label = "iteration";
        c.integer_x = true;
        c.y_label = quantity;
        double lo = INFINITY, hi = 0;
        render::Series s;
        s.name = quantity;
        s.markers = it->size() <= 60;
        for (std::size_t i = 0; i < it->size(); ++i) {
          s.x.push_back(static_cast<double>(i));
          s.y.push_back(number_or_nan((*it)[i]));
          if (s.y.back() > 0) lo = std::min(lo, s.y.back()), hi = std::max(hi, s.y.back());
        }
        c.log_y = hi > 0 && lo > 0 && hi / lo > 20;  // log only where the values span decades
        c.series.push_back(std::move(s));
        out.push_back(std::move(c));
      }
    }
  return out;
}

render::BarChart stage_time_chart(const json& record) {
  render::BarChart c;
  c.title = "time per stage (s)";
  c.value_label = "seconds";
  // Segments only colour the rows: a stage, a part of a stage, the run's total.
  c.segments = {"stage", "part of a stage", "total"};
  if (!record.contains("stages") || !record["stages"].is_array()) return c;
  for (const json& st : record["stages"]) {
    if (!st.is_object()) continue;
    const std::string name = st.value("name", std::string("?"));
    c.rows.push_back(name);
    c.values.push_back({st.contains("seconds") ? number_or_nan(st["seconds"]) : 0.0, 0.0, 0.0});
    if (st.contains("summary") && st["summary"].is_object() && st["summary"].contains("evolution_timings") &&
        st["summary"]["evolution_timings"].is_object())
      for (auto it = st["summary"]["evolution_timings"].begin(); it != st["summary"]["evolution_timings"].end(); ++it) {
        c.rows.push_back(name + "/" + it.key());
        c.values.push_back({0.0, number_or_nan(*it), 0.0});
      }
  }
  if (record.contains("time_total")) {
    c.rows.push_back("total");
    c.values.push_back({0.0, 0.0, number_or_nan(record["time_total"])});
  }
  return c;
}

render::BarChart time_overview_chart(const std::vector<json>& records, const std::string& title) {
  render::BarChart c;
  c.title = title;
  c.value_label = "seconds";
  for (const json& r : records)
    if (r.contains("stages") && r["stages"].is_array())
      for (const json& st : r["stages"])
        if (st.is_object() && std::find(c.segments.begin(), c.segments.end(), st.value("name", std::string("?"))) == c.segments.end())
          c.segments.push_back(st.value("name", std::string("?")));
  if (c.segments.empty()) c.segments.push_back("total");
  for (const json& r : records) {
    c.rows.push_back(run_name(r));
    std::vector<double> v(c.segments.size(), 0.0);
    bool any = false;
    if (r.contains("stages") && r["stages"].is_array())
      for (const json& st : r["stages"]) {
        if (!st.is_object()) continue;
        const auto k = std::find(c.segments.begin(), c.segments.end(), st.value("name", std::string("?"))) - c.segments.begin();
        if (st.contains("seconds") && st["seconds"].is_number()) v[k] += st["seconds"].get<double>(), any = true;
      }
    if (!any && r.contains("time_total") && r["time_total"].is_number()) v[0] = r["time_total"].get<double>();
    c.values.push_back(v);
  }
  return c;
}

const std::vector<SweepMetric>& sweep_metrics() {
  static const std::vector<SweepMetric> m = {
      {"e_avr", "e_avr (1e-3)", {"final", "point_errors", "e_avr"}, 1e3, false},
      {"e_max", "e_max (1e-3)", {"final", "point_errors", "e_max"}, 1e3, false},
      {"chamfer", "chamfer (1e-3)", {"final", "surface", "chamfer"}, 1e3, false},
      {"fscore", "F-score", {"final", "surface", "fscore"}, 1.0, false},
      {"time", "time (s)", {"time_total"}, 1.0, false},
  };
  return m;
}

render::LineChart sweep_chart(const std::vector<json>& records, const std::string& key,
                              const std::vector<std::string>& values, const SweepMetric& metric) {
  render::LineChart c;
  const std::string axis = key.substr(key.find_last_of('.') + 1);
  c.title = metric.label + " versus " + axis;
  c.x_label = key;
  c.y_label = metric.label;
  c.log_y = metric.log;
  bool numeric = !values.empty();
  std::vector<double> xs(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) numeric = numeric && parse_number(values[i], xs[i]);
  if (!numeric) c.x_categories = values;

  std::map<std::string, std::size_t> series_of;
  for (const json& r : records) {
    if (!r.contains("sweep") || !r["sweep"].is_object() || !r["sweep"].contains(key)) continue;
    const std::string v = r["sweep"][key].is_string() ? r["sweep"][key].get<std::string>() : r["sweep"][key].dump();
    const auto pos = std::find(values.begin(), values.end(), v);
    if (pos == values.end()) continue;
    std::string name = r.value("dataset", std::string()) + " / " + r.value("pipeline", std::string());
    for (auto it = r["sweep"].begin(); it != r["sweep"].end(); ++it)
      if (it.key() != key)
        name += ", " + it.key().substr(it.key().find_last_of('.') + 1) + "=" +
                (it->is_string() ? it->get<std::string>() : it->dump());
    if (!series_of.count(name)) {
      series_of[name] = c.series.size();
      c.series.push_back({name, {}, {}, true});
    }
    render::Series& s = c.series[series_of[name]];
    const json* cur = &r;
    for (const std::string& p : metric.path) cur = (cur && cur->is_object() && cur->contains(p)) ? &(*cur)[p] : nullptr;
    const double y = (cur && cur->is_number() && r.value("status", std::string()) == "ok") ? cur->get<double>() * metric.scale
                                                                                           : std::nan("");
    const std::size_t idx = pos - values.begin();
    s.x.push_back(numeric ? xs[idx] : static_cast<double>(idx));
    s.y.push_back(y);
  }
  for (render::Series& s : c.series) {  // in x order, so lines run left to right
    std::vector<std::size_t> order(s.x.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
    std::vector<double> x, y;
    for (std::size_t i : order) x.push_back(s.x[i]), y.push_back(s.y[i]);
    s.x = x, s.y = y;
  }
  return c;
}

}  // namespace dtsl::report

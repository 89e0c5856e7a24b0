#include "algorithms/method/refinement_guard.hpp"

#include <cmath>

#include "framework/core/error.hpp"

namespace dtsl {

namespace {

nlohmann::json to_json(const std::optional<ZeroSetTopology>& t) {
  if (!t) return "not meshed";
  nlohmann::json j = {{"components", t->components}, {"genus", nullptr}};
  if (std::isfinite(t->genus)) j["genus"] = t->genus;
  return j;
}

}  // namespace

bool no_more_complex(const ZeroSetTopology& after, const ZeroSetTopology& before) {
  if (after.components > before.components) return false;
  // The genus of an open mesh (a zero set cut by the domain's boundary) is NaN. A closed zero set may
  // not open; an open one is compared by its components only.
  if (!std::isfinite(before.genus)) return true;
  return std::isfinite(after.genus) && after.genus <= before.genus;
}

GuardedRefinement guard_refinement_topology(const TSpline& evolved, const TSpline& fitted,
                                            const std::vector<double>& transferred, const TopologyOf& topology_of,
                                            const std::vector<double>& alphas) {
  if (transferred.size() != fitted.coefficients().size())
    throw AlgorithmError("refinement guard: " + std::to_string(transferred.size()) +
                         " transferred coefficients for a refined basis of " +
                         std::to_string(fitted.coefficients().size()));
  if (alphas.empty() || alphas.front() != 1.0)
    throw AlgorithmError("refinement guard: the first alpha must be 1 (the whole fit)");
  for (std::size_t k = 0; k < alphas.size(); ++k)
    if (!(alphas[k] > 0.0 && alphas[k] <= 1.0) || (k > 0 && alphas[k] >= alphas[k - 1]))
      throw AlgorithmError("refinement guard: alphas must decrease within (0, 1], got " + std::to_string(alphas[k]));

  GuardedRefinement out{fitted, 1.0, nlohmann::json::object()};
  const std::optional<ZeroSetTopology> reference = topology_of(evolved, -1.0);
  out.summary["evolved"] = to_json(reference);
  nlohmann::json tried = nlohmann::json::array();
  if (!reference) {
    out.summary["kept_alpha"] = 1.0;
    out.summary["reason"] = "the evolved level set could not be meshed: no reference, the fit kept";
    out.summary["tried"] = tried;
    return out;
  }
  const std::vector<double>& c1 = fitted.coefficients();
  for (double alpha : alphas) {
    std::vector<double> c(c1.size());
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = transferred[i] + alpha * (c1[i] - transferred[i]);
    TSpline candidate(fitted.shared_basis(), std::move(c));
    const std::optional<ZeroSetTopology> t = topology_of(candidate, alpha);
    tried.push_back({{"alpha", alpha}, {"topology", to_json(t)}});
    if (t && no_more_complex(*t, *reference)) {
      out.level_set = std::move(candidate);
      out.alpha = alpha;
      out.summary["kept_alpha"] = alpha;
      out.summary["reason"] = alpha == 1.0 ? "the fit keeps the evolved topology"
                                            : "the whole fit added components or handles, opened the surface or "
                                              "could not be meshed";
      out.summary["tried"] = tried;
      return out;
    }
  }
  // Last resort: the evolved f on the refined T-mesh (the transfer moves f by O(h^2) only).
  out.level_set = TSpline(fitted.shared_basis(), transferred);
  out.alpha = 0.0;
  out.summary["kept_alpha"] = 0.0;
  out.summary["reason"] =
      "every scaled fit added components or handles, opened the surface or could not be meshed: the evolved level "
      "set on the refined T-mesh";
  out.summary["tried"] = tried;
  return out;
}

}  // namespace dtsl

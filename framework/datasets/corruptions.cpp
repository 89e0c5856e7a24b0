// Corruptions: what real scans do to points, applied in the configured order. Lengths are in the
// [-1,1]^3 frame of the normalised shape (the paper's frame). A point keeps the normal of the clean
// surface where it came from; points that come from nowhere (outliers) get a random unit normal, see
// Outliers.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"

namespace dtsl::dataset_detail {

namespace {

/// Keeps the points (and their normals) for which keep[i] is true, in order.
void filter(PointCloud& cloud, const std::vector<bool>& keep) {
  const bool normals = cloud.has_normals();
  std::size_t out = 0;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    if (!keep[i]) continue;
    cloud.points[out] = cloud.points[i];
    if (normals) cloud.normals[out] = cloud.normals[i];
    ++out;
  }
  cloud.points.resize(out);
  if (normals) cloud.normals.resize(out);
}

/// A direction uniform on the unit sphere (normalised Gaussian vector).
Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    const double x = g(rng), y = g(rng), z = g(rng);  // sequenced, unlike constructor arguments
    const Vec3 v(x, y, z);
    const double n = v.norm();
    if (n > 1e-12) return v / n;
  }
}

// ---- noise ------------------------------------------------------------------------------------

struct NoiseOptions final : Options {
  double sigma = 0.005;
  std::string direction = "isotropic";

  void visit(FieldVisitor& v) override {
    v.field("sigma", sigma, "standard deviation of the Gaussian displacement per coordinate ([-1,1] frame)");
    v.field("direction", direction,
            "isotropic: N(0, sigma^2) on each coordinate; normal: N(0, sigma^2) along the point's normal "
            "only (a scanner's depth error)");
  }
  void check() const override {
    check_positive("sigma", sigma);
    // Half the frame: beyond that the shape is gone, which is a mistake, not an experiment.
    require(sigma <= 1.0, "sigma", "must be at most 1 (the frame is [-1,1]^3), got " + format_number(sigma));
    check_one_of("direction", direction, {"isotropic", "normal"});
  }
};

class Noise final : public Corruption {
 public:
  Options& options() override { return o_; }
  void apply(PointCloud& cloud, std::mt19937_64& rng) override {
    std::normal_distribution<double> g(0.0, o_.sigma);
    if (o_.direction == "normal") {
      if (!cloud.has_normals())
        throw AlgorithmError("corruption 'noise' with direction 'normal' needs point normals; these points "
                             "have none (use direction: isotropic)");
      for (std::size_t i = 0; i < cloud.size(); ++i) cloud.points[i] += g(rng) * cloud.normals[i];
    } else {
      for (Vec3& p : cloud.points) {
        const double dx = g(rng), dy = g(rng), dz = g(rng);  // sequenced: the order is part of the seed's meaning
        p += Vec3(dx, dy, dz);
      }
    }
  }

 private:
  NoiseOptions o_;
};

// ---- holes ------------------------------------------------------------------------------------

struct HolesOptions final : Options {
  int count = 5;
  double radius = 0.1;

  void visit(FieldVisitor& v) override {
    v.field("count", count, "number of holes: balls centred at distinct random points of the cloud");
    v.field("radius", radius, "radius of each ball ([-1,1] frame); points inside are removed");
  }
  void check() const override {
    check_range("count", count, 1, 1000000);
    check_positive("radius", radius);
  }
};

class Holes final : public Corruption {
 public:
  Options& options() override { return o_; }
  void apply(PointCloud& cloud, std::mt19937_64& rng) override {
    centres_.clear();
    const std::size_t n = cloud.size();
    if (n == 0) return;
    // Distinct centres (partial Fisher-Yates), all chosen before any removal: a hole may swallow
    // another's centre, and overlapping holes make one larger hole, as on a real scan.
    std::vector<std::size_t> idx(n);
    std::iota(idx.begin(), idx.end(), 0);
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(o_.count), n);
    for (std::size_t i = 0; i < k; ++i) {
      std::uniform_int_distribution<std::size_t> pick(i, n - 1);
      std::swap(idx[i], idx[pick(rng)]);
      centres_.push_back(cloud.points[idx[i]]);
    }
    const double r2 = o_.radius * o_.radius;
    std::vector<bool> keep(n, true);
    for (std::size_t i = 0; i < n; ++i)
      for (const Vec3& c : centres_)
        if ((cloud.points[i] - c).squaredNorm() <= r2) {
          keep[i] = false;
          break;
        }
    filter(cloud, keep);
  }
  nlohmann::json report() const override {
    // In the frame the corruption ran in (the normalised shape's), so analyses can find the holes.
    nlohmann::json c = nlohmann::json::array();
    for (const Vec3& p : centres_) c.push_back({p.x(), p.y(), p.z()});
    return {{"centres", c}, {"frame", "shape"}};
  }

 private:
  HolesOptions o_;
  std::vector<Vec3> centres_;
};

// ---- plane_cut --------------------------------------------------------------------------------

struct PlaneCutOptions final : Options {
  std::vector<double> normal{0.0, 0.0, 1.0};
  double offset = 0.0;

  void visit(FieldVisitor& v) override {
    v.field("normal", normal, "plane normal [x, y, z] (need not be unit); points on its side are removed");
    v.field("offset", offset,
            "signed distance of the plane from the origin along the unit normal ([-1,1] frame): points "
            "with n.p > offset are removed");
  }
  void check() const override {
    require(normal.size() == 3, "normal", "must have 3 entries, got " + std::to_string(normal.size()));
    const double len = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    require(len > 0.0 && std::isfinite(len), "normal", "must be a non-zero vector");
  }
};

/// The paper's "Fandisk cut by a plane": one side of the shape is missing altogether.
class PlaneCut final : public Corruption {
 public:
  Options& options() override { return o_; }
  void apply(PointCloud& cloud, std::mt19937_64&) override {
    const Vec3 n = to_vec3(o_.normal).normalized();
    std::vector<bool> keep(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) keep[i] = !(n.dot(cloud.points[i]) > o_.offset);
    filter(cloud, keep);
  }

 private:
  PlaneCutOptions o_;
};

// ---- outliers ---------------------------------------------------------------------------------

struct OutliersOptions final : Options {
  double fraction = 0.01;
  double margin = 0.0;

  void visit(FieldVisitor& v) override {
    v.field("fraction", fraction, "outliers added, as a fraction of the current point count (rounded)");
    v.field("margin", margin,
            "the box the outliers are uniform in: the points' box grown by margin x its size on every "
            "side (0: the box itself)");
  }
  void check() const override {
    require(fraction > 0.0 && fraction <= 1.0, "fraction", "must be in (0, 1], got " + format_number(fraction));
    check_range("margin", margin, 0.0, 1.0);
  }
};

/// Outliers have no surface under them, so no true normal. They get a uniformly random unit normal
/// rather than none or a zero vector: the cloud keeps one unit normal per point (PointCloud's
/// invariant, which consumers divide by), the true normals of the other points are kept, and a method
/// fed ground-truth normals sees at the outliers what an estimate would give there: noise.
class Outliers final : public Corruption {
 public:
  Options& options() override { return o_; }
  void apply(PointCloud& cloud, std::mt19937_64& rng) override {
    added_ = 0;
    if (cloud.empty()) return;
    const bool normals = cloud.has_normals();
    const BoundingBox box = bounding_box(cloud.points);
    const Vec3 lo = box.min - o_.margin * box.extent(), hi = box.max + o_.margin * box.extent();
    added_ = static_cast<std::size_t>(std::llround(o_.fraction * static_cast<double>(cloud.size())));
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t i = 0; i < added_; ++i) {
      const double x = u(rng), y = u(rng), z = u(rng);
      cloud.points.push_back(lo + Vec3(x, y, z).cwiseProduct(hi - lo));
      if (normals) cloud.normals.push_back(random_direction(rng));
    }
  }
  nlohmann::json report() const override {
    return {{"added", added_}, {"normals", "uniformly random unit vectors (outliers have no true normal)"}};
  }

 private:
  OutliersOptions o_;
  std::size_t added_ = 0;
};

// ---- subsample --------------------------------------------------------------------------------

struct SubsampleOptions final : Options {
  int count = 6000;

  void visit(FieldVisitor& v) override {
    v.field("count", count,
            "points kept, chosen uniformly at random without replacement (fewer points: all kept)");
  }
  void check() const override { check_range("count", count, 1, 2000000000); }
};

class Subsample final : public Corruption {
 public:
  Options& options() override { return o_; }
  void apply(PointCloud& cloud, std::mt19937_64& rng) override {
    const std::size_t n = cloud.size(), k = static_cast<std::size_t>(o_.count);
    if (k >= n) return;
    std::vector<std::size_t> idx(n);
    std::iota(idx.begin(), idx.end(), 0);
    for (std::size_t i = 0; i < k; ++i) {
      std::uniform_int_distribution<std::size_t> pick(i, n - 1);
      std::swap(idx[i], idx[pick(rng)]);
    }
    std::vector<bool> keep(n, false);
    for (std::size_t i = 0; i < k; ++i) keep[idx[i]] = true;
    filter(cloud, keep);  // keeps the original order: neighbours in the file stay neighbours
  }

 private:
  SubsampleOptions o_;
};

}  // namespace

void register_corruptions() {
  corruptions().add("noise", "Gaussian displacement, isotropic or along the normal",
                    [] { return std::make_unique<Noise>(); });
  corruptions().add("holes", "remove the points inside random balls", [] { return std::make_unique<Holes>(); });
  corruptions().add("plane_cut", "remove the points on the positive side of a plane",
                    [] { return std::make_unique<PlaneCut>(); });
  corruptions().add("outliers", "add uniform points in the box (random unit normals)",
                    [] { return std::make_unique<Outliers>(); });
  corruptions().add("subsample", "keep a random subset of count points",
                    [] { return std::make_unique<Subsample>(); });
}

}  // namespace dtsl::dataset_detail

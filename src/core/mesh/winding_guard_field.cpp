#include "core/mesh/winding_guard_field.h"

#include <cmath>
#include <limits>

namespace hermite {

namespace {

// Cells a box may span before touches() tests every centre instead of the cells.
constexpr long long kMaxCellsScanned = 512;

}  // namespace

Eigen::Vector3i GuardRegion::cellOf(const Vec<3>& x) const {
  return (x / radius_).array().floor().cast<int>();
}

std::int64_t GuardRegion::key(const Eigen::Vector3i& c) const {
  // 21 bits per axis: cells of one radius over any box a grid of ≤ 10⁶ cells per axis covers.
  const auto part = [](int v) { return static_cast<std::int64_t>(v & 0x1FFFFF); };
  return part(c.x()) | (part(c.y()) << 21) | (part(c.z()) << 42);
}

void GuardRegion::add(const Vec<3>& centre) {
  const int id = static_cast<int>(centres_.size());
  centres_.push_back(centre);
  const Eigen::Vector3i c = cellOf(centre);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) cells_[key(c + Eigen::Vector3i(dx, dy, dz))].push_back(id);
}

bool GuardRegion::contains(const Vec<3>& x) const {
  const auto it = cells_.find(key(cellOf(x)));
  if (it == cells_.end()) return false;
  for (int id : it->second)
    if ((centres_[static_cast<std::size_t>(id)] - x).squaredNorm() <= radius_ * radius_) return true;
  return false;
}

bool GuardRegion::touches(const Box<3>& box) const {
  const auto meets = [&](int id) {
    const Vec<3>& p = centres_[static_cast<std::size_t>(id)];
    return (box.lo - p).cwiseMax(p - box.hi).cwiseMax(Vec<3>::Zero()).squaredNorm() <= radius_ * radius_;
  };
  const Eigen::Vector3i lo = cellOf(box.lo), hi = cellOf(box.hi);
  const Eigen::Matrix<long long, 3, 1> span = (hi - lo).cast<long long>().array() + 1;
  if (span.prod() > kMaxCellsScanned) {
    for (int id = 0; id < size(); ++id)
      if (meets(id)) return true;
    return false;
  }
  for (int z = lo.z(); z <= hi.z(); ++z)
    for (int y = lo.y(); y <= hi.y(); ++y)
      for (int x = lo.x(); x <= hi.x(); ++x) {
        const auto it = cells_.find(key(Eigen::Vector3i(x, y, z)));
        if (it == cells_.end()) continue;
        for (int id : it->second)
          if (meets(id)) return true;
      }
  return false;
}

WindingGuardField::WindingGuardField(const ImplicitField<3>& inner, std::shared_ptr<const CloudWinding<3>> winding,
                                     GuardRegion region,
                                     std::unique_ptr<ImplicitField<3>> owned)
    : inner_(inner), winding_(std::move(winding)), region_(std::move(region)), owned_(std::move(owned)) {}

bool WindingGuardField::overrules(const Vec<3>& x, double f) const {
  if (f == 0 || !region_.contains(x)) return false;
  const double w = winding_->at(x);
  return windingOverrules(w, f);
}

double WindingGuardField::evaluate(const Vec<3>& x, Vec<3>* g, Mat<3>* H) const {
  const double f = inner_.evaluate(x, g, H);
  if (!overrules(x, f)) return f;
  if (g) *g = -*g;
  if (H) *H = -*H;
  return -f;
}

void WindingGuardField::guardBatch(const Points<3>& X, Eigen::VectorXd& f, Points<3>* G) const {
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < X.cols(); ++i) {
    if (!overrules(X.col(i), f(i))) continue;
    f(i) = -f(i);
    if (G) G->col(i) = -G->col(i);
  }
}

void WindingGuardField::evaluateBatch(const Points<3>& X, Eigen::VectorXd& f, Points<3>* G) const {
  inner_.evaluateBatch(X, f, G);
  guardBatch(X, f, G);
}

void WindingGuardField::evaluateValidBatch(const Points<3>& X, Eigen::VectorXd& f, std::vector<char>& valid) const {
  inner_.evaluateValidBatch(X, f, valid);
  guardBatch(X, f, nullptr);
}

std::unique_ptr<ImplicitField<3>> WindingGuardField::forGridCells(double cellDiagonal) const {
  std::unique_ptr<ImplicitField<3>> near = inner_.forGridCells(cellDiagonal);
  if (!near) return nullptr;
  const ImplicitField<3>& ref = *near;
  return std::make_unique<WindingGuardField>(ref, winding_, region_, std::move(near));
}

double WindingGuardField::lipschitzBound(const Box<3>& box) const {
  if (region_.touches(box)) return std::numeric_limits<double>::infinity();
  return inner_.lipschitzBound(box);
}

}  // namespace hermite

#include "app/gui/in_frame_bake.h"

#include <algorithm>
#include <limits>

#include "core/rbf/radial_sum.h"

namespace hermite::app {

namespace {

// What a bake sample costs besides its kernel terms (polynomial, bricks, normal texel), in terms.
constexpr double kOverheadTerms = 16;

// Terms of one bake at R: R³ · (centres + overhead); 0 for fields that are no RadialSum.
double bakeTerms(const ImplicitField<3>& field, int resolution) {
  const RadialSum<3>* model = field.asRadialSum();
  if (model == nullptr) return 0;
  const double r = resolution;
  return r * r * r * (double(model->centres().cols()) + kOverheadTerms);
}

}  // namespace

double InFrameBake::estimateMs(const ImplicitField<3>& field, int resolution) const {
  const double terms = bakeTerms(field, resolution);
  return terms > 0 ? terms * msPerTerm_ : std::numeric_limits<double>::infinity();
}

int InFrameBake::resolutionFor(const ImplicitField<3>& field) {
  for (const int r : {32, 24, 16})
    if (estimateMs(field, r) <= kBudgetMs) return r;
  if (field.asRadialSum() != nullptr) msPerTerm_ = std::max(fastestMsPerTerm_, 0.9 * msPerTerm_);  // a load spike passes
  return 0;
}

render::TracerVolume InFrameBake::bake(const ImplicitField<3>& field, const Box<3>& bounds, int resolution) {
  render::TracerUploadOptions options;
  options.bakeResolution = resolution;
  render::TracerVolume volume = render::prepareTracerVolume(field, bounds, options);
  if (const double terms = bakeTerms(field, resolution); terms > 0) {
    msPerTerm_ = volume.bakeMs / terms;
    fastestMsPerTerm_ = std::min(fastestMsPerTerm_, msPerTerm_);
  }
  return volume;
}

}  // namespace hermite::app

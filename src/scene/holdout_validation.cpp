#include "scene/holdout_validation.h"

#include <cmath>
#include <string>

#include "core/base/errors.h"
#include "scene/scene_fit.h"

namespace hermite {

namespace {

// The scene with its data replaced by the samples whose index is not ≡ fold (mod folds).
template <int Dim>
Scene trainingScene(const Scene& scene, const HermiteSamples<Dim>& samples, int fold, int folds) {
  Scene s = scene;
  s.data = DataSpec{};
  s.transform = TransformSpec{};
  for (int i = 0; i < samples.size(); ++i) {
    if (i % folds == fold) continue;
    s.data.points.emplace_back(samples.points.col(i).data(), samples.points.col(i).data() + Dim);
    s.data.normals.emplace_back(samples.normals.col(i).data(), samples.normals.col(i).data() + Dim);
  }
  return s;
}

}  // namespace

template <int Dim>
LeaveOneOutResult kFoldValidation(const Scene& scene, const HermiteSamples<Dim>& samples, int folds) {
  const int n = samples.size();
  if (folds < 2 || folds > n)
    throw InputError("k-fold validation: needs 2 ≤ k ≤ N (k = " + std::to_string(folds) + ", N = " + std::to_string(n) +
                     ")");
  LeaveOneOutResult r;
  r.valueError.assign(std::size_t(n), 0.0);
  r.gradientError.assign(std::size_t(n), 0.0);
  for (int fold = 0; fold < folds; ++fold) {
    const SceneFit<Dim> fit = fitScene<Dim>(trainingScene<Dim>(scene, samples, fold, folds));
    for (int i = fold; i < n; i += folds) {
      Vec<Dim> g;
      const double f = fit.field().evaluate(samples.points.col(i), &g);
      r.valueError[std::size_t(i)] = std::abs(f);
      r.gradientError[std::size_t(i)] = (g - samples.normals.col(i)).norm();
    }
  }
  double sv = 0, sg = 0;
  for (int i = 0; i < n; ++i) {
    sv += r.valueError[std::size_t(i)] * r.valueError[std::size_t(i)];
    sg += r.gradientError[std::size_t(i)] * r.gradientError[std::size_t(i)];
    r.maxValue = std::max(r.maxValue, r.valueError[std::size_t(i)]);
    r.maxGradient = std::max(r.maxGradient, r.gradientError[std::size_t(i)]);
  }
  r.rmsValue = std::sqrt(sv / n);
  r.rmsGradient = std::sqrt(sg / n);
  r.combined = std::hypot(r.rmsValue, meanSampleSpacing<Dim>(samples.points) * r.rmsGradient);
  return r;
}

template LeaveOneOutResult kFoldValidation<2>(const Scene&, const HermiteSamples<2>&, int);
template LeaveOneOutResult kFoldValidation<3>(const Scene&, const HermiteSamples<3>&, int);

}  // namespace hermite

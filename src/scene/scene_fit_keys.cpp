// The keys of `fit` and `fit.partition` (docs/scene-format.md).

#include <climits>

#include "core/rbf/hrbf.h"
#include "scene/scene_file.h"
#include "scene/scene_keys.h"

namespace hermite {

namespace {

using json = nlohmann::json;
using Reader = SceneReader;

// An AutoSwitch member: "auto", true or false.
template <class Spec, auto Member>
constexpr SceneKey<Spec> autoSwitchKey(std::string_view name) {
  return {name,
          [](const SceneReader& r, const nlohmann::json& x, const std::string& p, Spec& s, int) {
            if (x.is_boolean())
              s.*Member = x.template get<bool>() ? AutoSwitch::On : AutoSwitch::Off;
            else if (x.is_string() && x.template get<std::string>() == "auto")
              s.*Member = AutoSwitch::Auto;
            else
              r.fail(p, "must be \"auto\", true or false (got " + describeJson(x) + ")");
          },
          [](const Spec& s, int) -> Written {
            if (s.*Member == AutoSwitch::Auto) return json("auto");
            return json(s.*Member == AutoSwitch::On);
          }};
}

constexpr SceneKey<PartitionSpec> kPartitionKeys[] = {
    autoSwitchKey<PartitionSpec, &PartitionSpec::enabled>("enabled"),
    integerKey<PartitionSpec, &PartitionSpec::maxPointsPerBox, 1, INT_MAX>("max_points_per_box"),
    valueKey<PartitionSpec, &PartitionSpec::boxSize, &Reader::nonNegative>("box_size"),
    {"overlap",
     [](const Reader& r, const json& x, const std::string& p, PartitionSpec& s, int) {
       s.overlap = r.number(x, p);
       if (!(s.overlap >= 1)) r.fail(p, "must be >= 1 (got " + describeJson(x) + ")");
     },
     [](const PartitionSpec& s, int) -> Written { return s.overlap; }},
    namedKey<PartitionSpec, &PartitionSpec::blend, parsePuBlend, puBlendName>("blend"),
    valueKey<PartitionSpec, &PartitionSpec::dataReach, &Reader::positive>("data_reach"),
};

constexpr SceneKey<FitSpec> kFitKeys[] = {
    enumKey<FitSpec, &FitSpec::method, kFitMethodNames>("method"),
    namedKey<FitSpec, &FitSpec::kernel, parseKernelType, kernelName>("kernel"),
    valueKey<FitSpec, &FitSpec::radius, &Reader::positive>("radius"),
    namedKey<FitSpec, &FitSpec::polynomial, parsePolynomial, polynomialName>("polynomial"),
    {"smoothing",
     [](const Reader& r, const json& x, const std::string& p, FitSpec& f, int) {
       f.smoothing = r.nonNegative(x, p);
       if (f.smoothing > kMaxSmoothing)
         r.fail(p, "must be <= 1e100 (got " + describeJson(x) + "); larger values overflow the solver, and far "
                   "smaller ones already leave only the polynomial part");
     },
     [](const FitSpec& f, int) -> Written { return json(f.smoothing); }},
    valueKey<FitSpec, &FitSpec::shift, &Reader::positive>("shift"),
    namedKey<FitSpec, &FitSpec::solver, parseSolverChoice, solverName>("solver"),
    {"partition",
     [](const Reader& r, const json& x, const std::string& p, FitSpec& f, int dim) {
       f.partition = readObject<PartitionSpec>(r, x, p, kPartitionKeys, dim);
     },
     [](const FitSpec& f, int dim) -> Written { return writeObject<PartitionSpec>(f.partition, kPartitionKeys, dim); }},
    autoSwitchKey<FitSpec, &FitSpec::reachMask>("reach_mask"),
};

}  // namespace

std::span<const SceneKey<FitSpec>> fitKeys() { return kFitKeys; }

}  // namespace hermite

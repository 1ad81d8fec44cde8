// fitPu (pu_model.h): the tree, which leaves the blend fits, and the local fits in parallel.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <exception>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <omp.h>

#include "core/base/errors.h"
#include "core/base/memory_check.h"
#include "core/base/ms_since.h"
#include "core/base/threading.h"
#include "core/pu/pu_blended_leaves.h"
#include "core/pu/pu_leaf_fitter.h"
#include "core/pu/pu_model.h"
#include "core/rbf/dense_fit_memory.h"
#include "core/rbf/dense_solver.h"

namespace hermite {

using namespace detail;

namespace {

// Refuses (MemoryLimitError) a PU fit whose local fits, one per thread at once, need more memory
// than is available: each holds a system of at most min(n, limits.max · (1 + kEdgeAddedShare))
// samples, as the in-process path (kernel block and saddle matrix: 2 square matrices) or
// fitHrbf's, plus each thread's BLAS buffer when the fits themselves reach kUncheckedBytes.
template <int Dim>
void checkLocalFitMemory(int samples, const SupportLimits& limits, const HrbfOptions& local) {
  const auto most = static_cast<std::int64_t>(limits.max) + static_cast<std::int64_t>(kEdgeAddedShare * limits.max);
  const std::int64_t k = std::min<std::int64_t>(samples, most);  // a refit across an edge adds to the limit
  const std::int64_t m = monomialCount<Dim>(local.polynomial);
  const std::int64_t unknowns = k * (Dim + 1) + m;
  const SolverChoice path =
      plannedSolverPath(local.solver, m, kernelDefiniteSign(local.kernel, local.polynomial, local.smoothing));
  const std::uint64_t perFit = std::max(denseFitBytes(unknowns, path, m),
                                        saturatingProduct({2, std::uint64_t(unknowns), std::uint64_t(unknowns), 8}));
  const int threads = omp_get_max_threads();
  const std::uint64_t fits = saturatingProduct({perFit, std::uint64_t(threads)});
  checkMemory({fits < kUncheckedBytes ? fits : saturatingSum({fits, blasBufferBytes(threads)}),
               "the partition-of-unity fit (" + std::to_string(threads) + " local fits at once, each of up to " +
                   std::to_string(unknowns) + " unknowns)"},
              "lower fit.partition.max_points_per_box or use fewer --threads");
}

// Fits every leaf, in parallel over boxes with one BLAS thread each (the local systems are
// small); rethrows the first failure after all threads are done. The cancel token is polled box
// by box (a box is milliseconds of work): once it is set the remaining boxes are skipped and
// Cancelled is rethrown.
template <int Dim>
void fitLeaves(const LeafFitter<Dim>& fitter, std::vector<typename PuModel<Dim>::Leaf>& leaves,
               std::vector<FitReport>& reports) {
  const int leafCount = static_cast<int>(leaves.size());
  std::exception_ptr failure;
  std::mutex failureMutex;
  const int blasThreads = blasThreadCount();
  setBlasThreadCount(1);
#pragma omp parallel
  {
    LeafScratch<Dim> scratch;
#pragma omp for schedule(dynamic, 8)
    for (int i = 0; i < leafCount; ++i) {
      try {
        throwIfCancelled(fitter.cancel());
        fitter.fit(i, leaves[i], reports[i], scratch);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failureMutex);
        if (!failure) failure = std::current_exception();
      }
    }
  }
  setBlasThreadCount(blasThreads);
  if (failure) std::rethrow_exception(failure);
}

// The local fits' warnings other than `skip`, grouped by kind (the text with its numbers
// blanked), as one line per kind: its count and its first example.
std::vector<std::string> groupLocalWarnings(const std::vector<FitReport>& reports,
                                            const std::vector<std::string>& skip) {
  std::vector<std::pair<std::string, std::pair<int, std::string>>> kinds;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    for (const std::string& w : reports[i].warnings) {
      if (std::find(skip.begin(), skip.end(), w) != skip.end()) continue;
      std::string kind;
      for (char ch : w)
        if (!(ch >= '0' && ch <= '9') && ch != '.' && ch != '+' && ch != 'e') kind += ch;
      auto it = std::find_if(kinds.begin(), kinds.end(), [&](const auto& k) { return k.first == kind; });
      if (it == kinds.end())
        kinds.push_back({kind, {1, "box " + std::to_string(i) + ": " + w}});
      else
        ++it->second.first;
    }
  }
  std::vector<std::string> lines;
  for (const auto& [kind, info] : kinds)
    lines.push_back("partition: " + std::to_string(info.first) + " of " + std::to_string(reports.size()) +
                    " local fits warned like " + info.second);
  return lines;
}

// The fit's report from its tree and local fits (all but the timings).
template <int Dim>
PuReport summariseFits(const PuTree<Dim>& tree, const std::vector<typename PuModel<Dim>::Leaf>& leaves,
                       const std::vector<FitReport>& reports, const PuOptions& options, const HrbfOptions& local) {
  const int leafCount = static_cast<int>(leaves.size());
  PuReport r;
  r.boxes = leafCount;
  r.warnings = polynomialOrderWarnings(local.kernel, local.polynomial);
  std::map<std::string, int> solvers;
  for (int i = 0; i < leafCount; ++i) r.fittedBoxes += leaves[i].blended ? 1 : 0;
  int* same = nullptr;  // the count of the last solver name: neighbouring boxes mostly share it
  const std::string* last = nullptr;
  for (int i = 0; i < leafCount; ++i) {
    r.maxBoxSamples = std::max(r.maxBoxSamples, tree.leafSampleCount(i));
    if (!leaves[i].blended) continue;
    r.maxSupportSamples = std::max(r.maxSupportSamples, leaves[i].samples);
    r.meanSupportSamples += leaves[i].samples / double(r.fittedBoxes);
    if (leaves[i].factor > options.overlap) ++r.grownSupports;
    r.unknowns += reports[i].nUnknowns;
    r.maxConditionEstimate = std::max(r.maxConditionEstimate, reports[i].conditionEstimate);
    if (!last || *last != reports[i].solver) {
      last = &reports[i].solver;
      same = &solvers[*last];
    }
    ++*same;
  }
  int best = -1;
  for (const auto& [name, count] : solvers)
    if (count > best) {
      best = count;
      r.solver = name;
    }
  for (std::string& line : groupLocalWarnings(reports, r.warnings)) r.warnings.push_back(std::move(line));
  return r;
}

// The tree's options of a PU fit (pu_tree.h).
PuTreeOptions treeOptionsOf(const PuOptions& options, const SupportLimits& limits) {
  PuTreeOptions tree;
  tree.maxPointsPerBox = options.maxPointsPerBox;
  tree.boxSize = options.boxSize;
  tree.maxSupportSamples = limits.max;
  tree.overlap = options.overlap;
  tree.splitEmpty = options.blend == PuBlend::Hard;
  tree.cancel = options.local.cancel;
  return tree;
}

}  // namespace

template <int Dim>
PuModel<Dim> fitPu(const HermiteSamples<Dim>& samples, const PuOptions& options, PuReport* report,
                   const Similarity<Dim>& frame) {
  const auto t0 = std::chrono::steady_clock::now();
  if (samples.size() < 1) throw InputError("partition: no samples");
  if (!(options.overlap >= 1)) throw InputError("partition: overlap must be >= 1");
  if (!(options.growth > 1)) throw InputError("partition: growth must be > 1");
  if (!(options.vertexReach > 0) || !std::isfinite(options.vertexReach))
    throw InputError("partition: the zero-set reach must be a finite number > 0");
  const int n = samples.size();
  const bool identity = frame.isIdentity();
  Points<Dim> Y;
  if (!identity) {
    Y.resize(Dim, n);
    for (int i = 0; i < n; ++i) Y.col(i) = frame.applyInverse(samples.points.col(i));
  }
  const Points<Dim>& frameY = identity ? samples.points : Y;
  const SupportLimits limits = supportLimits<Dim>(options);
  PuTree<Dim> tree(frameY, treeOptionsOf(options, limits));
  PuDataReach<Dim> dataReach;
  std::vector<char> blended = blendedLeaves<Dim>(tree, options.blend, options.overlap);
  HrbfOptions local = options.local;
  local.kernel.radius *= frame.q;
  const LeafFitter<Dim> sizer(samples, tree, options, local, limits, blended, nullptr);  // supports only
  splitCrowdedBlended<Dim>(tree, blended, options, sizer, limits);
  if (options.blend == PuBlend::Smooth) {
    // Normals in frame coordinates: y = R⁻¹(x − t)/q turns directions by R⁻¹ = Rᵀ.
    Points<Dim> frameN;
    if (!identity) frameN = frame.R.transpose() * samples.normals;
    dataReach = PuDataReach<Dim>(tree, frameY, options.dataReach, identity ? &samples.normals : &frameN,
                                 options.edgeShift, options.local.cancel);
    refineCover<Dim>(tree, dataReach, blended, options.local.cancel);
  }
  throwIfCancelled(options.local.cancel);
  const double treeMs = msSince(t0);
  const auto leafCount = static_cast<std::size_t>(tree.leafCount());
  std::vector<typename PuModel<Dim>::Leaf> leaves(leafCount);
  std::vector<FitReport> reports(leafCount);
  blendReachCover<Dim>(tree, dataReach, blended);
  throwIfCancelled(options.local.cancel);
  for (std::size_t i = 0; i < leafCount; ++i) leaves[i].blended = blended[i] != 0;
  checkLocalFitMemory<Dim>(n, limits, local);
  const PuDataReach<Dim>* reach = dataReach.empty() ? nullptr : &dataReach;
  fitLeaves<Dim>(LeafFitter<Dim>(samples, tree, options, local, limits, blended, reach), leaves, reports);
  if (report) {
    *report = summariseFits<Dim>(tree, leaves, reports, options, local);
    report->treeMs = treeMs;
    report->fitMs = msSince(t0);
  }
  // Freed on both threads: one local report per box, each with a solver name on the heap.
  const int boxes = static_cast<int>(reports.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < boxes; ++i) reports[static_cast<std::size_t>(i)] = FitReport{};
  return PuModel<Dim>(std::move(tree), std::move(leaves), options, frame, std::move(dataReach));
}

template PuModel<2> fitPu<2>(const HermiteSamples<2>&, const PuOptions&, PuReport*, const Similarity<2>&);
template PuModel<3> fitPu<3>(const HermiteSamples<3>&, const PuOptions&, PuReport*, const Similarity<3>&);

}  // namespace hermite

// `hermite-lab sweep SCENE --radii A:B:K -o DIR` (docs/cli.md): the scene
// refitted at K radii spaced logarithmically in [A, B], one PNG per radius (the view `render`
// draws) and diagnostics.csv with the condition estimate, residuals and leave-one-out error per
// radius, the suggested r (radius_sweep.h) marked — a teacher's figure in one command.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands/commands.h"
#include "app/commands/image_caption.h"
#include "app/commands/output.h"
#include "app/commands/output_path.h"
#include "app/gui/colour_range.h"
#include "app/gui/fit_worker.h"
#include "app/gui/scene_loading.h"
#include "app/gui/scene_view.h"
#include "core/base/errors.h"
#include "core/base/memory_check.h"
#include "core/rbf/dense_fit_memory.h"
#include "core/trace/image.h"
#include "io/atomic_file.h"
#include "io/png_file.h"
#include "render/render_memory.h"
#include "scene/radius_sweep.h"
#include "scene/scene_fit.h"
#include "scene/scene_fit_memory.h"

namespace hermite::app {

namespace {

// True for the files a sweep writes: diagnostics.csv and the images r_NN_R.png.
bool isSweepOutput(const std::string& name) {
  if (name == "diagnostics.csv") return true;
  if (name.size() < 9 || name.compare(0, 2, "r_") != 0 || name.compare(name.size() - 4, 4, ".png") != 0) return false;
  std::size_t i = 2;
  while (i < name.size() && name[i] >= '0' && name[i] <= '9') ++i;
  return i >= 4 && i < name.size() && name[i] == '_';
}

// DIR exists (created when missing) and is a directory holding nothing; with `overwrite` it may
// hold anything, and an earlier sweep's files in it are removed (other files stay).
// EnvironmentError otherwise.
void prepareDirectory(const std::string& dir, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (dir.empty()) throw UsageError("sweep: -o DIR is required");
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw EnvironmentError("sweep: '" + dir + "' exists and is not a directory");
  fs::create_directories(dir, ec);
  if (ec) throw EnvironmentError("sweep: cannot create '" + dir + "': " + ec.message());
  std::vector<fs::path> ours;
  std::size_t entries = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    ++entries;
    if (isSweepOutput(entry.path().filename().string()) && entry.is_regular_file(ec)) ours.push_back(entry.path());
  }
  if (ec) throw EnvironmentError("sweep: cannot list '" + dir + "': " + ec.message());
  if (entries > 0 && !overwrite)
    throw EnvironmentError("sweep: '" + dir + "' is not empty (" + std::to_string(entries) +
                           " entries); choose an empty or new directory, or pass --overwrite to replace an "
                           "earlier sweep's images and diagnostics.csv there");
  for (const fs::path& p : ours)
    if (!fs::remove(p, ec) && ec) throw EnvironmentError("sweep: cannot remove '" + p.string() + "': " + ec.message());
}

// The caption burnt into each image: what was fitted and how well.
std::vector<std::string> captionLines(const Scene& s, const RadiusSweepRow& row) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s  r = %.4g (%.3g x spacing)  cond %.3g", std::string(kernelName(s.fit.kernel)).c_str(),
                row.radius, row.radiusInSpacing, row.conditionEstimate);
  return {buf, radiusSweepVerdict(row, s.dimension()).substr(0, 120)};
}

// Tiles of at most ~2400 px per sheet row: each image shrunk by a whole factor, its own caption.
struct SheetBuilder {
  int columns = 1, factor = 1;
  std::vector<ImageRgba8> tiles;
  SheetBuilder(int count, int w) {
    columns = std::max(1, int(std::ceil(std::sqrt(double(count)))));
    factor = std::max(1, (columns * w + 2399) / 2400);
  }
  std::vector<int> rowOf;  // the sweep row of each tile
  void add(const ImageRgba8& image, const std::vector<std::string>& caption, int row) {
    tiles.push_back(shrinkImage(image, factor));
    burnCaption(tiles.back(), caption, 1);
    rowOf.push_back(row);
  }
  // A 3-pixel orange frame around the suggested row's tile.
  void markSuggested(int row) {
    for (std::size_t t = 0; t < tiles.size(); ++t) {
      if (rowOf[t] != row) continue;
      ImageRgba8& im = tiles[t];
      for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
          if (x < 3 || y < 3 || x >= im.width - 3 || y >= im.height - 3) {
            std::uint8_t* p = im.at(x, y);
            p[0] = 255, p[1] = 160, p[2] = 40, p[3] = 255;
          }
    }
  }
};

std::string imageName(int k, double r) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "r_%02d_%.4g.png", k, r);
  return buf;
}

// One radius's work, before the first: the fit (the same size at every radius; radii run one
// after another) and the image buffers. Leave-one-out, larger, reports its own refusal per row.
template <int Dim>
void checkSweepMemory(const Scene& scene) {
  std::vector<std::string> warnings;
  const HermiteSamples<Dim> samples = sceneSamples<Dim>(scene, warnings);
  if (const auto plan = sceneFitPlan(scene, samples.size())) checkMemory(*plan, kDenseFitRemedy);
}

// The sweep's scene: a data file's default scene is cubic (no radius), so the sweep takes
// wendland unless told; refused for modes and kernels without a radius.
Scene sweepScene(const SweepArgs& args) {
  SceneArgs sceneArgs = args.scene;
  const bool kernelGiven = std::any_of(sceneArgs.overrides.begin(), sceneArgs.overrides.end(),
                                       [](const std::string& o) { return o.rfind("fit.kernel=", 0) == 0; });
  if (!sceneArgs.scenePath.empty() && !isSceneFilePath(sceneArgs.scenePath) && !kernelGiven)
    sceneArgs.overrides.insert(sceneArgs.overrides.begin(), "fit.kernel=wendland");
  Scene scene = loadCommandScene(sceneArgs);
  if (scene.mode != SceneMode::Implicit2d && scene.mode != SceneMode::Implicit3d)
    throw InputError("sweep: mode '" + std::string(sceneModeName(scene.mode)) + "' has no radius to sweep");
  if (!Kernel{scene.fit.kernel, 1.0}.usesRadius())
    throw InputError("sweep: kernel '" + std::string(kernelName(scene.fit.kernel)) +
                     "' has no radius (it is scale-free): nothing to sweep");
  return scene;
}

// What the sweep produced: a row and an image name ("" when the fit failed) per radius.
struct SweepRun {
  std::vector<RadiusSweepRow> rows;
  std::vector<std::string> images;
  std::string firstError;
};

// Fits and renders every radius into `dir` (and onto the contact sheet when asked).
SweepRun sweepRadii(const Scene& scene, const std::vector<double>& radii, const SweepArgs& args,
                    const std::filesystem::path& dir, SheetBuilder& sheet) {
  const int w = scene.view.size[0], h = scene.view.size[1];
  const auto context = offscreenContext(args.backend, w, h);
  SceneViewRenderer renderer;
  renderer.colourRange = sharedColourRange(scene);  // one heat-map range for every radius
  SweepRun run;
  double spacing = -1;
  bool warned = false;
  for (std::size_t k = 0; k < radii.size(); ++k) {
    Scene s = scene;
    s.fit.radius = radii[k];
    const std::shared_ptr<const FitOutcome> fit = fitOutcome(s);
    RadiusSweepRow row;
    std::string image;
    if (fit->ok()) {
      if (!warned && fit->implicitFit()) printDataWarnings(*fit->implicitFit());  // the same data at every radius
      warned = true;
      fit->visitImplicit([&](const auto& f) {
        constexpr int D = std::decay_t<decltype(f)>::kDim;
        if (spacing < 0) spacing = meanSampleSpacing<D>(f.samples.points);
        row = radiusSweepRow<D>(s, f, spacing);
      });
      image = imageName(int(k), radii[k]);
      SceneViewResult view = renderer.render(fit, s, w, h, ViewQuality::Settled);
      const std::vector<std::string> caption = captionLines(s, row);
      if (!args.sheet.empty()) sheet.add(view.image, caption, int(k));
      burnCaption(view.image, caption, std::max(1, w / 500));
      writePng((dir / image).string(), view.image);
    } else {
      row.radius = radii[k];
      row.error = fit->error;
      if (run.firstError.empty()) run.firstError = fit->error;
    }
    run.rows.push_back(std::move(row));
    run.images.push_back(std::move(image));
  }
  return run;
}

// The table printed on stdout: one line per radius, the suggestion starred, then notes.
std::string sweepSummary(const SweepRun& run, int best, int dim) {
  std::string out;
  char buf[256];
  for (std::size_t k = 0; k < run.rows.size(); ++k) {
    const RadiusSweepRow& r = run.rows[k];
    if (r.ok())
      std::snprintf(buf, sizeof buf, "%s r = %-10.4g cond %-10.3g ", int(k) == best ? "*" : " ", r.radius,
                    r.conditionEstimate);
    else
      std::snprintf(buf, sizeof buf, "  r = %-10.4g ", r.radius);
    out += buf + radiusSweepVerdict(r, dim).substr(0, 200);
    out += run.images[k].empty() ? "\n" : "  " + run.images[k] + "\n";
  }
  if (best < 0)
    out += "no radius suggested: every radius failed, is ill-conditioned (condition above 1e14) or has no finite "
           "validation error; try smaller radii or a polynomial term\n";
  else if (run.rows[std::size_t(best)].degenerate || run.rows[std::size_t(best)].defects() > 0)
    out += "note: every candidate radius has a degenerate field, spurious zero-set components or sign failures; the "
           "suggestion has the fewest — try a wider range of radii or a polynomial term\n";
  return out;
}

}  // namespace

int runSweep(const SweepArgs& args) {
  Scene scene = sweepScene(args);
  const std::vector<double> radii = parseRadiiArgument(args.radii);
  if (!args.size.empty()) scene.view.size = parseImageSize(args.size);
  checkMemory(renderPlan(scene.view.size[0], scene.view.size[1]), kRenderRemedy);
  if (scene.mode == SceneMode::Implicit2d) checkSweepMemory<2>(scene);
  else checkSweepMemory<3>(scene);
  if (!args.sheet.empty()) {
    requireExtension("sweep --sheet", args.sheet, {"png"});
    requireWritableLocation("sweep --sheet", args.sheet);
  }
  prepareDirectory(args.outputDirectory, args.overwrite);
  const std::filesystem::path dir(args.outputDirectory);

  SheetBuilder sheet(int(radii.size()), scene.view.size[0]);
  const SweepRun run = sweepRadii(scene, radii, args, dir, sheet);
  writeFileAtomically((dir / "diagnostics.csv").string(), radiusSweepCsv(run.rows, &run.images));

  const int best = suggestedRadiusIndex(run.rows);
  std::string out = sweepSummary(run, best, scene.dimension());
  out += "wrote " + std::to_string(radii.size()) + " rows to " + (dir / "diagnostics.csv").string() + "\n";
  if (!args.sheet.empty()) {
    sheet.markSuggested(best);
    writePng(args.sheet, contactSheet(sheet.tiles, sheet.columns));
    out += "wrote a contact sheet of " + std::to_string(sheet.tiles.size()) + " images to " + args.sheet + "\n";
  }
  writeStdout(out);
  bool anyOk = false;
  for (const auto& r : run.rows) anyOk |= r.ok();
  if (!anyOk) throw NumericalError("sweep: no radius could be fitted: " + run.firstError);
  return 0;
}

}  // namespace hermite::app

#include "app/commands/cli.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <malloc.h>
#include <new>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands/byte_size.h"
#include "app/commands/commands.h"
#include "app/commands/error_report.h"
#include "app/commands/fatal_exit.h"
#include "app/commands/kept_until_exit.h"
#include "app/commands/output.h"
#include "core/base/blas_setup.h"
#include "core/base/edit_distance.h"
#include "core/base/errors.h"
#include "core/base/memory_check.h"
#include "core/base/threading.h"
#include "io/input_file.h"
#include "io/system_memory.h"

namespace hermite::app {

namespace {

constexpr const char* kUsage =
    "hermite-lab: Hermite data (points + normals) fitted by Hermite RBF implicits.\n"
    "\n"
    "usage:\n"
    "  hermite-lab [SCENE] [--ui-scale S] [--set KEY=VALUE ...]  the GUI on SCENE (default: the demo scene);\n"
    "                                                            without a display: its fit report\n"
    "  hermite-lab fit SCENE [--json] [--coefficients] [--set KEY=VALUE ...]\n"
    "  hermite-lab eval SCENE --at FILE [--set KEY=VALUE ...]\n"
    "  hermite-lab render SCENE -o OUT.png [--size WxH] [--ui [--explore]] [--ui-scale S] [--backend osmesa|egl] [--set KEY=VALUE ...]\n"
    "  hermite-lab sweep SCENE --radii A:B:K -o DIR [--overwrite] [--size WxH] [--set KEY=VALUE ...]\n"
    "  hermite-lab mesh SCENE -o OUT.{glb,gltf,ply,obj} [--resolution N] [--chord-tolerance F] [--set KEY=VALUE ...]  (2D: OUT.{obj,svg})\n"
    "  hermite-lab holefill IN -o OUT [--json] [--rings N] [--implicit rbf-offset|hrbf] [--allow-open]\n"
    "  hermite-lab patch-table [--samples N] [--splits 1x1,2x1,2x2,3x3] [--domain U0,U1,V0,V1] [--json]\n"
    "  hermite-lab bench [--json] [--only NAME]\n"
    "SCENE is a scene file (.json) or a data file (.xyz .pwn .xyzn .xyn .ply .obj .gltf .glb .off): a default\n"
    "scene is built around a data file (docs/scene-format.md, Data files as scenes)\n"
    "options everywhere: --threads N (default: all cores), --max-input-size BYTES (default 4G);\n"
    "`hermite-lab COMMAND --help` for details\n";

void addSceneOptions(CLI::App& cmd, SceneArgs& scene, bool required) {
  auto* opt = cmd.add_option("scene", scene.scenePath,
                             "scene file (JSON, docs/scene-format.md) or a point or mesh file (a default scene "
                             "around it)");
  if (required) opt->required();
  cmd.add_option("--set", scene.overrides, "override a scene key: KEY=VALUE (VALUE is JSON or a string)")
      ->take_all()
      ->allow_extra_args(false);
}

// N in [1, 4096]; above the cores this process may use it is lowered to them, with a note (more
// threads than cores only add memory and contention: OpenBLAS gives each its own buffers).
void addThreads(CLI::App& cmd, int& threads) {
  cmd.add_option("--threads", threads, "worker threads (default: all cores; at most the cores available)")
      ->check(CLI::Range(1, 4096))
      ->transform([](std::string value) {
        const int cores = availableCores();
        long n = 0;
        const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
        // Not a whole number, or one the range check rejects anyway: left to that check's message.
        if (ec != std::errc() || end != value.data() + value.size() || n <= cores) return value;
        std::fprintf(stderr, "note: --threads %s is more than the %d cores available to this process; using %d\n",
                     value.c_str(), cores, cores);
        return std::to_string(cores);
      });
}

// --ui-scale S in [0.5, 4]: the type, widgets and layout of the GUI (and of render --ui).
void addUiScale(CLI::App& cmd, double& scale) {
  cmd.add_option("--ui-scale", scale, "UI scale, 0.5 to 4 (GUI default: the monitor's content scale; render --ui: 1)")
      ->check(CLI::Range(0.5, 4.0));
}

// --max-input-size BYTES, an option of every command: the largest input file read.
void addMaxInputSize(CLI::App& cmd, std::string& text) {
  cmd.add_option("--max-input-size", text, "largest input file read, e.g. 512M, 8G (default 4G)")
      ->type_name("BYTES")
      ->check([](const std::string& value) {
        const auto bytes = parseByteSize(value);
        return bytes && *bytes > 0 ? std::string() : "expected a byte count > 0 such as 4096, 512M or 8G";
      });
}

// Parses with CLI11, with the options every command shares and no command handles itself
// (--max-input-size); returns -1 to go on, or the exit code (0 for --help, 2 for usage errors).
int parse(CLI::App& cmd, int argc, char** argv) {
  std::string maxInput;
  addMaxInputSize(cmd, maxInput);
  try {
    cmd.parse(argc, argv);
    if (!maxInput.empty()) setMaxInputSize(*parseByteSize(maxInput));
  } catch (const CLI::CallForHelp& e) {
    return cmd.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cmd.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::string help = cmd.get_name() == "hermite-lab" ? "hermite-lab --help" : "hermite-lab " + cmd.get_name() + " --help";
    reportError(2, "hermite-lab", e.what());
    std::fprintf(stderr, "run '%s' for usage\n", help.c_str());
    return 2;
  }
  return -1;
}

// The display command `name` of `display`, or a usage error when this is the headless program
// (run directly instead of through the hermite-lab launcher).
template <class Command>
Command displayCommand(Command command, const char* name) {
  if (command == nullptr)
    throw UsageError(std::string("'") + name + "' needs the full program: run it as hermite-lab " + name +
                     " (this executable runs fit, eval, mesh, holefill and patch-table only)");
  return command;
}

// Adds --threads, parses argv (argc counts from the command's name) and runs `run` when the
// arguments are complete; the exit code of a help or parse error otherwise.
template <class Run>
int parseThenRun(CLI::App& cmd, int argc, char** argv, Run run) {
  int threads = 0;
  addThreads(cmd, threads);
  if (int rc = parse(cmd, argc, argv); rc >= 0) return rc;
  if (threads > 0) setThreadCount(threads);
  return run();
}

int fitCommand(int argc, char** argv, const DisplayCommands& /*display*/) {
  FitArgs a;
  CLI::App cmd("fit a scene and report residuals, solver and timing", "fit");
  addSceneOptions(cmd, a.scene, true);
  cmd.add_flag("--json", a.json, "machine-readable output (docs/cli.md)");
  cmd.add_flag("--coefficients", a.coefficients, "also print the fitted model (centres, alpha, beta, poly)");
  cmd.add_flag("--verify", a.verify,
               "with a transform, also re-solve on the transformed data and compare (as transform.verify)");
  return parseThenRun(cmd, argc - 1, argv + 1, [&] { return runFit(a); });
}

int evalCommand(int argc, char** argv, const DisplayCommands& /*display*/) {
  EvalArgs a;
  CLI::App cmd("evaluate the fitted field and its gradient at points read from a file", "eval");
  addSceneOptions(cmd, a.scene, true);
  cmd.add_option("--at", a.probeFile, "file with one point per line (2 or 3 numbers)")->required();
  return parseThenRun(cmd, argc - 1, argv + 1, [&] { return runEval(a); });
}

int renderCommand(int argc, char** argv, const DisplayCommands& display) {
  RenderArgs a;
  CLI::App cmd("render a scene to a PNG without a display (OSMesa or EGL)", "render");
  addSceneOptions(cmd, a.scene, true);
  cmd.add_option("-o,--output", a.output, "output PNG (written atomically)");
  cmd.add_option("--size", a.size, "image size WxH (default: the scene's view.size)");
  cmd.add_flag("--ui", a.ui, "draw the application's panels on top");
  cmd.add_flag("--explore", a.explore, "with --ui: open the r explorer and run its sweep to the end first");
  addUiScale(cmd, a.uiScale);
  cmd.add_option("--backend", a.backend, "headless GL context: osmesa (default) or egl")
      ->check(CLI::IsMember({"osmesa", "egl"}));
  return parseThenRun(cmd, argc - 1, argv + 1, [&] { return displayCommand(display.render, "render")(a); });
}

int sweepCommand(int argc, char** argv, const DisplayCommands& display) {
  SweepArgs a;
  CLI::App cmd("refit a scene at log-spaced radii: one PNG per radius and diagnostics.csv", "sweep");
  addSceneOptions(cmd, a.scene, true);
  cmd.add_option("--radii", a.radii, "A:B:K — K radii spaced logarithmically from A to B")->required();
  cmd.add_option("-o,--output", a.outputDirectory, "output directory (created when missing)")->required();
  cmd.add_flag("--overwrite", a.overwrite,
               "reuse a non-empty output directory: remove its earlier sweep images and diagnostics.csv first");
  cmd.add_option("--size", a.size, "image size WxH (default: the scene's view.size)");
  cmd.add_option("--sheet", a.sheet, "also write a contact sheet of every image (a .png file)");
  cmd.add_option("--backend", a.backend, "headless GL context: osmesa (default) or egl")
      ->check(CLI::IsMember({"osmesa", "egl"}));
  return parseThenRun(cmd, argc - 1, argv + 1, [&] { return displayCommand(display.sweep, "sweep")(a); });
}

int meshCommand(int argc, char** argv, const DisplayCommands& /*display*/) {
  MeshArgs a;
  CLI::App cmd("mesh the fitted zero set over view.bounds: marching cubes (3D), marching squares (2D)", "mesh");
  addSceneOptions(cmd, a.scene, true);
  cmd.add_option("-o,--output", a.output, "OUT.glb, .gltf, .ply or .obj (2D: .obj polylines or .svg)")->required();
  cmd.add_option("--resolution", a.resolution,
                 "cells along the longest side of view.bounds (default: 3D round(0.6*sqrt(samples)) within "
                 "64-256, 2D 64)")
      ->check(CLI::Range(1, 4096));
  cmd.add_option("--chord-tolerance", a.chordTolerance,
                 "3D: split edges whose chord strays more than this many grid cells from the zero set, the new "
                 "vertices projected onto it (default 0.02; 0: off)")
      ->check(CLI::Range(0.0, 1.0));
  return parseThenRun(cmd, argc - 1, argv + 1, [&] { return runMesh(a); });
}

int holefillCommand(int argc, char** argv, const DisplayCommands& /*display*/) {
  HoleFillArgs a;
  CLI::App cmd("fill the holes of a triangle mesh (advancing front, fairing, RBF projection)", "holefill");
  cmd.add_option("input", a.input, "triangle mesh (.off, .obj, .ply, .glb, .gltf)")->required();
  cmd.add_option("-o,--output", a.output, "OUT.glb, .gltf, .ply or .obj (written atomically)")->required();
  cmd.add_flag("--json", a.json, "machine-readable output (docs/cli.md)");
  cmd.add_option("--rings", a.rings, "vertex rings around each hole fitted by the implicit (default 2)")
      ->check(CLI::Range(1, 10));
  cmd.add_option("--implicit", a.implicit, "rbf-offset (default: cubic, linear, ±d offsets) or hrbf")
      ->check(CLI::IsMember({"rbf-offset", "hrbf"}));
  cmd.add_flag("--allow-open", a.allowOpen, "exit 0 even when some hole stays open (default: exit 5)");
  return parseThenRun(cmd, argc - 1, argv + 1, [&] { return runHoleFill(a); });
}

int patchTableCommand(int argc, char** argv, const DisplayCommands& /*display*/) {
  PatchTableArgs a;
  CLI::App cmd("torus error study: bicubic Hermite patches from exact data vs the torus", "patch-table");
  cmd.add_option("--samples", a.samples, "N x N local parameters per patch (default 15)")->check(CLI::Range(2, 100000));
  cmd.add_option("--splits", a.splits, "comma-separated NxM splits, N along u (default 1x1,2x1,2x2,3x3)");
  cmd.add_option("--domain", a.domain, "U0,U1,V0,V1 (default 0,1,0,1)");
  cmd.add_flag("--json", a.json, "machine-readable output (docs/cli.md)");
  return parseThenRun(cmd, argc - 1, argv + 1, [&] { return runPatchTable(a); });
}

int benchCommand(int argc, char** argv, const DisplayCommands& display) {
  BenchArgs a;
  CLI::App cmd("measure fit and evaluation speed on this machine", "bench");
  cmd.add_flag("--json", a.json, "machine-readable output");
  cmd.add_option("--only", a.only, "run the benchmarks whose name contains NAME");
  cmd.add_flag("--quick", a.quick, "one repetition, small sizes (smoke test)");
  return parseThenRun(cmd, argc - 1, argv + 1, [&] { return displayCommand(display.bench, "bench")(a); });
}

using CommandFunction = int (*)(int, char**, const DisplayCommands&);
constexpr std::pair<const char*, CommandFunction> kCommandFunctions[] = {
    {"fit", fitCommand},
    {"eval", evalCommand},
    {"render", renderCommand},
    {"sweep", sweepCommand},
    {"mesh", meshCommand},
    {"holefill", holefillCommand},
    {"patch-table", patchTableCommand},
    {"bench", benchCommand},
};

// What the first argument asks before any command runs: help, the version, or a mistyped
// command (a word that is no file and within two edits of a command); none to go on.
std::optional<int> topLevel(const std::string& first) {
  if (first == "--help" || first == "-h" || first == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (first == "--version" || first == "version") {
    writeStdout("hermite-lab " HERMITE_VERSION "\n");
    return 0;
  }
  if (first.empty() || first[0] == '-' || first.find_first_of("./") != std::string::npos ||
      std::filesystem::exists(first))
    return std::nullopt;
  std::vector<const char*> commands;  // in this order for the first suggestion within two edits
  for (const auto& [name, command] : kCommandFunctions) commands.push_back(name);
  commands.insert(commands.end(), {"help", "version"});
  for (const char* command : commands)
    if (first == command) return std::nullopt;
  for (const char* command : commands)
    if (editDistance(first, command) <= 2)
      throw UsageError("unknown command '" + first + "' (did you mean '" + command + "'?); 'hermite-lab --help' lists the commands");
  return std::nullopt;
}

int dispatch(int argc, char** argv, const DisplayCommands& display) {
  const std::string first = argc > 1 ? argv[1] : "";
  if (const std::optional<int> rc = topLevel(first)) return *rc;
  for (const auto& [name, command] : kCommandFunctions)
    if (first == name) return command(argc, argv, display);
  // No subcommand: the program's main job on SCENE (or the demo scene).
  SceneArgs a;
  double uiScale = 0;
  CLI::App cmd("Hermite Lab", "hermite-lab");
  addSceneOptions(cmd, a, false);
  addUiScale(cmd, uiScale);
  return parseThenRun(cmd, argc, argv, [&] { return displayCommand(display.window, "the window")(a, uiScale); });
}

}  // namespace

int runCli(int argc, char** argv, const DisplayCommands& display) {
  installFatalHandlers();
  setAvailableMemorySource(querySystemMemory);
  noteJsonRequested(argc, argv);
  try {
    const int rc = dispatch(argc, argv, display);
    finishStdout();
    return rc;
  } catch (const InputError& e) {
    return reportError(1, "error", e.what());
  } catch (const UsageError& e) {
    return reportError(2, "usage error", e.what());
  } catch (const NumericalError& e) {
    return reportError(3, "numerical failure", e.what());
  } catch (const EnvironmentError& e) {
    return reportError(4, "environment error", e.what());
  } catch (const std::bad_alloc&) {
    exitOutOfMemory("");
  } catch (const std::exception& e) {
    return reportError(4, "internal error", e.what());
  }
}

int runProgram(int argc, char** argv, const DisplayCommands& display) {
  reexecWithTunedBlas(argv);
  // Keep large freed blocks in the heap instead of returning them to the kernel: the GUI and the
  // fits allocate the same multi-megabyte buffers again and again (tessellations, grids, kernel
  // matrices), and with glibc's defaults each one is a fresh mmap whose first touch page-faults
  // (docs/performance.md).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  enableKeepUntilExit();  // a command's last large objects go with the process (kept_until_exit.h)
  return runCli(argc, argv, display);
}

}  // namespace hermite::app

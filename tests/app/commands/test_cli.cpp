#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <cmath>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"

using hermite::testing::runCli;
using hermite::testing::writeTemp;
using json = nlohmann::json;

namespace {

// An independent evaluation of docs/maths.md (HRBF system) from the exported coefficients: scalar code written
// from the formulas, sharing nothing with src/core.
struct IndependentModel {
  std::string kernel;
  double r;
  std::string poly;
  int dim;
  std::vector<std::vector<double>> c, beta;
  std::vector<double> alpha, pc, po;  // po: the polynomial is p(y − po)

  explicit IndependentModel(const json& m)
      : kernel(m["kernel"]), r(m["radius"]), poly(m["polynomial"]), dim(m["dimension"]) {
    for (const auto& v : m["centres"]) c.push_back(v.get<std::vector<double>>());
    for (const auto& v : m["beta"]) beta.push_back(v.get<std::vector<double>>());
    alpha = m["alpha"].get<std::vector<double>>();
    pc = m["poly"].get<std::vector<double>>();
    po = m.contains("poly_origin") ? m["poly_origin"].get<std::vector<double>>() : std::vector<double>(dim, 0.0);
  }
  // φ(x) and φ′(x), φ″(x) by the textbook formulas.
  void radial(double x, double& p0, double& p1, double& p2) const {
    const double s = x / r;
    if (kernel == "gaussian") {
      p0 = std::exp(-s * s);
      p1 = -2 * x / (r * r) * p0;
      p2 = (-2 / (r * r) + 4 * x * x / std::pow(r, 4)) * p0;
    } else if (kernel == "wendland") {
      const double u = std::max(0.0, 1 - s);
      p0 = std::pow(u, 4) * (4 * s + 1);
      p1 = -20 * s * std::pow(u, 3) / r;
      p2 = (-20 * std::pow(u, 3) + 60 * s * u * u) / (r * r);
    } else if (kernel == "cubic") {
      p0 = x * x * x, p1 = 3 * x * x, p2 = 6 * x;
    } else {
      throw std::runtime_error("kernel not covered by this reference");
    }
  }
  // f and ∇f at y.
  std::vector<double> eval(const std::vector<double>& y) const {
    std::vector<double> out(dim + 1, 0.0);
    for (size_t j = 0; j < c.size(); ++j) {
      std::vector<double> d(dim);
      double x2 = 0;
      for (int k = 0; k < dim; ++k) d[k] = y[k] - c[j][k], x2 += d[k] * d[k];
      const double x = std::sqrt(x2);
      double p0, p1, p2;
      radial(x, p0, p1, p2);
      // ∇φ = φ′ d/x;  Hφ = φ′/x I + (φ″ − φ′/x) d dᵀ/x²   (x > 0 at the probe points)
      const double a = p1 / x, b = (p2 - a) / x2;
      double bd = 0;
      for (int k = 0; k < dim; ++k) bd += beta[j][k] * d[k];
      out[0] += alpha[j] * p0 - a * bd;
      for (int k = 0; k < dim; ++k) out[1 + k] += alpha[j] * a * d[k] - (a * beta[j][k] + b * bd * d[k]);
    }
    if (poly != "none") {
      out[0] += pc[0];
      std::vector<double> yp(dim);
      for (int k = 0; k < dim; ++k) yp[k] = y[k] - po[k];
      for (int k = 0; k < dim; ++k) out[0] += pc[1 + k] * yp[k], out[1 + k] += pc[1 + k];
      if (poly == "quadratic") {
        int q = 1 + dim;
        for (int i = 0; i < dim; ++i)
          for (int k = i; k < dim; ++k, ++q) {
            out[0] += pc[q] * yp[i] * yp[k];
            out[1 + i] += pc[q] * yp[k];
            out[1 + k] += pc[q] * yp[i];
          }
      }
    }
    return out;
  }
};

std::string sceneJson(int dim, const std::string& kernel, double radius, const std::string& poly) {
  std::ostringstream s;
  s << R"({"version": 1, "mode": ")" << (dim == 2 ? "implicit2d" : "implicit3d") << R"(", "data": {"preset": ")"
    << (dim == 2 ? "curve2d" : "torus") << R"(", "count": )" << (dim == 2 ? 40 : 150) << R"(}, "fit": {"kernel": ")"
    << kernel << R"(", "radius": )" << radius << R"(, "polynomial": ")" << poly << R"("}})";
  return s.str();
}

}  // namespace

TEST_CASE("fit --json reports the docs/cli.md keys with interpolation residuals ≤ 1e-9") {
  const std::string scene = writeTemp("torus_cubic.json", sceneJson(3, "cubic", 1.0, "linear"));
  const auto r = runCli("fit " + scene + " --json");
  REQUIRE(r.rc == 0);
  const json j = json::parse(r.out);
  for (const char* key : {"n_samples", "n_unknowns", "solver", "condition_estimate", "max_abs_f", "max_grad_error",
                          "fit_ms", "warnings", "partition", "transform"})
    CHECK(j.contains(key));
  CHECK(j["n_samples"] == 150);
  CHECK(j["n_unknowns"] == 150 * 4 + 4);
  CHECK(j["max_abs_f"].get<double>() <= 1e-9);
  CHECK(j["max_grad_error"].get<double>() <= 1e-9);
  CHECK(j["partition"].is_null());
  CHECK(j["transform"].is_null());
}

TEST_CASE("eval and --coefficients agree with an independent implementation of docs/maths.md") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.1, 1.1);
  struct Case {
    int dim;
    std::string kernel;
    double radius;
    std::string poly;
  };
  for (const Case& c : {Case{3, "cubic", 1, "linear"}, Case{3, "gaussian", 0.6, "none"}, Case{3, "wendland", 1.5, "quadratic"},
                        Case{2, "cubic", 1, "quadratic"}, Case{2, "gaussian", 0.2, "linear"}}) {
    CAPTURE(c.kernel);
    CAPTURE(c.dim);
    const std::string scene = writeTemp("eval_" + c.kernel + std::to_string(c.dim) + ".json",
                                        sceneJson(c.dim, c.kernel, c.radius, c.poly));
    // One thread each: the dense solve takes as many BLAS threads as the machine has idle cores
    // (BlasThreadsForLoad), and for this ill-conditioned gaussian fit a one-thread and a
    // two-thread LU differ by 4e-9 relative, so `fit` and `eval` would disagree whenever the
    // load changed between them (about 1 run in 10 under ctest -j2).
    const auto fit = runCli("fit " + scene + " --json --coefficients --threads 1");
    REQUIRE(fit.rc == 0);
    const IndependentModel model(json::parse(fit.out)["model"]);
    std::ostringstream probes;
    probes.precision(17);
    std::vector<std::vector<double>> pts;
    for (int i = 0; i < 40; ++i) {
      std::vector<double> p(c.dim);
      for (double& v : p) v = u(rng);
      pts.push_back(p);
      for (double v : p) probes << v << ' ';
      probes << '\n';
    }
    const std::string probeFile = writeTemp("probes" + std::to_string(c.dim) + ".txt", probes.str());
    const auto ev = runCli("eval " + scene + " --at " + probeFile + " --threads 1");
    REQUIRE(ev.rc == 0);
    std::istringstream in(ev.out);
    double maxF = 0, maxG = 0, errF = 0, errG = 0;
    for (const auto& p : pts) {
      const std::vector<double> ref = model.eval(p);
      std::vector<double> got(c.dim + 1);
      for (double& v : got) REQUIRE(static_cast<bool>(in >> v));
      maxF = std::max(maxF, std::abs(ref[0]));
      errF = std::max(errF, std::abs(ref[0] - got[0]));
      for (int k = 0; k < c.dim; ++k) {
        maxG = std::max(maxG, std::abs(ref[1 + k]));
        errG = std::max(errG, std::abs(ref[1 + k] - got[1 + k]));
      }
    }
    CHECK(errF <= 1e-10 * maxF);
    CHECK(errG <= 1e-10 * maxG);
  }
}

TEST_CASE("exit codes: 1 bad input naming the place, 2 usage, 3 numerical failure, 4 output failure") {
  const std::string bad = writeTemp("bad_radius.json",
                                    R"({"version": 1, "mode": "implicit3d", "data": {"preset": "sphere6"}, "fit": {"radius": -1}})");
  auto r = runCli("fit " + bad);
  CHECK(r.rc == 1);
  CHECK(r.err.find("fit.radius") != std::string::npos);

  const std::string syntax = writeTemp("syntax.json", "{\n  \"version\": 1,\n  \"mode\": \"implicit3d\",,\n}");
  r = runCli("fit " + syntax);
  CHECK(r.rc == 1);
  CHECK(r.err.find(":3:") != std::string::npos);

  r = runCli("fit /nonexistent/scene.json");
  CHECK(r.rc == 1);
  CHECK(r.err.find("/nonexistent/scene.json") != std::string::npos);

  const std::string good = writeTemp("good.json", sceneJson(3, "cubic", 1.0, "linear"));
  r = runCli("fit " + good + " --set fit.kernel=thin-plate");
  CHECK(r.rc == 1);
  CHECK(r.err.find("fit.kernel") != std::string::npos);

  r = runCli("fit " + good + " --no-such-flag");
  CHECK(r.rc == 2);
  r = runCli("fit");
  CHECK(r.rc == 2);
  r = runCli("eval " + good);  // --at is required
  CHECK(r.rc == 2);

  const std::string line = writeTemp("line.json", R"({"version": 1, "mode": "implicit3d", "data": {"points": [[0,0,0],[1,0,0]],
    "normals": [[0,0,1],[0,0,1]]}, "fit": {"kernel": "gaussian", "polynomial": "quadratic"}})");
  r = runCli("fit " + line);
  CHECK(r.rc == 3);
  CHECK(r.err.find("polynomial") != std::string::npos);

  const std::string probes = writeTemp("one_probe.txt", "0 0 0\n");
  r = runCli("eval " + good + " --at " + probes, "/dev/full");
  CHECK(r.rc == 4);

  const std::string badProbe = writeTemp("bad_probe.txt", "0 0 0\n1 2 x\n");
  r = runCli("eval " + good + " --at " + badProbe);
  CHECK(r.rc == 1);
  CHECK(r.err.find(":2:") != std::string::npos);
}

TEST_CASE("--set overrides scene keys with JSON values or strings") {
  const std::string scene = writeTemp("set.json", sceneJson(3, "cubic", 1.0, "linear"));
  const auto r = runCli("fit " + scene + " --json --set fit.kernel=gaussian --set fit.radius=0.7 --set fit.polynomial=none "
                        "--set data.count=50");
  REQUIRE(r.rc == 0);
  const json j = json::parse(r.out);
  CHECK(j["kernel"] == "gaussian");
  CHECK(j["radius"] == 0.7);
  CHECK(j["n_samples"] == 50);
  CHECK(j["solver"] == "cholesky");
}

TEST_CASE("a transformed scene is the interpolant of the transformed data") {
  const std::string scene = writeTemp("moved.json", R"({"version": 1, "mode": "implicit3d", "data": {"preset": "sphere6"},
    "fit": {"kernel": "gaussian", "radius": 1.0, "polynomial": "none"},
    "transform": {"translate": [1, 2, 3], "rotate_axis_angle_deg": [0, 0, 1, 90], "scale": 2}})");
  const auto plain = runCli("fit " + scene + " --json");
  REQUIRE(plain.rc == 0);
  const json p = json::parse(plain.out);
  REQUIRE(p["transform"].is_object());
  for (const char* key : {"resolve_ms", "max_abs_df", "max_grad_diff"}) {
    CHECK(p["transform"].contains(key));
    CHECK(p["transform"][key].is_null());  // no comparison without --verify
  }
  const auto r = runCli("fit " + scene + " --json --verify");
  REQUIRE(r.rc == 0);
  const json j = json::parse(r.out);
  REQUIRE(j["transform"].is_object());
  CHECK(j["transform"]["method"] == "coefficient-update");
  CHECK(j["transform"]["max_abs_df"].get<double>() <= 1e-9);
  CHECK(j["transform"]["max_grad_diff"].get<double>() <= 1e-9);
  CHECK(j["transform"]["update_ms"].get<double>() >= 0);
  CHECK(j["transform"]["resolve_ms"].get<double>() > 0);
  CHECK(j["max_abs_f"].get<double>() <= 1e-9);
  CHECK(j["max_grad_error"].get<double>() <= 1e-9);
  // The transformed sphere of radius 2 about (1, 2, 3): f vanishes on it, ∇f points outward.
  const std::string probes = writeTemp("moved_probes.txt", "3 2 3\n1 4 3\n");
  const auto ev = runCli("eval " + scene + " --at " + probes);
  REQUIRE(ev.rc == 0);
  std::istringstream in(ev.out);
  double f, gx, gy, gz;
  in >> f >> gx >> gy >> gz;
  CHECK(std::abs(f) <= 1e-9);
  CHECK(gx == doctest::Approx(1.0).epsilon(1e-9));
  in >> f >> gx >> gy >> gz;
  CHECK(std::abs(f) <= 1e-9);
  CHECK(gy == doctest::Approx(1.0).epsilon(1e-9));
}

TEST_CASE("bench --quick --json reports cores and results") {
  const auto r = runCli("bench --quick --json --only fit3d/");
  REQUIRE(r.rc == 0);
  const json j = json::parse(r.out);
  CHECK(j["cores"].get<int>() >= 1);
  CHECK(!j["blas_core"].get<std::string>().empty());
  REQUIRE(j["results"].size() == 12);  // three fit cases × four sizes
  for (const auto& res : j["results"]) {
    CHECK(res["unit"] == "ms");
    CHECK(res["median"].get<double>() > 0);
    // The factorisation's speed next to plain LAPACK's on the block it factorised.
    CHECK(res["params"]["factor_gflops"].get<double>() > 0);
    CHECK(res["params"]["lapack_gflops"].get<double>() > 0);
    CHECK(res["params"]["factorised_size"].get<int>() > 0);
  }
  CHECK(runCli("bench --only no-such-benchmark").rc == 2);
}

TEST_CASE("without a display the program says so and prints the demo scene's fit report") {
  const char* display = std::getenv("DISPLAY");
  const std::string saved = display ? display : "";
  ::unsetenv("DISPLAY");
  ::unsetenv("WAYLAND_DISPLAY");
  const auto r = runCli("");
  if (!saved.empty()) ::setenv("DISPLAY", saved.c_str(), 1);
  CHECK(r.rc == 0);
  CHECK(r.err.find("the GUI needs a display") != std::string::npos);
  CHECK(r.out.find("solver") != std::string::npos);
  CHECK(r.out.find("residuals") != std::string::npos);
}

TEST_CASE("sweep: one PNG per radius and diagnostics.csv with the suggested r marked once") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "hermite_sweep_test";
  fs::remove_all(dir);
  const std::string scene = writeTemp("sweep.json", R"({"version": 1, "mode": "implicit2d",
    "data": {"preset": "curve2d", "count": 30}, "fit": {"kernel": "gaussian", "polynomial": "none"}})");
  const auto r = runCli("sweep " + scene + " --radii 0.05:0.6:4 --size 64x48 -o " + dir.string());
  REQUIRE(r.rc == 0);
  std::ifstream csv(dir / "diagnostics.csv");
  REQUIRE(csv.good());
  std::string line;
  std::getline(csv, line);
  CHECK(line.rfind("radius,", 0) == 0);
  CHECK(line.find("loo_combined") != std::string::npos);
  int rows = 0, suggested = 0;
  double previous = 0;
  while (std::getline(csv, line)) {
    ++rows;
    const double radius = std::stod(line.substr(0, line.find(',')));
    CHECK(radius > previous);  // increasing, log-spaced
    previous = radius;
    const std::string image = line.substr(line.rfind(',') + 1);
    CHECK(fs::exists(dir / image));
    // The `suggested` column (the 11th) is 1 on exactly one row.
    std::size_t pos = 0;
    for (int k = 0; k < 10; ++k) pos = line.find(',', pos) + 1;
    suggested += line[pos] == '1' ? 1 : 0;
  }
  CHECK(rows == 4);
  CHECK(previous == doctest::Approx(0.6));
  CHECK(suggested == 1);
  CHECK(runCli("sweep " + scene + " --radii 0.05:0.6 -o " + dir.string()).rc == 2);
  CHECK(runCli("sweep " + scene + " --radii 0.05:0.6:3 -o " + dir.string() + " --set fit.kernel=cubic").rc == 1);
  fs::remove_all(dir);
}

TEST_CASE("a transform outside the exact conditions is re-solved, with a warning") {
  const std::string scene = writeTemp("smoothed.json", R"({"version": 1, "mode": "implicit3d", "data": {"preset": "sphere", "count": 40},
    "fit": {"kernel": "cubic", "polynomial": "linear", "smoothing": 0.01}, "transform": {"scale": 2}})");
  const auto r = runCli("fit " + scene + " --json");
  REQUIRE(r.rc == 0);
  const json j = json::parse(r.out);
  CHECK(j["transform"]["method"] == "re-solve");
  CHECK(j["transform"]["exact"] == false);
  bool warned = false;
  for (const auto& w : j["warnings"]) warned |= w.get<std::string>().find("smoothing") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("patch-table --json: rows with splits, per-coordinate error and Hermite/Bézier agreement") {
  auto r = runCli("patch-table --json --splits 1x1,2x2 --samples 15");
  REQUIRE(r.rc == 0);
  const json j = json::parse(r.out);
  REQUIRE(j["rows"].size() == 2);
  CHECK(j["rows"][0]["splits"] == json::array({1, 1}));
  CHECK(j["rows"][0]["error"][0].get<double>() == doctest::Approx(0.0717).epsilon(0.01));
  CHECK(j["rows"][1]["error"][0].get<double>() < j["rows"][0]["error"][0].get<double>());
  CHECK(j["rows"][0]["hermite_bezier_max_diff"].get<double>() <= 1e-13);
  r = runCli("patch-table --domain 0,0.5,0,0.5 --splits 1x1 --json");
  REQUIRE(r.rc == 0);
  CHECK(json::parse(r.out)["rows"][0]["error"][2].get<double>() == doctest::Approx(3.7e-4).epsilon(0.03));
  CHECK(runCli("patch-table --splits 2y2").rc == 2);
  CHECK(runCli("patch-table --domain 1,0,0,1").rc == 1);
  r = runCli("patch-table");
  CHECK(r.rc == 0);
  CHECK(r.out.find("3x3") != std::string::npos);
}

TEST_CASE("a partition-of-unity scene fits, reports its boxes, transforms and evaluates") {
  const std::string scene = writeTemp("pu.json", R"({"version": 1, "mode": "implicit3d", "data": {"preset": "torus", "count": 600},
    "fit": {"kernel": "cubic", "polynomial": "linear", "partition": {"enabled": true, "max_points_per_box": 20}}})");
  auto r = runCli("fit " + scene + " --json --coefficients");
  REQUIRE(r.rc == 0);
  json j = json::parse(r.out);
  REQUIRE(j["partition"].is_object());
  const int boxes = j["partition"]["boxes"].get<int>();
  CHECK(boxes > 8);
  CHECK(j["partition"]["max_box_samples"].get<int>() <= 20);
  CHECK(j["max_abs_f"].get<double>() <= 1e-9);
  CHECK(j["max_grad_error"].get<double>() <= 1e-8);
  REQUIRE(j["model"]["boxes"].size() == static_cast<std::size_t>(boxes));
  const json& box0 = j["model"]["boxes"][0];
  CHECK(box0["lo"].size() == 3);
  CHECK(box0["support"]["hi"].size() == 3);
  CHECK(box0["model"]["alpha"].size() == box0["model"]["centres"].size());
  CHECK(box0["model"]["poly"].size() == 4);

  r = runCli("fit " + scene + " --json --verify --set 'transform={\"translate\":[0.5,-1,2],\"rotate_axis_angle_deg\":[1,1,0,40],\"scale\":1.5}'");
  REQUIRE(r.rc == 0);
  j = json::parse(r.out);
  REQUIRE(j["transform"].is_object());
  CHECK(j["transform"]["method"] == "coefficient-update");
  CHECK(j["transform"]["max_abs_df"].get<double>() <= 1e-9);
  CHECK(j["transform"]["max_grad_diff"].get<double>() <= 1e-8);
  CHECK(j["max_abs_f"].get<double>() <= 1e-9);

  // The torus preset (R = 0.7, r = 0.3 about z): f ≈ 0 on the outer equator, ∇f along +x there.
  const std::string probes = writeTemp("pu_probes.txt", "1 0 0\n");
  const auto ev = runCli("eval " + scene + " --at " + probes);
  REQUIRE(ev.rc == 0);
  std::istringstream in(ev.out);
  double f, gx, gy, gz;
  in >> f >> gx >> gy >> gz;
  CHECK(std::abs(f) <= 1e-3);
  CHECK(gx / std::sqrt(gx * gx + gy * gy + gz * gz) >= 0.99);

  const std::string offset = writeTemp("pu_offset.json", R"({"version": 1, "mode": "implicit2d", "data": {"preset": "curve2d"},
    "fit": {"method": "rbf-offset", "partition": {"enabled": true}}})");
  r = runCli("fit " + offset);
  CHECK(r.rc == 1);
  CHECK(r.err.find("fit.partition.enabled") != std::string::npos);
}

TEST_CASE("headless commands run without the display's libraries; the others in the full program") {
  namespace fs = std::filesystem;
  const std::string scene = std::string(HERMITE_FIXTURES) + "/scenes/minimal.json";
  const std::string probes = writeTemp("headless_probes.txt", "0 0 0\n");
  const std::string mesh = (fs::temp_directory_path() / "hermite_headless_mesh.ply").string();
  // LD_DEBUG=libs makes the dynamic loader name every library it initialises on stderr.
  const auto loaded = [](const std::string& args) {
    const std::string err = (fs::temp_directory_path() / "hermite_headless_ld.txt").string();
    const int status = std::system(("LD_DEBUG=libs " + std::string(HERMITE_EXE) + " " + args + " > /dev/null 2> " + err).c_str());
    return std::make_pair(WIFEXITED(status) ? WEXITSTATUS(status) : -1, hermite::testing::readAll(err));
  };
  for (const std::string& args : {"fit " + scene + " --json", "eval " + scene + " --at " + probes,
                                  "mesh " + scene + " -o " + mesh + " --resolution 16", std::string("patch-table --help"),
                                  std::string("holefill --help")}) {
    CAPTURE(args);
    const auto [rc, log] = loaded(args);
    CHECK(rc == 0);
    CHECK(log.find("calling init:") != std::string::npos);  // the loader's log is there
    for (const char* display : {"libglfw", "libEGL", "libX11", "libGL"}) CHECK(log.find(display) == std::string::npos);
  }
  // The same check sees the display's libraries in the full program.
  const auto [rc, log] = loaded("render --help");
  CHECK(rc == 0);
  CHECK(log.find("libglfw") != std::string::npos);
  fs::remove(mesh);

  // Run directly, the headless program names the command it cannot run and the one that can.
  const fs::path headless = fs::path(HERMITE_EXE).parent_path() / "hermite-lab-cli";
  const int status = std::system((headless.string() + " render " + scene + " -o x.png > /dev/null 2> " +
                                  (fs::temp_directory_path() / "hermite_headless_err.txt").string()).c_str());
  CHECK(WEXITSTATUS(status) == 2);
  CHECK(hermite::testing::readAll((fs::temp_directory_path() / "hermite_headless_err.txt").string())
            .find("run it as hermite-lab render") != std::string::npos);
}

#pragma once
// The 3D tracer's figures for `hermite-lab bench` (render/trace-baked): bake, baked trace and
// exact refinement of a fitted HRBF, timed in a fresh offscreen context.

namespace hermite::app {

// Times in milliseconds.
struct TracerBenchResult {
  double bakeMs = 0;         // bake at bakeResolution³ of an HRBF with bakeCentres centres
  double traceMs = 0;        // median baked trace (no refinement) at width×height, N = traceCentres
  double refineMs = 0;       // median CPU exact refinement of that settled view, N = traceCentres
  double traceAllPixelsMs = 0;  // the same trace with skipEmptyTiles off (every pixel traced)
  long long tracedPixels = 0;   // pixels the trace pass ran on (the others are in empty tiles)
  int bakeCentres = 250;
  int traceCentres = 1000;
  int bakeResolution = 128;
  int width = 1024, height = 768;
  int hitPixels = 0;
};

// Fits cubic HRBFs to the torus preset with the given sample counts and times bake, trace and
// refinement in a fresh context (`backend` names it, as createContext). `repeats` ≥ 1 frames each.
TracerBenchResult benchTracer(int bakeCentres = 250, int traceCentres = 1000, int bakeResolution = 128,
                              int width = 1024, int height = 768, int repeats = 3, const char* backend = "osmesa");

}  // namespace hermite::app

#pragma once
// The GUI latency figures of `hermite-lab bench`: a sample dragged with scripted
// mouse input in the real application (GuiApp on an OSMesa context, fits on the worker thread as
// in the window), timed from the start of the frame whose input moved the sample to the end of
// the frame that shows the view refitted to the new position ("within one 60 Hz frame": frames
// = 1 and at most 16.7 ms) — in 3D the refit's first, coarse bake; finalMs waits for the view's
// finer bake too. Frames keep to 60 per second as under vsync.

#include "app/gui/frame_phases.h"

namespace hermite::app {

struct DragLatencyResult {
  double medianMs = 0;  // start of the frame reading the input → updated image presented
  double maxMs = 0;
  double finalMs = 0;   // median until the view shows the refit at its final (drag) quality
  double withFrameWaitMs = 0;  // median from the mouse move, incl. the wait for the frame slot
  double frames = 0;           // median frames from the input to the updated image (1: the same)
  double fitMs = 0;     // median fit time inside it
  double viewMs = 0;    // median redraw time inside it
  int samples = 0;
  int width = 0, height = 0;  // window size (the view is the part right of the panel)
  int moves = 0;
};

// dimension 2: the curve2d preset with `samples` points; 3: the bunny preset. Cubic + linear
// (the demo settings).
DragLatencyResult benchDragLatency(int dimension, int samples, int moves, int width, int height);

// Frame times while long work runs (issue 18: every frame ≤ 33 ms at 1280×800 on llvmpipe):
// frames paced at 60 Hz from the moment the work starts until the view shows its settled result.
struct BusyFramesResult {
  double worstMs = 0;   // the slowest frame (GuiApp::frame + present)
  double medianMs = 0;
  int frames = 0;
  double totalMs = 0;   // from the start of the work to the settled view
  int samples = 0;
  int width = 0, height = 0;
  FramePhases worstPhases;  // where the slowest frame's time went
  double worstPresentMs = 0;  // its present (glFinish on the offscreen context)
  double fitMs = 0;           // the shown fit's own wall clock (FitOutcome::wallMs)
  double over33 = 0;          // frames longer than 33 ms
};

// A dense HRBF fit of the bunny preset with `samples` points submitted from a settled 50-point
// view; frames until it is on screen.
BusyFramesResult benchFramesDuringDenseFit(int samples, int width, int height);
// A partition-of-unity fit of the bunny preset with `samples` points, settled, orbited by a short
// drag; frames from the release until the settled (baked + refined) render is on screen.
BusyFramesResult benchFramesDuringSettledRender(int samples, int width, int height);

}  // namespace hermite::app

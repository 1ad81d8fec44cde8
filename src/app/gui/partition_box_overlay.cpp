#include "app/gui/partition_box_overlay.h"

#include <imgui.h>

#include <algorithm>

#include "scene/scene_fit.h"

namespace hermite::app {

namespace {

const ImU32 kBoxColour = IM_COL32(90, 60, 160, 170);
constexpr std::size_t kMaxBoxes = 4000;  // beyond this the lines only hide the view

// o: the view's origin in the window (pixels).
void drawBoxes(const GuiContext& ctx, const PuModel<2>& pu, ImDrawList* dl, const Vec<2>& o) {
  const ImU32 colour = kBoxColour;
  const View2d view = sceneView2d(ctx.scene(), ctx.view.primaryWidth(), ctx.view.h);
  for (std::size_t k = 0; k < std::min(pu.leaves().size(), kMaxBoxes); ++k) {
    const auto& leaf = pu.leaves()[k];
    const Vec<2> c = leaf.support.center(), h = 0.5 * leaf.support.extent() / leaf.factor;
    ImVec2 pts[4];
    const Vec<2> corners[4] = {c + Vec<2>(-h.x(), -h.y()), c + Vec<2>(h.x(), -h.y()), c + Vec<2>(h.x(), h.y()),
                               c + Vec<2>(-h.x(), h.y())};
    for (int i = 0; i < 4; ++i) {
      const Vec<2> q = view.worldToPixel(pu.frame().apply(corners[i])) + o;
      pts[i] = ImVec2(float(q.x()), float(q.y()));
    }
    dl->AddPolyline(pts, 4, colour, ImDrawFlags_Closed, 1.0f);
  }
}

void drawBoxes(const GuiContext& ctx, const PuModel<3>& pu, ImDrawList* dl, const Vec<2>& o) {
  const ImU32 colour = kBoxColour;
  const Camera cam = sceneCamera(ctx.scene(), ctx.view.primaryWidth(), ctx.view.h);
  for (std::size_t k = 0; k < std::min(pu.leaves().size(), kMaxBoxes); ++k) {
    const auto& leaf = pu.leaves()[k];
    const Vec<3> c = leaf.support.center(), h = 0.5 * leaf.support.extent() / leaf.factor;
    const auto corner = [&](int i) {
      return pu.frame().apply(Vec<3>(c.x() + ((i & 1) ? h.x() : -h.x()), c.y() + ((i & 2) ? h.y() : -h.y()),
                                     c.z() + ((i & 4) ? h.z() : -h.z())));
    };
    for (int i = 0; i < 8; ++i)
      for (int bit = 1; bit <= 4; bit <<= 1) {
        if (i & bit) continue;
        const Vec<3> a = corner(i), b = corner(i | bit);
        if (cam.projection() == Projection::Perspective &&
            ((a - cam.eye()).dot(cam.forward()) <= 0 || (b - cam.eye()).dot(cam.forward()) <= 0))
          continue;
        const Vec<2> pa = cam.project(a) + o, pb = cam.project(b) + o;
        dl->AddLine(ImVec2(float(pa.x()), float(pa.y())), ImVec2(float(pb.x()), float(pb.y())), colour, 1.0f);
      }
  }
}

}  // namespace

void drawPartitionBoxes(const GuiContext& ctx) {
  const FitOutcome* f = ctx.fits.shown().get();
  if (!f) return;
  f->visitImplicit([&](const auto& fit) {
    if (fit.pu()) drawBoxes(ctx, *fit.pu(), ImGui::GetBackgroundDrawList(), ctx.view.origin());
  });
}

}  // namespace hermite::app

#include <doctest/doctest.h>

#include <imgui.h>

#include "render/gl/offscreen.h"
#include "render/imgui_renderer.h"
#include "support/render_test_support.h"

using namespace hermite;
using namespace hermite::render;

namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;
// The panel's rectangle in pixels (row 0 = top).
constexpr int kLeft = 20, kTop = 30, kPanelWidth = 100, kPanelHeight = 60;

struct ImGuiScope {
  ImGuiScope() {
    context = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.LogFilename = nullptr;
    io.DisplaySize = ImVec2(kWidth, kHeight);
    io.DeltaTime = 1.0f / 60.0f;
    ImGui::StyleColorsDark();
  }
  ~ImGuiScope() { ImGui::DestroyContext(context); }
  ImGuiContext* context;
};

void buildFrame() {
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(kLeft, kTop), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, kPanelHeight), ImGuiCond_Always);
  ImGui::Begin("Fit", nullptr, ImGuiWindowFlags_NoSavedSettings);
  ImGui::Text("radius 0.5");
  ImGui::Text("kernel cubic");
  ImGui::End();
  ImGui::Render();
}

ImageRgba8 renderFrame(ImGuiRenderer& renderer) {
  buildFrame();
  OffscreenTarget target(kWidth, kHeight, false);
  target.bind();
  glClearColor(10.0f / 255.0f, 200.0f / 255.0f, 10.0f / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  renderer.render(ImGui::GetDrawData());
  checkGl("ImGui frame");
  return target.read();
}

bool isBackground(const std::uint8_t* p) { return p[0] == 10 && p[1] == 200 && p[2] == 10 && p[3] == 255; }

}  // namespace

TEST_CASE("ImGui draw data renders offscreen inside the panel only, and identically twice") {
  auto context = testing::makeTestContext();
  const ImGuiScope imgui;
  ImGuiRenderer renderer;
  buildFrame();  // the first frame lays the window out
  const ImageRgba8 first = renderFrame(renderer);
  const ImageRgba8 second = renderFrame(renderer);

  int outside = 0;
  int inside_drawn = 0;
  int bright_text = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t* p = first.at(x, y);
      const bool in_panel = x >= kLeft && x < kLeft + kPanelWidth && y >= kTop && y < kTop + kPanelHeight;
      if (!in_panel) {
        outside += isBackground(p) ? 0 : 1;
      } else {
        inside_drawn += isBackground(p) ? 0 : 1;
        // Text is light grey/white on the dark window background.
        bright_text += (p[0] > 180 && p[1] > 180 && p[2] > 180) ? 1 : 0;
      }
    }
  }
  CHECK(outside == 0);
  CHECK(inside_drawn == kPanelWidth * kPanelHeight);
  CHECK(bright_text > 40);
  CHECK(first == second);
}

TEST_CASE("the ImGui renderer leaves the caller's GL state as it found it") {
  auto context = testing::makeTestContext();
  const ImGuiScope imgui;
  ImGuiRenderer renderer;
  buildFrame();
  buildFrame();
  OffscreenTarget target(kWidth, kHeight, true);
  target.bind();
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glViewport(1, 2, 3, 4);
  renderer.render(ImGui::GetDrawData());
  CHECK(glIsEnabled(GL_DEPTH_TEST) == GL_TRUE);
  CHECK(glIsEnabled(GL_BLEND) == GL_FALSE);
  CHECK(glIsEnabled(GL_SCISSOR_TEST) == GL_FALSE);
  GLint viewport[4] = {};
  glGetIntegerv(GL_VIEWPORT, viewport);
  CHECK(viewport[0] == 1);
  CHECK(viewport[3] == 4);
}

#pragma once
// Draws Dear ImGui 1.86 draw data with the project's GL wrappers, so panels look the same in a
// window and offscreen (Debian's prebuilt imgui_impl_opengl3 cannot load GL under OSMesa).
// Needs a current ImGui context and a current GL 4.5 context while constructed and used.

#include "render/gl/gl_objects.h"

struct ImDrawData;

namespace hermite::render {

class ImGuiRenderer {
 public:
  // Builds the font atlas of the current ImGui context into a texture and registers itself as
  // the renderer backend (io.BackendRendererName, vertex offsets supported).
  ImGuiRenderer();
  // Unregisters from the ImGui context that is current then (if any).
  ~ImGuiRenderer();
  ImGuiRenderer(const ImGuiRenderer&) = delete;
  ImGuiRenderer& operator=(const ImGuiRenderer&) = delete;

  // Re-uploads the font atlas (after fonts were added or the atlas rebuilt).
  void rebuildFontTexture();

  // Draws into the framebuffer bound now, whose size must be DisplaySize * FramebufferScale
  // pixels. Blending, scissor and the other state it changes are restored afterwards.
  void render(const ImDrawData* draw_data);

 private:
  Program program_;
  VertexArray vertex_array_;
  Buffer vertices_;
  Buffer indices_;
  Texture font_;
};

}  // namespace hermite::render

#include "render/imgui_renderer.h"

#include <imgui.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/gl/shader_library.h"

namespace hermite::render {

namespace {

constexpr GLenum kIndexType = sizeof(ImDrawIdx) == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT;

ImTextureID toTextureId(GLuint texture) {
  return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(texture));
}

GLuint fromTextureId(ImTextureID id) {
  return static_cast<GLuint>(reinterpret_cast<std::intptr_t>(id));
}

// The GL state render() changes, restored afterwards so the caller's drawing is unaffected.
struct SavedState {
  GLint program = 0;
  GLint vertex_array = 0;
  GLint active_texture = 0;
  GLint texture = 0;
  GLint viewport[4] = {};
  GLint scissor_box[4] = {};
  GLint blend_src_rgb = 0, blend_dst_rgb = 0, blend_src_alpha = 0, blend_dst_alpha = 0;
  GLint blend_equation_rgb = 0, blend_equation_alpha = 0;
  GLint polygon_mode[2] = {};
  GLboolean blend = GL_FALSE, cull = GL_FALSE, depth = GL_FALSE, stencil = GL_FALSE, scissor = GL_FALSE;

  SavedState() {
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture);
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetIntegerv(GL_SCISSOR_BOX, scissor_box);
    glGetIntegerv(GL_BLEND_SRC_RGB, &blend_src_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &blend_dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_src_alpha);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_dst_alpha);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &blend_equation_rgb);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &blend_equation_alpha);
    glGetIntegerv(GL_POLYGON_MODE, polygon_mode);
    blend = glIsEnabled(GL_BLEND);
    cull = glIsEnabled(GL_CULL_FACE);
    depth = glIsEnabled(GL_DEPTH_TEST);
    stencil = glIsEnabled(GL_STENCIL_TEST);
    scissor = glIsEnabled(GL_SCISSOR_TEST);
  }

  static void setEnabled(GLenum cap, GLboolean on) {
    if (on) {
      glEnable(cap);
    } else {
      glDisable(cap);
    }
  }

  void restore() const {
    glUseProgram(static_cast<GLuint>(program));
    glBindVertexArray(static_cast<GLuint>(vertex_array));
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(texture));
    glActiveTexture(static_cast<GLenum>(active_texture));
    glBlendEquationSeparate(static_cast<GLenum>(blend_equation_rgb), static_cast<GLenum>(blend_equation_alpha));
    glBlendFuncSeparate(static_cast<GLenum>(blend_src_rgb), static_cast<GLenum>(blend_dst_rgb),
                        static_cast<GLenum>(blend_src_alpha), static_cast<GLenum>(blend_dst_alpha));
    setEnabled(GL_BLEND, blend);
    setEnabled(GL_CULL_FACE, cull);
    setEnabled(GL_DEPTH_TEST, depth);
    setEnabled(GL_STENCIL_TEST, stencil);
    setEnabled(GL_SCISSOR_TEST, scissor);
    glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygon_mode[0]));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glScissor(scissor_box[0], scissor_box[1], scissor_box[2], scissor_box[3]);
  }
};

// Where each draw list starts in the one vertex and one index buffer of a frame.
struct ListBases {
  std::vector<std::size_t> vertex, index;
};

// All lists in one vertex and one index upload; each list keeps its own base vertex/index.
ListBases uploadDrawLists(const ImDrawData* draw_data, Buffer& vertices, Buffer& indices) {
  ListBases bases;
  bases.vertex.resize(static_cast<std::size_t>(draw_data->CmdListsCount));
  bases.index.resize(bases.vertex.size());
  std::size_t vertex_count = 0;
  std::size_t index_count = 0;
  for (int n = 0; n < draw_data->CmdListsCount; ++n) {
    const ImDrawList* list = draw_data->CmdLists[n];
    bases.vertex[static_cast<std::size_t>(n)] = vertex_count;
    bases.index[static_cast<std::size_t>(n)] = index_count;
    vertex_count += static_cast<std::size_t>(list->VtxBuffer.Size);
    index_count += static_cast<std::size_t>(list->IdxBuffer.Size);
  }
  vertices.setData(nullptr, vertex_count * sizeof(ImDrawVert), GL_STREAM_DRAW);
  indices.setData(nullptr, index_count * sizeof(ImDrawIdx), GL_STREAM_DRAW);
  for (int n = 0; n < draw_data->CmdListsCount; ++n) {
    const ImDrawList* list = draw_data->CmdLists[n];
    vertices.setSubData(bases.vertex[static_cast<std::size_t>(n)] * sizeof(ImDrawVert), list->VtxBuffer.Data,
                        static_cast<std::size_t>(list->VtxBuffer.Size) * sizeof(ImDrawVert));
    indices.setSubData(bases.index[static_cast<std::size_t>(n)] * sizeof(ImDrawIdx), list->IdxBuffer.Data,
                       static_cast<std::size_t>(list->IdxBuffer.Size) * sizeof(ImDrawIdx));
  }
  return bases;
}

// Orthographic map of the display rectangle (y down) to clip space.
glm::mat4 displayProjection(const ImDrawData* draw_data) {
  const float l = draw_data->DisplayPos.x;
  const float r = l + draw_data->DisplaySize.x;
  const float t = draw_data->DisplayPos.y;
  const float b = t + draw_data->DisplaySize.y;
  return glm::mat4(2.0f / (r - l), 0.0f, 0.0f, 0.0f,
                   0.0f, 2.0f / (t - b), 0.0f, 0.0f,
                   0.0f, 0.0f, -1.0f, 0.0f,
                   (r + l) / (l - r), (t + b) / (b - t), 0.0f, 1.0f);
}

// Blending on, culling, depth and stencil off, scissor on, over the whole framebuffer.
void setupBlendState(int fb_width, int fb_height) {
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_SCISSOR_TEST);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glViewport(0, 0, fb_width, fb_height);
}

// One textured command of list n, clipped to its rectangle (skipped when that is empty).
void drawCommand(const ImDrawData* draw_data, const ImDrawCmd& cmd, const ListBases& bases, int n, int fb_height) {
  const ImVec2 origin = draw_data->DisplayPos;
  const ImVec2 scale = draw_data->FramebufferScale;
  // Clip rectangle in framebuffer pixels (y down), then flipped for glScissor (y up).
  const float x0 = (cmd.ClipRect.x - origin.x) * scale.x;
  const float y0 = (cmd.ClipRect.y - origin.y) * scale.y;
  const float x1 = (cmd.ClipRect.z - origin.x) * scale.x;
  const float y1 = (cmd.ClipRect.w - origin.y) * scale.y;
  if (x1 <= x0 || y1 <= y0) return;
  glScissor(static_cast<GLint>(x0), static_cast<GLint>(static_cast<float>(fb_height) - y1),
            static_cast<GLsizei>(x1 - x0), static_cast<GLsizei>(y1 - y0));
  glBindTextureUnit(0, fromTextureId(cmd.TextureId));
  const std::size_t first_index = bases.index[static_cast<std::size_t>(n)] + cmd.IdxOffset;
  glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(cmd.ElemCount), kIndexType,
                           reinterpret_cast<const void*>(first_index * sizeof(ImDrawIdx)),
                           static_cast<GLint>(bases.vertex[static_cast<std::size_t>(n)] + cmd.VtxOffset));
}

}  // namespace

ImGuiRenderer::ImGuiRenderer() : program_(buildProgram({"imgui.vert", "imgui.frag"})) {
  // One interleaved ImDrawVert stream: pos (2 floats), uv (2 floats), col (RGBA8).
  vertex_array_.setVertexBuffer(0, vertices_, 0, sizeof(ImDrawVert));
  vertex_array_.setAttribute(0, 0, 2, GL_FLOAT, false, offsetof(ImDrawVert, pos));
  vertex_array_.setAttribute(1, 0, 2, GL_FLOAT, false, offsetof(ImDrawVert, uv));
  vertex_array_.setAttribute(2, 0, 4, GL_UNSIGNED_BYTE, true, offsetof(ImDrawVert, col));
  vertex_array_.setElementBuffer(indices_);

  ImGuiIO& io = ImGui::GetIO();
  io.BackendRendererName = "hermite_render";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;
  rebuildFontTexture();
}

ImGuiRenderer::~ImGuiRenderer() {
  if (ImGui::GetCurrentContext() == nullptr) return;
  ImGuiIO& io = ImGui::GetIO();
  if (io.Fonts->TexID == toTextureId(font_.id())) io.Fonts->SetTexID(nullptr);
  io.BackendRendererName = nullptr;
  io.BackendFlags &= ~ImGuiBackendFlags_RendererHasVtxOffset;
}

void ImGuiRenderer::rebuildFontTexture() {
  ImGuiIO& io = ImGui::GetIO();
  unsigned char* pixels = nullptr;
  int width = 0;
  int height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  font_ = Texture::create2D(GL_RGBA8, width, height);
  font_.upload2D(GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  io.Fonts->SetTexID(toTextureId(font_.id()));
}

void ImGuiRenderer::render(const ImDrawData* draw_data) {
  if (draw_data == nullptr || draw_data->CmdListsCount == 0) return;
  const int fb_width = static_cast<int>(draw_data->DisplaySize.x * draw_data->FramebufferScale.x);
  const int fb_height = static_cast<int>(draw_data->DisplaySize.y * draw_data->FramebufferScale.y);
  if (fb_width <= 0 || fb_height <= 0) return;
  const ListBases bases = uploadDrawLists(draw_data, vertices_, indices_);

  const SavedState saved;
  auto setupState = [&] {
    setupBlendState(fb_width, fb_height);
    program_.use();
    program_.setUniform("u_projection", displayProjection(draw_data));
    vertex_array_.bind();
  };
  setupState();
  for (int n = 0; n < draw_data->CmdListsCount; ++n) {
    const ImDrawList* list = draw_data->CmdLists[n];
    for (int c = 0; c < list->CmdBuffer.Size; ++c) {
      const ImDrawCmd& cmd = list->CmdBuffer[c];
      if (cmd.UserCallback == nullptr)
        drawCommand(draw_data, cmd, bases, n, fb_height);
      else if (cmd.UserCallback == ImDrawCallback_ResetRenderState)
        setupState();
      else
        cmd.UserCallback(list, &cmd);
    }
  }
  checkGl("drawing ImGui draw data");
  saved.restore();
}

}  // namespace hermite::render

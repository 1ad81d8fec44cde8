#pragma once
// RAII, move-only wrappers of OpenGL 4.5 objects (direct state access: no binding to edit), and
// the optional GL error checks. Objects must be destroyed while their context is current.

#include <glad/gl.h>

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>

#include <glm/glm.hpp>

namespace hermite::render {

// ---- error checks -------------------------------------------------------------------------
// Off by default (glGetError stalls the pipeline). On: every wrapper operation calls checkGl, and
// contexts created afterwards get synchronous GL debug output whose error messages go into the
// exception (for a context that already exists, call installGlDebugOutput while it is current).
// Tests turn it on; HERMITE_GL_CHECKS=1 in the environment turns it on at start-up.
void setGlChecks(bool enabled);
bool glChecksEnabled();
// Installs the synchronous debug-output callback on the current context (no-op without
// GL_KHR_debug support). Called by contexts on creation while checks are enabled.
void installGlDebugOutput();
// With checks enabled: throws hermite::EnvironmentError naming `what`, the GL error code(s) and
// the driver's debug message when glGetError reports an error. Without: does nothing.
void checkGl(std::string_view what);
// Drops pending GL error flags and recorded debug messages (after deliberate errors).
void clearGlErrors();
// "GL_INVALID_VALUE", or hex for unknown codes.
std::string glErrorName(GLenum code);

// ---- Buffer ---------------------------------------------------------------------------------
class Buffer {
 public:
  Buffer();  // glCreateBuffers: an empty buffer
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  // Replaces the store (glNamedBufferData); `data` may be null to allocate only.
  void setData(const void* data, std::size_t bytes, GLenum usage = GL_DYNAMIC_DRAW);
  template <class T>
  void setData(std::span<const T> values, GLenum usage = GL_DYNAMIC_DRAW) {
    setData(values.data(), values.size_bytes(), usage);
  }
  void setSubData(std::size_t offset, const void* data, std::size_t bytes);

  GLuint id() const { return id_; }
  std::size_t size() const { return size_; }  // bytes

 private:
  GLuint id_ = 0;
  std::size_t size_ = 0;
};

// ---- VertexArray ----------------------------------------------------------------------------
class VertexArray {
 public:
  VertexArray();
  ~VertexArray();
  VertexArray(VertexArray&& other) noexcept;
  VertexArray& operator=(VertexArray&& other) noexcept;
  VertexArray(const VertexArray&) = delete;
  VertexArray& operator=(const VertexArray&) = delete;

  // Binds `buffer` to binding point `binding`: vertices start at `offset` bytes, `stride` bytes apart.
  void setVertexBuffer(GLuint binding, const Buffer& buffer, std::size_t offset, GLsizei stride);
  // Enables attribute `location` read from `binding`: `components` values of `type` at
  // `relative_offset` bytes into each vertex; normalized maps integer types to [0, 1] / [-1, 1].
  void setAttribute(GLuint location, GLuint binding, GLint components, GLenum type, bool normalized,
                    GLuint relative_offset);
  void setElementBuffer(const Buffer& buffer);
  void bind() const;

  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

// ---- Texture --------------------------------------------------------------------------------
class Texture {
 public:
  Texture() = default;  // no GL object
  ~Texture();
  Texture(Texture&& other) noexcept;
  Texture& operator=(Texture&& other) noexcept;
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;

  // Immutable storage. `internal_format` e.g. GL_RGBA8, GL_R32F, GL_DEPTH_COMPONENT24.
  // Linear filtering and clamp-to-edge by default.
  static Texture create2D(GLenum internal_format, int width, int height, int levels = 1);
  static Texture create3D(GLenum internal_format, int width, int height, int depth, int levels = 1);

  // Whole level 0 from tightly packed rows (unpack alignment 1): width*height(*depth) texels of
  // `format`/`type`, x fastest, then y, then z.
  void upload2D(GLenum format, GLenum type, const void* pixels);
  void upload3D(GLenum format, GLenum type, const void* voxels);
  void setFilter(GLenum min_filter, GLenum mag_filter);
  void setWrap(GLenum wrap);  // all axes
  void bind(GLuint unit) const;

  GLuint id() const { return id_; }
  GLenum target() const { return target_; }
  GLenum internalFormat() const { return internal_format_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int depth() const { return depth_; }
  bool valid() const { return id_ != 0; }

 private:
  GLuint id_ = 0;
  GLenum target_ = 0;
  GLenum internal_format_ = 0;
  int width_ = 0;
  int height_ = 0;
  int depth_ = 0;
};

// ---- Framebuffer ----------------------------------------------------------------------------
class Framebuffer {
 public:
  Framebuffer() = default;  // no GL object
  // A complete framebuffer of width x height pixels with an owned GL_RGBA8 colour texture and,
  // when `with_depth`, a GL_DEPTH_COMPONENT24 depth texture.
  Framebuffer(int width, int height, bool with_depth);
  ~Framebuffer();
  Framebuffer(Framebuffer&& other) noexcept;
  Framebuffer& operator=(Framebuffer&& other) noexcept;
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  // Binds for drawing and sets the viewport to the whole framebuffer.
  void bind() const;
  // Throws hermite::EnvironmentError unless glCheckNamedFramebufferStatus says complete.
  void checkComplete() const;

  GLuint id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const Texture& color() const { return color_; }
  const Texture& depth() const { return depth_; }

 private:
  GLuint id_ = 0;
  int width_ = 0;
  int height_ = 0;
  Texture color_;
  Texture depth_;
};

// ---- Shader and Program ---------------------------------------------------------------------
// Plain compile/link; shader_library.h turns the logs into file:line errors.
class Shader {
 public:
  explicit Shader(GLenum stage);  // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ...
  ~Shader();
  Shader(Shader&& other) noexcept;
  Shader& operator=(Shader&& other) noexcept;
  Shader(const Shader&) = delete;
  Shader& operator=(const Shader&) = delete;

  // Returns false on a compile error; infoLog() has the driver's message.
  bool compile(std::string_view source);
  std::string infoLog() const;

  GLuint id() const { return id_; }
  GLenum stage() const { return stage_; }

 private:
  GLuint id_ = 0;
  GLenum stage_ = 0;
};

class Program {
 public:
  Program();
  ~Program();
  Program(Program&& other) noexcept;
  Program& operator=(Program&& other) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  void attach(const Shader& shader);
  // Returns false on a link error; infoLog() has the driver's message. Shaders may be deleted after.
  bool link();
  std::string infoLog() const;
  void use() const;

  // -1 when the uniform does not exist or was optimised away (setting it is then a no-op).
  GLint uniformLocation(const std::string& name) const;
  void setUniform(const std::string& name, int value) const;
  void setUniform(const std::string& name, float value) const;
  void setUniform(const std::string& name, double value) const;  // a `double` uniform (GLSL 4.00)
  void setUniform(const std::string& name, const glm::vec2& value) const;
  void setUniform(const std::string& name, const glm::vec3& value) const;
  void setUniform(const std::string& name, const glm::vec4& value) const;
  void setUniform(const std::string& name, const glm::ivec2& value) const;
  void setUniform(const std::string& name, const glm::ivec3& value) const;
  void setUniform(const std::string& name, const glm::mat3& value) const;
  void setUniform(const std::string& name, const glm::mat4& value) const;

  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
  mutable std::unordered_map<std::string, GLint> locations_;
};

}  // namespace hermite::render

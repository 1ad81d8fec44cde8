#include "render/gl/gl_objects.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "core/base/errors.h"

namespace hermite::render {

// ---- error checks -------------------------------------------------------------------------
namespace {

bool checksFromEnvironment() {
  const char* value = std::getenv("HERMITE_GL_CHECKS");
  return value != nullptr && std::strcmp(value, "1") == 0;
}

std::atomic<bool> g_checks{checksFromEnvironment()};

// Error messages from the debug callback since the last checkGl on this thread. The callback
// runs inside the driver (synchronous output), where throwing is not allowed.
thread_local std::string t_debug_errors;

void GLAPIENTRY onDebugMessage(GLenum source, GLenum type, GLuint /*id*/, GLenum severity,
                               GLsizei length, const GLchar* message, const void* /*user*/) {
  // Compile and link errors come back through the shader/program logs (shader_library.h).
  if (source == GL_DEBUG_SOURCE_SHADER_COMPILER || !g_checks) return;
  if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH) return;
  if (!t_debug_errors.empty()) t_debug_errors += "; ";
  if (length < 0) {
    t_debug_errors += message;
  } else {
    t_debug_errors.append(message, static_cast<std::size_t>(length));
  }
}

}  // namespace

void setGlChecks(bool enabled) { g_checks = enabled; }

bool glChecksEnabled() { return g_checks; }

void installGlDebugOutput() {
  t_debug_errors.clear();
  if (glad_glDebugMessageCallback == nullptr) return;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(&onDebugMessage, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

std::string glErrorName(GLenum code) {
  switch (code) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    default: {
      char buffer[16];
      std::snprintf(buffer, sizeof buffer, "0x%04x", code);
      return buffer;
    }
  }
}

void clearGlErrors() {
  for (int i = 0; i < 8 && glGetError() != GL_NO_ERROR; ++i) {
  }
  t_debug_errors.clear();
}

void checkGl(std::string_view what) {
  if (!g_checks) return;
  std::string errors;
  // glGetError returns one flag per call; a broken context can keep returning errors: bound it.
  for (int i = 0; i < 8; ++i) {
    const GLenum code = glGetError();
    if (code == GL_NO_ERROR) break;
    if (!errors.empty()) errors += ", ";
    errors += glErrorName(code);
  }
  if (errors.empty() && t_debug_errors.empty()) return;
  std::string message = "OpenGL error after " + std::string(what) + ": " + (errors.empty() ? "(debug output)" : errors);
  if (!t_debug_errors.empty()) message += " — " + t_debug_errors;
  t_debug_errors.clear();
  throw EnvironmentError(message);
}

// ---- Buffer ---------------------------------------------------------------------------------
Buffer::Buffer() {
  glCreateBuffers(1, &id_);
  checkGl("glCreateBuffers");
}

Buffer::~Buffer() {
  if (id_ != 0) glDeleteBuffers(1, &id_);
}

Buffer::Buffer(Buffer&& other) noexcept
    : id_(std::exchange(other.id_, 0)), size_(std::exchange(other.size_, 0)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteBuffers(1, &id_);
    id_ = std::exchange(other.id_, 0);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

void Buffer::setData(const void* data, std::size_t bytes, GLenum usage) {
  glNamedBufferData(id_, static_cast<GLsizeiptr>(bytes), data, usage);
  size_ = bytes;
  checkGl("glNamedBufferData");
}

void Buffer::setSubData(std::size_t offset, const void* data, std::size_t bytes) {
  glNamedBufferSubData(id_, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
  checkGl("glNamedBufferSubData");
}

// ---- VertexArray ----------------------------------------------------------------------------
VertexArray::VertexArray() {
  glCreateVertexArrays(1, &id_);
  checkGl("glCreateVertexArrays");
}

VertexArray::~VertexArray() {
  if (id_ != 0) glDeleteVertexArrays(1, &id_);
}

VertexArray::VertexArray(VertexArray&& other) noexcept : id_(std::exchange(other.id_, 0)) {}

VertexArray& VertexArray::operator=(VertexArray&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteVertexArrays(1, &id_);
    id_ = std::exchange(other.id_, 0);
  }
  return *this;
}

void VertexArray::setVertexBuffer(GLuint binding, const Buffer& buffer, std::size_t offset, GLsizei stride) {
  glVertexArrayVertexBuffer(id_, binding, buffer.id(), static_cast<GLintptr>(offset), stride);
  checkGl("glVertexArrayVertexBuffer");
}

void VertexArray::setAttribute(GLuint location, GLuint binding, GLint components, GLenum type, bool normalized,
                               GLuint relative_offset) {
  glEnableVertexArrayAttrib(id_, location);
  const bool integer = !normalized && type != GL_FLOAT && type != GL_HALF_FLOAT && type != GL_DOUBLE;
  if (integer) {
    glVertexArrayAttribIFormat(id_, location, components, type, relative_offset);
  } else {
    glVertexArrayAttribFormat(id_, location, components, type, normalized ? GL_TRUE : GL_FALSE, relative_offset);
  }
  glVertexArrayAttribBinding(id_, location, binding);
  checkGl("vertex attribute setup");
}

void VertexArray::setElementBuffer(const Buffer& buffer) {
  glVertexArrayElementBuffer(id_, buffer.id());
  checkGl("glVertexArrayElementBuffer");
}

void VertexArray::bind() const { glBindVertexArray(id_); }

// ---- Texture --------------------------------------------------------------------------------
Texture::~Texture() {
  if (id_ != 0) glDeleteTextures(1, &id_);
}

Texture::Texture(Texture&& other) noexcept
    : id_(std::exchange(other.id_, 0)),
      target_(other.target_),
      internal_format_(other.internal_format_),
      width_(other.width_),
      height_(other.height_),
      depth_(other.depth_) {}

Texture& Texture::operator=(Texture&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteTextures(1, &id_);
    id_ = std::exchange(other.id_, 0);
    target_ = other.target_;
    internal_format_ = other.internal_format_;
    width_ = other.width_;
    height_ = other.height_;
    depth_ = other.depth_;
  }
  return *this;
}

namespace {
bool isDepthFormat(GLenum format) {
  return format == GL_DEPTH_COMPONENT16 || format == GL_DEPTH_COMPONENT24 || format == GL_DEPTH_COMPONENT32F ||
         format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8;
}
}  // namespace

Texture Texture::create2D(GLenum internal_format, int width, int height, int levels) {
  if (width <= 0 || height <= 0) {
    throw EnvironmentError("texture size must be positive (got " + std::to_string(width) + "x" +
                           std::to_string(height) + ")");
  }
  Texture t;
  t.target_ = GL_TEXTURE_2D;
  t.internal_format_ = internal_format;
  t.width_ = width;
  t.height_ = height;
  t.depth_ = 1;
  glCreateTextures(GL_TEXTURE_2D, 1, &t.id_);
  glTextureStorage2D(t.id_, levels, internal_format, width, height);
  checkGl("glTextureStorage2D");
  const GLenum filter = isDepthFormat(internal_format) ? GL_NEAREST : GL_LINEAR;
  t.setFilter(filter, filter);
  t.setWrap(GL_CLAMP_TO_EDGE);
  return t;
}

Texture Texture::create3D(GLenum internal_format, int width, int height, int depth, int levels) {
  if (width <= 0 || height <= 0 || depth <= 0) {
    throw EnvironmentError("3D texture size must be positive (got " + std::to_string(width) + "x" +
                           std::to_string(height) + "x" + std::to_string(depth) + ")");
  }
  Texture t;
  t.target_ = GL_TEXTURE_3D;
  t.internal_format_ = internal_format;
  t.width_ = width;
  t.height_ = height;
  t.depth_ = depth;
  glCreateTextures(GL_TEXTURE_3D, 1, &t.id_);
  glTextureStorage3D(t.id_, levels, internal_format, width, height, depth);
  checkGl("glTextureStorage3D");
  t.setFilter(GL_LINEAR, GL_LINEAR);
  t.setWrap(GL_CLAMP_TO_EDGE);
  return t;
}

void Texture::upload2D(GLenum format, GLenum type, const void* pixels) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(id_, 0, 0, 0, width_, height_, format, type, pixels);
  checkGl("glTextureSubImage2D");
}

void Texture::upload3D(GLenum format, GLenum type, const void* voxels) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage3D(id_, 0, 0, 0, 0, width_, height_, depth_, format, type, voxels);
  checkGl("glTextureSubImage3D");
}

void Texture::setFilter(GLenum min_filter, GLenum mag_filter) {
  glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(min_filter));
  glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(mag_filter));
  checkGl("texture filter");
}

void Texture::setWrap(GLenum wrap) {
  glTextureParameteri(id_, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
  glTextureParameteri(id_, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
  glTextureParameteri(id_, GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap));
  checkGl("texture wrap");
}

void Texture::bind(GLuint unit) const { glBindTextureUnit(unit, id_); }

// ---- Framebuffer ----------------------------------------------------------------------------
Framebuffer::Framebuffer(int width, int height, bool with_depth) : width_(width), height_(height) {
  color_ = Texture::create2D(GL_RGBA8, width, height);
  color_.setFilter(GL_NEAREST, GL_NEAREST);
  glCreateFramebuffers(1, &id_);
  glNamedFramebufferTexture(id_, GL_COLOR_ATTACHMENT0, color_.id(), 0);
  if (with_depth) {
    depth_ = Texture::create2D(GL_DEPTH_COMPONENT24, width, height);
    glNamedFramebufferTexture(id_, GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  }
  checkGl("framebuffer setup");
  checkComplete();
}

Framebuffer::~Framebuffer() {
  if (id_ != 0) glDeleteFramebuffers(1, &id_);
}

Framebuffer::Framebuffer(Framebuffer&& other) noexcept
    : id_(std::exchange(other.id_, 0)),
      width_(other.width_),
      height_(other.height_),
      color_(std::move(other.color_)),
      depth_(std::move(other.depth_)) {}

Framebuffer& Framebuffer::operator=(Framebuffer&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteFramebuffers(1, &id_);
    id_ = std::exchange(other.id_, 0);
    width_ = other.width_;
    height_ = other.height_;
    color_ = std::move(other.color_);
    depth_ = std::move(other.depth_);
  }
  return *this;
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, id_);
  glViewport(0, 0, width_, height_);
}

void Framebuffer::checkComplete() const {
  const GLenum status = glCheckNamedFramebufferStatus(id_, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "0x%04x", status);
    throw EnvironmentError("framebuffer " + std::to_string(width_) + "x" + std::to_string(height_) +
                           " is incomplete (status " + buffer + ")");
  }
}

// ---- Shader ---------------------------------------------------------------------------------
Shader::Shader(GLenum stage) : stage_(stage) {
  id_ = glCreateShader(stage);
  checkGl("glCreateShader");
  if (id_ == 0) throw EnvironmentError("glCreateShader failed (stage 0x" + std::to_string(stage) + ")");
}

Shader::~Shader() {
  if (id_ != 0) glDeleteShader(id_);
}

Shader::Shader(Shader&& other) noexcept : id_(std::exchange(other.id_, 0)), stage_(other.stage_) {}

Shader& Shader::operator=(Shader&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteShader(id_);
    id_ = std::exchange(other.id_, 0);
    stage_ = other.stage_;
  }
  return *this;
}

bool Shader::compile(std::string_view source) {
  const GLchar* text = source.data();
  const auto length = static_cast<GLint>(source.size());
  glShaderSource(id_, 1, &text, &length);
  glCompileShader(id_);
  GLint ok = GL_FALSE;
  glGetShaderiv(id_, GL_COMPILE_STATUS, &ok);
  return ok == GL_TRUE;
}

std::string Shader::infoLog() const {
  GLint length = 0;
  glGetShaderiv(id_, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
  if (length > 0) glGetShaderInfoLog(id_, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

// ---- Program --------------------------------------------------------------------------------
Program::Program() {
  id_ = glCreateProgram();
  checkGl("glCreateProgram");
  if (id_ == 0) throw EnvironmentError("glCreateProgram failed");
}

Program::~Program() {
  if (id_ != 0) glDeleteProgram(id_);
}

Program::Program(Program&& other) noexcept
    : id_(std::exchange(other.id_, 0)), locations_(std::move(other.locations_)) {}

Program& Program::operator=(Program&& other) noexcept {
  if (this != &other) {
    if (id_ != 0) glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
    locations_ = std::move(other.locations_);
  }
  return *this;
}

void Program::attach(const Shader& shader) {
  glAttachShader(id_, shader.id());
  checkGl("glAttachShader");
}

bool Program::link() {
  glLinkProgram(id_);
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  locations_.clear();
  return ok == GL_TRUE;
}

std::string Program::infoLog() const {
  GLint length = 0;
  glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
  if (length > 0) glGetProgramInfoLog(id_, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

void Program::use() const { glUseProgram(id_); }

GLint Program::uniformLocation(const std::string& name) const {
  const auto found = locations_.find(name);
  if (found != locations_.end()) return found->second;
  const GLint location = glGetUniformLocation(id_, name.c_str());
  locations_.emplace(name, location);
  return location;
}

void Program::setUniform(const std::string& name, int value) const {
  glProgramUniform1i(id_, uniformLocation(name), value);
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, float value) const {
  glProgramUniform1f(id_, uniformLocation(name), value);
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, double value) const {
  glProgramUniform1d(id_, uniformLocation(name), value);
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, const glm::vec2& value) const {
  glProgramUniform2fv(id_, uniformLocation(name), 1, glm::value_ptr(value));
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, const glm::vec3& value) const {
  glProgramUniform3fv(id_, uniformLocation(name), 1, glm::value_ptr(value));
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, const glm::vec4& value) const {
  glProgramUniform4fv(id_, uniformLocation(name), 1, glm::value_ptr(value));
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, const glm::ivec2& value) const {
  glProgramUniform2iv(id_, uniformLocation(name), 1, glm::value_ptr(value));
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, const glm::ivec3& value) const {
  glProgramUniform3iv(id_, uniformLocation(name), 1, glm::value_ptr(value));
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, const glm::mat3& value) const {
  glProgramUniformMatrix3fv(id_, uniformLocation(name), 1, GL_FALSE, glm::value_ptr(value));
  checkGl("uniform " + name);
}
void Program::setUniform(const std::string& name, const glm::mat4& value) const {
  glProgramUniformMatrix4fv(id_, uniformLocation(name), 1, GL_FALSE, glm::value_ptr(value));
  checkGl("uniform " + name);
}

}  // namespace hermite::render

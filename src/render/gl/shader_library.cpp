#include "render/gl/shader_library.h"

#include <algorithm>
#include <regex>
#include <sstream>

#include "core/base/errors.h"

namespace hermite::render {

namespace {

const detail::EmbeddedShader* findEmbedded(std::string_view file) {
  for (std::size_t i = 0; i < detail::kEmbeddedShaderCount; ++i) {
    if (file == detail::kEmbeddedShaders[i].name) return &detail::kEmbeddedShaders[i];
  }
  return nullptr;
}

std::string_view trimLeft(std::string_view s) {
  const std::size_t start = s.find_first_not_of(" \t\r");
  return start == std::string_view::npos ? std::string_view{} : s.substr(start);
}

// Expands the source into `out` with `#line` directives; `files` collects source-string numbers.
struct Preprocessor {
  std::vector<std::string> files;
  std::string out;

  void expand(std::string_view source, const std::string& file, int depth, bool top_level) {
    if (depth > 16) throw EnvironmentError(file + ": #include nested more than 16 levels (a cycle?)");
    const int number = static_cast<int>(files.size());
    files.push_back(file);
    int line_number = 0;
    if (!top_level) {
      out += "#line 1 " + std::to_string(number) + "\n";
    } else if (!trimLeft(source).starts_with("#version")) {
      // The prelude, then the file from its line 1.
      out += "#version 450 core\n#line 1 " + std::to_string(number) + "\n";
    }
    std::size_t position = 0;
    while (position <= source.size()) {
      std::size_t end = source.find('\n', position);
      if (end == std::string_view::npos) end = source.size();
      const std::string_view line = source.substr(position, end - position);
      ++line_number;
      const std::string_view directive = trimLeft(line);
      if (directive.starts_with("#version")) {
        if (!top_level) throw EnvironmentError(file + ":" + std::to_string(line_number) + ": #version in an included file");
        out.append(line).append("\n");
        out += "#line " + std::to_string(line_number + 1) + " " + std::to_string(number) + "\n";
      } else if (directive.starts_with("#include")) {
        const std::size_t open = directive.find('"');
        const std::size_t close = open == std::string_view::npos ? open : directive.find('"', open + 1);
        if (close == std::string_view::npos) {
          throw EnvironmentError(file + ":" + std::to_string(line_number) + ": malformed #include (expected #include \"name\")");
        }
        const std::string name(directive.substr(open + 1, close - open - 1));
        const detail::EmbeddedShader* included = findEmbedded(name);
        if (included == nullptr) {
          throw EnvironmentError(file + ":" + std::to_string(line_number) + ": #include \"" + name +
                                 "\": no such embedded shader");
        }
        expand(std::string_view(included->data, included->size), name, depth + 1, false);
        out += "#line " + std::to_string(line_number + 1) + " " + std::to_string(number) + "\n";
      } else {
        out.append(line).append("\n");
      }
      position = end + 1;
    }
  }
};

std::string firstErrorLine(const std::string& log) {
  std::istringstream lines(log);
  std::string line;
  std::string first;
  while (std::getline(lines, line)) {
    if (first.empty() && !line.empty()) first = line;
    if (line.find("error") != std::string::npos || line.find("ERROR") != std::string::npos) return line;
  }
  return first;
}

}  // namespace

std::vector<std::string> shaderNames() {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < detail::kEmbeddedShaderCount; ++i) names.emplace_back(detail::kEmbeddedShaders[i].name);
  std::sort(names.begin(), names.end());
  return names;
}

bool hasShader(std::string_view file) { return findEmbedded(file) != nullptr; }

std::string_view shaderSource(std::string_view file) {
  const detail::EmbeddedShader* shader = findEmbedded(file);
  if (shader == nullptr) {
    std::string known;
    for (const std::string& name : shaderNames()) known += (known.empty() ? "" : ", ") + name;
    throw EnvironmentError("no embedded shader '" + std::string(file) + "' (embedded: " + known + ")");
  }
  return {shader->data, shader->size};
}

GLenum shaderStageFor(std::string_view file) {
  if (file.ends_with(".vert")) return GL_VERTEX_SHADER;
  if (file.ends_with(".frag")) return GL_FRAGMENT_SHADER;
  if (file.ends_with(".geom")) return GL_GEOMETRY_SHADER;
  if (file.ends_with(".comp")) return GL_COMPUTE_SHADER;
  if (file.ends_with(".tesc")) return GL_TESS_CONTROL_SHADER;
  if (file.ends_with(".tese")) return GL_TESS_EVALUATION_SHADER;
  throw EnvironmentError("cannot tell the shader stage of '" + std::string(file) +
                         "' (expected .vert, .frag, .geom, .comp, .tesc or .tese)");
}

std::string translateShaderLog(std::string_view log, const std::vector<std::string>& files) {
  // Mesa "0:12(3): error: ...", NVIDIA "0(12) : error C1008: ...", AMD/Intel "ERROR: 0:12: ...".
  static const std::regex mesa(R"(^\s*(\d+):(\d+)\((\d+)\):\s*(.*)$)");
  static const std::regex nvidia(R"(^\s*(\d+)\((\d+)\)\s*:\s*(.*)$)");
  static const std::regex generic(R"(^\s*(ERROR|WARNING):\s*(\d+):(\d+):\s*(.*)$)");
  auto fileOf = [&](const std::string& number) {
    const std::size_t index = std::stoul(number);
    return index < files.size() ? files[index] : "<source " + number + ">";
  };
  std::string result;
  std::istringstream lines{std::string(log)};
  std::string line;
  std::smatch m;
  while (std::getline(lines, line)) {
    if (!result.empty()) result += "\n";
    if (std::regex_match(line, m, mesa)) {
      result += fileOf(m[1]) + ":" + m[2].str() + ":" + m[3].str() + ": " + m[4].str();
    } else if (std::regex_match(line, m, nvidia)) {
      result += fileOf(m[1]) + ":" + m[2].str() + ": " + m[3].str();
    } else if (std::regex_match(line, m, generic)) {
      std::string kind = m[1].str();
      std::transform(kind.begin(), kind.end(), kind.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      result += fileOf(m[2]) + ":" + m[3].str() + ": " + kind + ": " + m[4].str();
    } else {
      result += line;
    }
  }
  return result;
}

Shader compileShader(const ShaderSource& source) {
  Preprocessor pre;
  pre.expand(source.source, source.file, 0, true);
  Shader shader(source.stage);
  if (!shader.compile(pre.out)) {
    const std::string log = translateShaderLog(shader.infoLog(), pre.files);
    throw EnvironmentError("shader compile error: " + firstErrorLine(log) + "\n" + log);
  }
  checkGl("compiling " + source.file);
  return shader;
}

Program buildProgram(const std::vector<ShaderSource>& sources) {
  std::vector<Shader> shaders;
  shaders.reserve(sources.size());
  for (const ShaderSource& source : sources) shaders.push_back(compileShader(source));
  Program program;
  for (const Shader& shader : shaders) program.attach(shader);
  if (!program.link()) {
    std::string names;
    for (const ShaderSource& source : sources) names += (names.empty() ? "" : " + ") + source.file;
    throw EnvironmentError("shader link error (" + names + "): " + program.infoLog());
  }
  for (const Shader& shader : shaders) glDetachShader(program.id(), shader.id());
  checkGl("linking a program");
  return program;
}

Program buildProgram(std::initializer_list<std::string_view> files) {
  std::vector<ShaderSource> sources;
  for (std::string_view file : files) {
    sources.push_back({shaderStageFor(file), std::string(shaderSource(file)), std::string(file)});
  }
  return buildProgram(sources);
}

}  // namespace hermite::render

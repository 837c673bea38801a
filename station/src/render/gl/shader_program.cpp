#include "render/gl/shader_program.h"

#include <utility>

#include <glm/gtc/type_ptr.hpp>

namespace sculpt::station::gl {
namespace {

std::string log_of(GLuint id, bool program) {
  GLint n = 0;
  program ? glGetProgramiv(id, GL_INFO_LOG_LENGTH, &n) : glGetShaderiv(id, GL_INFO_LOG_LENGTH, &n);
  std::string log(static_cast<size_t>(std::max(n, 1)), '\0');
  program ? glGetProgramInfoLog(id, n, nullptr, log.data())
          : glGetShaderInfoLog(id, n, nullptr, log.data());
  return log;
}

GLuint compile(GLenum kind, const char* source) {
  const GLuint s = glCreateShader(kind);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  return s;
}

}  // namespace

Result<ShaderProgram> ShaderProgram::build(const char* vertex, const char* fragment,
                                           const std::string& name) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment);
  for (GLuint s : {vs, fs}) {
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      const std::string log = log_of(s, false);
      glDeleteShader(vs);
      glDeleteShader(fs);
      return Error("shader " + name + " does not compile: " + log);
    }
  }
  ShaderProgram p;
  p.id_ = glCreateProgram();
  glAttachShader(p.id_, vs);
  glAttachShader(p.id_, fs);
  glLinkProgram(p.id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(p.id_, GL_LINK_STATUS, &ok);
  if (!ok) return Error("shader " + name + " does not link: " + log_of(p.id_, true));
  return p;
}

ShaderProgram::~ShaderProgram() {
  if (id_ != 0) glDeleteProgram(id_);
}
ShaderProgram::ShaderProgram(ShaderProgram&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
ShaderProgram& ShaderProgram::operator=(ShaderProgram&& o) noexcept {
  if (this != &o) {
    if (id_ != 0) glDeleteProgram(id_);
    id_ = std::exchange(o.id_, 0);
  }
  return *this;
}

void ShaderProgram::set(const char* name, const glm::mat4& m) const {
  glUniformMatrix4fv(glGetUniformLocation(id_, name), 1, GL_FALSE, glm::value_ptr(m));
}
void ShaderProgram::set(const char* name, glm::vec3 v) const {
  glUniform3f(glGetUniformLocation(id_, name), v.x, v.y, v.z);
}
void ShaderProgram::set(const char* name, glm::vec4 v) const {
  glUniform4f(glGetUniformLocation(id_, name), v.x, v.y, v.z, v.w);
}
void ShaderProgram::set(const char* name, float v) const {
  glUniform1f(glGetUniformLocation(id_, name), v);
}

}  // namespace sculpt::station::gl

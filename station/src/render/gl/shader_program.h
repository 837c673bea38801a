#pragma once
// A linked GLSL program with its uniforms looked up by name.

#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/gl/gl_api.h"
#include "sculpt/base/result.h"

namespace sculpt::station::gl {

class ShaderProgram {
 public:
  /// Compiles and links; the error carries the driver's log.
  static Result<ShaderProgram> build(const char* vertex, const char* fragment,
                                     const std::string& name);
  ShaderProgram() = default;
  ~ShaderProgram();
  ShaderProgram(ShaderProgram&& other) noexcept;
  ShaderProgram& operator=(ShaderProgram&& other) noexcept;
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  void use() const { glUseProgram(id_); }
  void set(const char* name, const glm::mat4& m) const;
  void set(const char* name, glm::vec3 v) const;
  void set(const char* name, glm::vec4 v) const;
  void set(const char* name, float v) const;

 private:
  GLuint id_ = 0;
};

}  // namespace sculpt::station::gl

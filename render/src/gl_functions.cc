#include "gl_functions.h"

#include <stdexcept>

namespace idbench::render_internal {

GlFunctions LoadGlFunctions(GlProcLoader loader) {
  if (loader == nullptr) throw std::runtime_error("OpenGL: no function loader given");
  GlFunctions gl;
#define IDBENCH_GL_LOAD(type, name)                                                      \
  gl.name = reinterpret_cast<type>(loader("gl" #name));                                  \
  if (gl.name == nullptr) throw std::runtime_error("OpenGL: the context does not provide gl" #name);
  IDBENCH_GL_FUNCTIONS(IDBENCH_GL_LOAD)
#undef IDBENCH_GL_LOAD
  return gl;
}

}  // namespace idbench::render_internal

// A headless OpenGL 3.3 core context (Mesa's OSMesa, software rendering by
// llvmpipe), current on the calling thread while the object lives. The
// renderer draws into its own framebuffer object, so the context's own
// buffer is a 1×1 placeholder. The only file that includes OSMesa.
#pragma once

#include "idbench/render/gl_proc_loader.h"

namespace idbench {

class OsMesaContext {
 public:
  // Creates the context and makes it current. Throws std::runtime_error when
  // OSMesa cannot create a 3.3 core context.
  OsMesaContext();
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  // OSMesaGetProcAddress, for the renderer.
  static GlProcLoader loader();

 private:
  void* context_ = nullptr;  // OSMesaContext
  unsigned char buffer_[4] = {};  // the 1×1 RGBA default framebuffer
};

}  // namespace idbench

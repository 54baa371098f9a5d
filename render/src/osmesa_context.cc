#include "idbench/render/osmesa_context.h"

#include <GL/osmesa.h>

#include <stdexcept>

namespace idbench {
namespace {

void* GetProcAddress(const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); }

}  // namespace

OsMesaContext::OsMesaContext() {
  const int attributes[] = {OSMESA_FORMAT,       OSMESA_RGBA,         OSMESA_DEPTH_BITS,
                            0,                   OSMESA_PROFILE,      OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3,          OSMESA_CONTEXT_MINOR_VERSION,
                            3,                   0};
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (context == nullptr) throw std::runtime_error("OSMesa: cannot create an OpenGL 3.3 core context");
  if (!OSMesaMakeCurrent(context, buffer_, GL_UNSIGNED_BYTE, 1, 1)) {
    OSMesaDestroyContext(context);
    throw std::runtime_error("OSMesa: cannot make the OpenGL context current");
  }
  context_ = context;
}

OsMesaContext::~OsMesaContext() { OSMesaDestroyContext(static_cast<OSMesaContext>(context_)); }

GlProcLoader OsMesaContext::loader() { return &GetProcAddress; }

}  // namespace idbench

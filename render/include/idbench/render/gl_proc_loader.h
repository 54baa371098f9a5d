// How the renderer finds OpenGL: a function returning the address of a GL
// entry point by name, or null. OSMesaGetProcAddress headless (see
// osmesa_context.h), glfwGetProcAddress in a window.
#pragma once

namespace idbench {

using GlProcLoader = void* (*)(const char* name);

}  // namespace idbench

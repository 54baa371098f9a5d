// The version of idbench and the git revision the binaries were built from
// (`idbench --version`, Python's idbench.__version__).
#pragma once

namespace idbench {

// "0.1.0": the project's version (CMakeLists.txt).
const char* Version();
// `git describe --always --dirty` of the source tree at build time, e.g.
// "6a69499abcde-dirty"; "unknown" when built outside a git checkout.
const char* GitRevision();

}  // namespace idbench

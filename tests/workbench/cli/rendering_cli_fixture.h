// CliFixture for commands that render (OSMesa): one llvmpipe thread per
// process, as ctest runs tests in parallel.
#pragma once

#include <cstdlib>

#include "workbench/cli/cli_fixture.h"

namespace idbench::testing {

class RenderingCliFixture : public CliFixture {
 protected:
  void SetUp() override {
    CliFixture::SetUp();
    setenv("LP_NUM_THREADS", "1", 1);  // inherited by the idbench processes
  }
};

}  // namespace idbench::testing

// The experiments' main() under the project's error policy (src/gvdp/base/error.h): run(argc,
// argv); bad input (a gvdp::InputError) is a one-line message and exit status 2, any other
// exception a one-line message and exit status 1.
#pragma once

#include <cstdio>
#include <exception>

#include "gvdp/base/error.h"

namespace gvdp::detail {

template <class Run>
int experimentMain(const char* program, Run run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace gvdp::detail

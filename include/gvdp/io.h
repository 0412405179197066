// Image files for a program using gvdp: PNG in and out.
#pragma once

#include "gvdp/io/png.h"
#include "gvdp/renderer.h"

namespace gvdp {

using detail::readPng;
using detail::writePng;

}  // namespace gvdp

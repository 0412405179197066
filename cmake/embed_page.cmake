# Writes OUT, a C++ file defining gvdp::detail::viewerPage() as the text of IN (the viewer's
# page), so that `gvdp serve` reads no file at run time.
file(READ ${IN} page)
string(FIND "${page}" ")GVDP_PAGE\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} holds the raw string's delimiter")
endif()
file(WRITE ${OUT}.tmp "// Generated from ${IN} by cmake/embed_page.cmake.
#include \"gvdp/serve/server.h\"

namespace gvdp::detail {

const std::string& viewerPage() {
  static const std::string page = R\"GVDP_PAGE(${page})GVDP_PAGE\";
  return page;
}

}  // namespace gvdp::detail
")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)

// One error policy (docs/STYLE.md 8): host code throws, carrying file:line and the bad value; only
// main() turns an exception into a message and an exit status. InputError is the user's fault
// (unknown scene, bad size, missing file) and exits with status 2.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace gvdp {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class InputError : public Error {
 public:
  using Error::Error;
};

namespace detail {
template <class... Args>
std::string concat(const Args&... args) {
  std::ostringstream s;
  (s << ... << args);
  return s.str();
}
}  // namespace detail

}  // namespace gvdp

// Internal invariant: throws gvdp::Error with the location.
#define GVDP_CHECK(cond, ...)                                                                     \
  do {                                                                                            \
    if (!(cond))                                                                                  \
      throw ::gvdp::Error(::gvdp::detail::concat(__FILE__, ":", __LINE__,                         \
                                                 ": check '" #cond "' failed: ", ##__VA_ARGS__)); \
  } while (0)

// Bad user input: throws gvdp::InputError with a one-line message.
#define GVDP_INPUT_CHECK(cond, ...)                                             \
  do {                                                                          \
    if (!(cond)) throw ::gvdp::InputError(::gvdp::detail::concat(__VA_ARGS__)); \
  } while (0)

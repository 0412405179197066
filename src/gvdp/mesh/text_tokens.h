// Small text helpers for the mesh readers: lines, whitespace-separated tokens, whole-token
// number parsing (a token that is not entirely a number is refused, never half read).
#pragma once

#include <charconv>
#include <cstdint>
#include <string_view>
#include <vector>

namespace gvdp::detail {

// Splits at spaces, tabs and carriage returns; `comment` (0: none) ends the line.
inline void splitTokens(std::string_view line, std::vector<std::string_view>& out,
                        char comment = '#') {
  out.clear();
  size_t i = 0;
  while (i < line.size()) {
    char c = line[i];
    if (c == comment && comment != 0) break;
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r' &&
           line[j] != '\f' && line[j] != '\v' && !(line[j] == comment && comment != 0))
      ++j;
    out.push_back(line.substr(i, j - i));
    i = j;
  }
}

// The next line of `text` from `pos` (without its '\n'); false at the end.
inline bool nextLine(std::string_view text, size_t& pos, std::string_view& line) {
  if (pos >= text.size()) return false;
  size_t end = text.find('\n', pos);
  if (end == std::string_view::npos) end = text.size();
  line = text.substr(pos, end - pos);
  pos = end + 1;
  return true;
}

// A float (NaN and infinities parse: the caller's validation names them).
inline bool parseFloat(std::string_view s, float& v) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  double d = 0.0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), d);
  if (end != s.data() + s.size() || s.empty()) return false;
  if (ec == std::errc::result_out_of_range) {  // underflow reads as zero, overflow as infinity
    size_t e = s.find_first_of("eE");
    bool tiny = e != std::string_view::npos && e + 1 < s.size() && s[e + 1] == '-';
    d = tiny ? 0.0 : 1e300;
    if (s[0] == '-') d = -d;
  }
  v = static_cast<float>(d);
  return ec == std::errc() || ec == std::errc::result_out_of_range;
}

inline bool parseInt(std::string_view s, int64_t& v) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size() && !s.empty();
}

}  // namespace gvdp::detail

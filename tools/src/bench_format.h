// A number printed with a printf format, for the bench tables of tools/.
#pragma once

#include <cstdio>
#include <string>

namespace reeve {

inline std::string fixed(double v, const char* format) {
  char text[32];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

}  // namespace reeve

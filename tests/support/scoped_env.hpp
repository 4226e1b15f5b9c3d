#pragma once
// setenv for the lifetime of a scope.
#include <cstdlib>
#include <string>

namespace ssrcl::test {

struct ScopedEnv {
  std::string name;
  ScopedEnv(const char* n, const char* value) : name(n) { setenv(n, value, 1); }
  ~ScopedEnv() { unsetenv(name.c_str()); }
};

}  // namespace ssrcl::test

// Helpers shared by the GoogleTest suites (tests/test_*.cpp).
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "bouncer/model/spec.hpp"

namespace bouncer::test_support {

// The validated model of law `law` with the triangle wall, from exact decimal texts: gravity
// a, restitution eps (read for Law::constant only) and c (Law::veldep's constant). Throws
// InputError as the command line would.
inline ModelSpec spec(Law law, const std::string& a, const std::string& eps = "1", const std::string& c = "1000") {
  ModelSpec m;
  m.law = law;
  m.a = parse_decimal("a", a);
  if (law == Law::constant) m.eps = parse_decimal("eps", eps);
  m.c = parse_decimal("c", c);
  m.wall = parse_wall("wall", "triangle");
  validate(m);
  return m;
}

// A fresh private directory under the system's temporary one (mkdtemp, mode 0700), removed
// with everything in it when the object goes; `dir / "name"` is a path inside it.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& prefix = "bouncer-test") {
    std::string t = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    path = ::mkdtemp(t.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  long entries() const {
    return std::distance(std::filesystem::directory_iterator(path), std::filesystem::directory_iterator());
  }
};

// A file's bytes; a file written with `text` (returns its path).
inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}
inline std::string put(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A body for the writers of base/output.hpp that writes `t`.
inline auto text(const std::string& t) {
  return [t](std::ostream& s) { s << t; };
}

inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Runs f and expects an InputError naming `field`, whose message starts with the field's name
// (so that a user sees which input is wrong); returns the message.
template <class F>
std::string expect_input_error(F&& f, const std::string& field) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, field) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(field + ": ", 0), 0u) << e.what();
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError(" << field << "), got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError(" << field << "), nothing was thrown";
  return {};
}

}  // namespace bouncer::test_support

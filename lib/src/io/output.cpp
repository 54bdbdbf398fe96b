// Output files (io/output.hpp).
#include "bouncer/io/output.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "bouncer/model/spec.hpp"

namespace bouncer {

namespace fs = std::filesystem;

OutputTarget output_target(const std::string& field, const std::string& path) {
  if (path.empty()) throw InputError(field, "is empty (give a file path)");
  if (path.back() == '/') throw InputError(field, "'" + path + "' ends in '/': give a file path, not a directory");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT) {  // a new file: its folder must exist (a missing one is a typo, not a full disk)
      const fs::path parent = fs::path(path).parent_path();
      std::error_code ec;
      if (!parent.empty() && !fs::is_directory(parent, ec))
        throw InputError(field, "folder '" + parent.string() + "' does not exist (for '" + path + "')");
      return {OutputTarget::Kind::file, path};
    }
    throw InputError(field, "cannot use '" + path + "': " + std::strerror(errno));
  }
  if (S_ISREG(st.st_mode)) {
    std::error_code ec;
    const fs::path real = fs::canonical(path, ec);  // write the link's target, keep the link
    return {OutputTarget::Kind::file, ec ? path : real.string()};
  }
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return {OutputTarget::Kind::stream, path};
  const char* what = S_ISDIR(st.st_mode) ? "a directory" : S_ISSOCK(st.st_mode) ? "a socket" : "a block device or special file";
  throw InputError(field, "'" + path + "' is " + what + ": give a regular file (or a character device or pipe to write through)");
}

void write_output(const OutputTarget& target, const std::function<void(std::ostream&)>& body) {
  if (target.kind == OutputTarget::Kind::stream) {
    std::ofstream f(target.path, std::ios::binary);
    if (!f) throw OutputError("cannot open '" + target.path + "' for writing: " + std::strerror(errno));
    body(f);
    f.flush();
    if (!f) throw OutputError("writing '" + target.path + "' failed");
    f.close();
    if (!f) throw OutputError("closing '" + target.path + "' failed");
    return;
  }
  const std::string tmp = target.path + ".partial";
  try {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw OutputError("cannot write '" + target.path + "': " + std::strerror(errno));
    body(f);
    f.flush();
    if (!f) throw OutputError("writing '" + target.path + "' failed (disk full?)");
    f.close();
    if (!f) throw OutputError("closing '" + target.path + "' failed (disk full?)");
    std::error_code ec;
    fs::rename(tmp, target.path, ec);
    if (ec) throw OutputError("cannot rename '" + tmp + "' to '" + target.path + "': " + ec.message());
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void check_stdout() {
  std::cout.flush();
  if (!std::cout) throw OutputError("writing to standard output failed");
  if (std::fflush(stdout) != 0) throw OutputError(std::string("writing to standard output failed: ") + std::strerror(errno));
}

}  // namespace bouncer

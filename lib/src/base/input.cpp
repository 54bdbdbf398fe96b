// Reading untrusted files (base/input.hpp).
#include "bouncer/base/input.hpp"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "bouncer/base/error.hpp"

namespace bouncer {

namespace {

std::string size_text(std::size_t bytes) {
  if (bytes >= (std::size_t{1} << 30) && bytes % (std::size_t{1} << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (std::size_t{1} << 20) && bytes % (std::size_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

const char* kind_of(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a named pipe (FIFO)";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

// Opens without blocking (a FIFO with no writer would block a plain open) and without
// becoming the controlling terminal; -1 with errno on failure.
int open_for_reading(const std::string& path) {
  int fd;
  do fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  while (fd < 0 && errno == EINTR);
  return fd;
}

std::optional<std::string> read_file(const std::string& field, const std::string& path, std::size_t max_bytes,
                                     bool missing_ok) {
  if (path.empty()) throw InputError(field, "is empty (give a file path)");
  check_path_name(field, path);
  const int fd = open_for_reading(path);
  if (fd < 0) {
    if (errno == ENOENT && missing_ok) return std::nullopt;
    if (errno == ENOENT) throw InputError(field, "'" + path + "' not found");
    throw InputError(field, "cannot read '" + path + "': " + std::strerror(errno));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw InputError(field, "cannot read '" + path + "': " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw InputError(field, "'" + path + "' is " + kind_of(st.st_mode) + ", not a regular file");
  if (static_cast<unsigned long long>(st.st_size) > max_bytes)
    throw InputError(field, "'" + path + "' is larger than " + size_text(max_bytes) + " (" + std::to_string(st.st_size) +
                                " bytes)");
  std::string text;
  text.reserve(static_cast<std::size_t>(st.st_size));
  std::vector<char> buf(1 << 16);
  for (;;) {
    const ssize_t n = ::read(fd, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(field, "cannot read '" + path + "': " + std::strerror(errno));
    if (n == 0) break;
    text.append(buf.data(), static_cast<std::size_t>(n));
    // A file that grows while it is read (a log being written) is bounded too.
    if (text.size() > max_bytes) throw InputError(field, "'" + path + "' is larger than " + size_text(max_bytes));
  }
  return text;
}

}  // namespace

void check_path_name(const std::string& field, const std::string& path, std::size_t suffix_room) {
  if (path.find('\0') != std::string::npos) throw InputError(field, "contains a NUL byte");
  if (path.size() + suffix_room >= PATH_MAX)
    throw InputError(field, "the path is longer than " + std::to_string(PATH_MAX - 1 - suffix_room) + " bytes");
  for (std::size_t start = 0; start < path.size();) {
    std::size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    const std::size_t len = end - start + (end == path.size() ? suffix_room : 0);
    if (len > NAME_MAX)
      throw InputError(field, "a name in '" + path.substr(0, 60) + (path.size() > 60 ? "..." : "") + "' is longer than " +
                                  std::to_string(NAME_MAX - suffix_room) + " bytes (the file system's limit is " +
                                  std::to_string(NAME_MAX) + ")");
    start = end + 1;
  }
}

std::string read_input_file(const std::string& field, const std::string& path, std::size_t max_bytes) {
  return *read_file(field, path, max_bytes, false);
}

std::optional<std::string> read_input_file_if_present(const std::string& field, const std::string& path,
                                                      std::size_t max_bytes) {
  return read_file(field, path, max_bytes, true);
}

// The shape check is a small lexer of TOML's structure, not a parser: it skips strings (basic,
// literal, multi-line) and comments, and follows the brackets. Outside strings, a '.' in a key
// (before '=' on a key line, in a [table.header], or in a key of an inline table) is one more
// level of tables; '[' and '{' of values are one more level each. What it accepts, toml++ then
// parses in full (and rejects what is not TOML); what it rejects is deeper than any bouncer
// file, which keeps toml++'s recursive descent (and its destructor) well within the stack.
void check_toml_text(const std::string& field, const std::string& text, const std::string& source, std::size_t max_bytes) {
  if (text.size() > max_bytes)
    throw InputError(field, source + ": larger than " + size_text(max_bytes) + " (" + std::to_string(text.size()) + " bytes)");
  long line = 1;
  auto fail = [&](const std::string& what) {
    throw InputError(field, source + " line " + std::to_string(line) + ": " + what);
  };
  if (const auto nul = text.find('\0'); nul != std::string::npos) {
    for (std::size_t i = 0; i < nul; ++i) line += text[i] == '\n';
    fail("contains a NUL byte");
  }
  enum class Open : char { header, array, table };
  std::vector<Open> open;  // the brackets not yet closed
  std::vector<int> outer;  // per open bracket: the dotted parts of the key it is the value of
  int outer_dots = 0;      // their sum
  bool key = true;         // in a key (dots nest tables) rather than a value
  bool line_start = true;  // only blanks so far on this line
  int dots = 0;            // dotted parts of the current key
  int header_dots = 0;     // of the current [table.header]: the keys below nest under it
  const std::size_t n = text.size();
  auto depth_check = [&] {
    const int depth = static_cast<int>(open.size()) + outer_dots + dots + header_dots;
    if (depth > kMaxTomlDepth)
      fail("tables or arrays nested more than " + std::to_string(kMaxTomlDepth) + " deep (dotted keys count)");
  };
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      if (open.empty() || open.back() == Open::header) {
        open.clear();
        outer.clear();
        outer_dots = 0;
        key = true;
        dots = 0;
      }
      line_start = true;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') continue;
    const bool was_line_start = line_start;
    line_start = false;
    if (c == '#') {
      while (i + 1 < n && text[i + 1] != '\n') ++i;
      continue;
    }
    if (c == '"' || c == '\'') {
      const bool multi = i + 2 < n && text[i + 1] == c && text[i + 2] == c;
      if (multi) {
        const std::string close(3, c);
        std::size_t j = i + 3;
        for (;;) {
          if (j >= n) fail("a multi-line string is never closed");
          if (c == '"' && text[j] == '\\') {
            if (j + 1 < n && text[j + 1] == '\n') ++line;
            j += 2;
            continue;
          }
          if (text[j] == '\n') ++line;
          if (text.compare(j, 3, close) == 0) break;
          ++j;
        }
        // Up to two more quotes may end the string itself ("""a""""" is a"").
        for (int extra = 0; extra < 2 && j + 3 < n && text[j + 3] == c; ++extra) ++j;
        i = j + 2;
      } else {
        std::size_t j = i + 1;
        for (;;) {
          if (j >= n || text[j] == '\n') fail("a string is never closed on its line");
          if (c == '"' && text[j] == '\\') {
            j += 2;
            continue;
          }
          if (text[j] == c) break;
          ++j;
        }
        i = j;
      }
      continue;
    }
    switch (c) {
      case '[':
        if (was_line_start && open.empty()) {  // [table] or [[array.of.tables]]
          if (i + 1 < n && text[i + 1] == '[') ++i;
          open.push_back(Open::header);
          outer.push_back(0);
          header_dots = 0;
          dots = 0;
          key = true;
        } else {
          open.push_back(Open::array);
          outer.push_back(dots);
          outer_dots += dots;
          dots = 0;
          key = false;
        }
        depth_check();
        break;
      case ']':
        if (!open.empty()) {
          const Open was = open.back();
          open.pop_back();
          outer_dots -= outer.back();
          outer.pop_back();
          if (was == Open::header) {
            if (i + 1 < n && text[i + 1] == ']') ++i;
            header_dots = dots;  // the keys below the header nest under its tables
            dots = 0;
            key = false;         // (only a comment may follow on this line)
          }
        }
        break;
      case '{':
        open.push_back(Open::table);
        outer.push_back(dots);
        outer_dots += dots;
        key = true;
        dots = 0;
        depth_check();
        break;
      case '}':
        if (!open.empty()) {
          open.pop_back();
          outer_dots -= outer.back();
          outer.pop_back();
        }
        key = false;
        dots = 0;
        break;
      case '=':
        key = false;
        break;
      case ',':
        if (!open.empty() && open.back() == Open::table) {
          key = true;
          dots = 0;
        }
        break;
      case '.':
        if (key) {
          ++dots;
          depth_check();
        }
        break;
      default:
        break;
    }
  }
}

bool safe_name(const std::string& s) {
  if (s.empty() || s.size() > 100 || s.find("..") != std::string::npos || s[0] == '.' || s[0] == '-') return false;
  return s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._:+-") == std::string::npos;
}

std::string one_line(const std::string& s, std::size_t limit) {
  std::string out;
  for (unsigned char c : s) {
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c < 0x20 || c == 0x7f) {
      const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  if (out.size() > limit) out = out.substr(0, limit - 60) + " ... [" + std::to_string(out.size() - limit + 40) + " characters cut] ... " + out.substr(out.size() - 20);
  return out;
}

}  // namespace bouncer

// Reading files that bouncer did not write in this run, and so may not trust: scenes,
// manifests, job files, tiles, result files given to `audit`. A file from a stranger can be
// anything: a FIFO whose writer never comes, a device that never ends, a symlink to one, a
// gigabyte of text, a TOML file whose 40,000 nested dotted keys overflow the parser's stack.
// Everything read goes through these functions, which bound what they accept and reject the
// rest with bouncer's one-line InputError (exit status 2) naming the field.
//
// Reading never runs anything a file names and never writes anywhere it names: that is the
// callers' side of the contract (README, "Security").
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace bouncer {

// Size limits of the inputs bouncer reads.
inline constexpr std::size_t kMaxSceneBytes = std::size_t{1} << 20;      // a scene, a job.toml
inline constexpr std::size_t kMaxManifestBytes = std::size_t{4} << 20;   // a reproduce manifest
inline constexpr std::size_t kMaxResultBytes = std::size_t{1} << 30;     // a result file given to audit
// TOML shape limits: tables nested (headers, dotted keys, inline tables, arrays) at most this
// deep. bouncer's own files nest at most 3 deep.
inline constexpr int kMaxTomlDepth = 32;

// Checks that the file system can name `path` (plus `suffix_room` bytes added to its last
// component, e.g. ".partial"): no NUL byte, at most PATH_MAX - 1 bytes, no component longer
// than NAME_MAX. Throws InputError(field, ...), so that a name too long is bad input found
// at once, not an "internal error" or an output failure after the work.
void check_path_name(const std::string& field, const std::string& path, std::size_t suffix_room = 0);

// A name from a file bouncer did not write (a manifest's ids and labels, a claims.json's
// file names) that becomes a file name: letters, digits and . _ : + - only, not starting
// with '.' or '-', no "..", at most 100 characters. No '/', so it names nothing outside the
// directory it is put in.
bool safe_name(const std::string& s);

// A value from such a file (or from a command line) echoed in a one-line message: control
// characters escaped (\n, \t, \xNN), at most `limit` characters (a 100,000-character value
// becomes its start and end).
std::string one_line(const std::string& s, std::size_t limit = 400);

// The whole content of the regular file at `path` (a symlink to a regular file is read).
// A missing file, a directory, a FIFO, a device or socket, a file larger than `max_bytes`
// or an unreadable one is InputError(field, ...), never a hang: the file is opened
// non-blocking and checked to be a regular file before a byte is read.
std::string read_input_file(const std::string& field, const std::string& path, std::size_t max_bytes);

// The same, but nothing (std::nullopt) when no file is at `path` (a missing optional input,
// e.g. a tile not yet computed). Other problems throw as above.
std::optional<std::string> read_input_file_if_present(const std::string& field, const std::string& path,
                                                      std::size_t max_bytes);

// Checks TOML text before it reaches the parser: at most `max_bytes`, no NUL byte, valid
// UTF-8 is left to the parser, and no table or array nested deeper than kMaxTomlDepth
// (counting table headers' and keys' dotted parts, inline tables and arrays). Throws
// InputError(field, "SOURCE: ...") naming the line. `source` names the file in messages.
void check_toml_text(const std::string& field, const std::string& text, const std::string& source, std::size_t max_bytes);

}  // namespace bouncer

// libFuzzer target: the option parser and every command's validation of its options.
// Input: the words of a command line after "bouncer", one per line ('\n' separates words).
// Each is run in this process with its cancellation flag already set (fuzz_common.hpp), in a
// private directory holding data/scenes/ (the scenes built into bouncer), so that
// `--scene data/scenes/NAME.toml` and relative --out paths work and nothing outside is touched.
// Skipped: command lines that would start a process (audit, reproduce without --check or
// --claims-table) or name a path outside the directory (absolute, "..").
// Property: the outcome is never an internal error, and bad input is one non-empty line.
#include <cstdint>
#include <fstream>

#include "fuzz_common.hpp"
#include "bouncer/workflow/paper.hpp"

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  bouncer::fuzz::enter_private_dir(argc, argv);
  const auto& dir = bouncer::fuzz::private_dir();
  for (const auto& [path, text] : bouncer::built_in_scenes()) {
    std::filesystem::create_directories((dir / path).parent_path());
    std::ofstream(dir / path) << text;
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace bouncer::fuzz;
  if (size > 4096) return -1;  // a command line of a few options; long values are the parsers' (fuzz_toml)
  std::vector<std::string> words = words_of(data, size);
  for (const std::string& w : words)
    if (names_outside(w)) return -1;
  words.insert(words.begin(), "bouncer");
  if (starts_processes(words)) return -1;
  check_outcome(run_cancelled(words), words);
  clean_private_dir({"data"});
  return 0;
}

// libFuzzer target: the TOML readers. Input: the bytes of a file, read as
//   * TOML text: check_toml_text (base/input.hpp: size, NUL bytes, nesting depth) and, when it
//     passes, toml++'s parser, as every reader does; only InputError / toml::parse_error may
//     come out (a stack overflow in the parser, as 40,000 dotted keys once caused, is a crash);
//   * a scene: `bouncer orbit --scene F` and `bouncer --scene F` (the scene's own command);
//   * a manifest: `bouncer reproduce --claims-table --manifest F` (parsed and validated in
//     full, the table printed; nothing runs).
// The commands run in this process, cancelled at their first long step (fuzz_common.hpp).
// Property: no crash, never an internal error, bad input one non-empty line.
// A file whose strings name a path outside the private directory is not given to the
// commands (only to the parser), so that nothing outside it is read or written.
#include <toml++/toml.h>

#include <cstdint>
#include <fstream>

#include "bouncer/base/input.hpp"
#include "fuzz_common.hpp"

namespace {

// True when a string anywhere in the parsed table names a path outside the private directory.
bool names_outside(const toml::node& n) {
  if (const auto* s = n.as_string()) return bouncer::fuzz::names_outside(s->get());
  if (const auto* t = n.as_table()) {
    for (const auto& [k, v] : *t)
      if (bouncer::fuzz::names_outside(std::string(k.str())) || names_outside(v)) return true;
  }
  if (const auto* a = n.as_array())
    for (const auto& v : *a)
      if (names_outside(v)) return true;
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  bouncer::fuzz::enter_private_dir(argc, argv);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace bouncer::fuzz;
  const std::string text(reinterpret_cast<const char*>(data), size);
  bool run_commands = true;
  try {
    bouncer::check_toml_text("scene", text, "f", bouncer::kMaxSceneBytes);
    try {
      const toml::table t = toml::parse(text, std::string_view("f"));
      run_commands = !names_outside(t);
    } catch (const toml::parse_error&) {
    }
  } catch (const bouncer::InputError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) violated(std::string("check_toml_text: a message of several lines: ") + e.what());
  } catch (const std::exception& e) {
    violated(std::string("check_toml_text/toml::parse threw neither InputError nor parse_error: ") + e.what());
  }
  if (!run_commands) return 0;
  private_dir();
  {
    std::ofstream out("f.toml", std::ios::binary);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  }
  for (const std::vector<std::string>& words :
       {std::vector<std::string>{"bouncer", "orbit", "--scene", "f.toml"}, {"bouncer", "--scene", "f.toml"},
        {"bouncer", "reproduce", "--claims-table", "--manifest", "f.toml"}})
    check_outcome(run_cancelled(words), words);
  clean_private_dir();
  return 0;
}

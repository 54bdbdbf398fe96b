#include "run_command.hpp"

#include <iostream>

#include "bouncer/base/cancel.hpp"
#include "bouncer/base/output.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/io/scene.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/workflow/commands.hpp"
#include "cli_common.hpp"
#include "command_line.hpp"
#include "commands.hpp"
#include "option_types.hpp"

namespace bouncer::cli {

namespace {

// `bouncer help [CMD]` is `bouncer [CMD] --help`; `bouncer --scene FILE ...` is
// `bouncer CMD --scene FILE ...` with CMD the scene's `command` key.
std::vector<std::string> front_end_words(std::vector<std::string> w) {
  if (w.size() >= 2 && w[1] == "help") {
    w.erase(w.begin() + 1);
    w.push_back("--help");
  } else if (w.size() >= 2 && (w[1] == "--scene" || w[1].rfind("--scene=", 0) == 0)) {
    const std::string path = w[1] == "--scene" ? (w.size() >= 3 ? w[2] : "") : w[1].substr(8);
    if (path.empty()) throw InputError("scene", "give a scene file: bouncer --scene FILE");
    w.insert(w.begin() + 1, scene_command(path));
  }
  return w;
}

// RFC 3629 UTF-8: no overlong forms, no surrogates, nothing above U+10FFFF.
bool valid_utf8(const std::string& s) {
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    int more = 0;
    unsigned char lo = 0x80, hi = 0xbf;  // the allowed range of the second byte
    if (c >= 0xc2 && c <= 0xdf) more = 1;
    else if (c == 0xe0) more = 2, lo = 0xa0;
    else if (c == 0xed) more = 2, hi = 0x9f;
    else if (c >= 0xe1 && c <= 0xef) more = 2;
    else if (c == 0xf0) more = 3, lo = 0x90;
    else if (c == 0xf4) more = 3, hi = 0x8f;
    else if (c >= 0xf1 && c <= 0xf3) more = 3;
    else return false;
    for (int k = 1; k <= more; ++k) {
      if (i + k >= s.size()) return false;
      const unsigned char d = static_cast<unsigned char>(s[i + k]);
      if (d < (k == 1 ? lo : 0x80) || d > (k == 1 ? hi : 0xbf)) return false;
    }
    i += static_cast<size_t>(more) + 1;
  }
  return true;
}

// A word for a message: bytes above 0x7f as \xNN (one_line escapes the control characters).
std::string shown_bytes(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else {
      const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

CommandOutcome failed(CommandOutcome::Kind kind, int status, const std::string& message) {
  CommandOutcome o;
  o.kind = kind;
  o.status = status;
  o.message = one_line(message);
  return o;
}

// The option named by an "unknown option '--x'" message, or "".
std::string unknown_option_in(const std::string& message) {
  const std::string mark = "unknown option '";
  const auto at = message.find(mark);
  if (at == std::string::npos) return "";
  const auto end = message.find('\'', at + mark.size());
  return end == std::string::npos ? "" : message.substr(at + mark.size(), end - at - mark.size());
}

}  // namespace

CommandOutcome run_command(std::vector<std::string> words_in, bool standalone) {
  using Kind = CommandOutcome::Kind;
  // A host can pass what a command line cannot: no words at all, or a NUL byte inside one
  // (Python's "24\x00junk", which a C string would cut to "24").
  if (words_in.empty()) return failed(Kind::input, 2, "no command line: give the program name and a command");
  for (size_t i = 0; i < words_in.size(); ++i)
    if (words_in[i].find('\0') != std::string::npos) {
      const bool value = i > 0 && words_in[i - 1].rfind("--", 0) == 0;
      return failed(Kind::input, 2, (value ? words_in[i - 1].substr(2) + ": the value '" : "the argument '") +
                                        words_in[i] + "' contains a NUL byte");
    }
  // Every input is recorded in the outputs' provenance, in JSON among them, which holds UTF-8
  // text only: a word that is not UTF-8 (bytes from a host, a file name in another encoding)
  // is bad input here, not an exception when the JSON is written after the work.
  for (size_t i = 0; i < words_in.size(); ++i)
    if (!valid_utf8(words_in[i])) {
      const bool value = i > 0 && words_in[i - 1].rfind("--", 0) == 0;
      return failed(Kind::input, 2, (value ? words_in[i - 1].substr(2) + ": the value '" : "the argument '") +
                                        shown_bytes(words_in[i]) + "' is not valid UTF-8 (outputs record their inputs as UTF-8 text)");
    }
  std::vector<std::string> words;
  try {
    words = front_end_words(std::move(words_in));
  } catch (const InputError& e) {
    return failed(Kind::input, 2, e.what());
  }
  std::vector<char*> word_ptrs;
  for (std::string& w : words) word_ptrs.push_back(w.data());
  word_ptrs.push_back(nullptr);
  const int argc = static_cast<int>(words.size());
  char** argv = word_ptrs.data();
  // Named, so that usage lines say "bouncer", not the path the program was started from.
  CLI::App app{"bouncer: verified numerics for the piecewise linear bouncer (Langer & Miller 2014)", "bouncer"};
  app.require_subcommand(1);
  app.footer("Also: bouncer help COMMAND (the same as bouncer COMMAND --help).");
  // One subcommand per row of the table of commands (workflow/commands.hpp), with the
  // options of its setup (tools/commands.cpp).
  struct Parsed {
    CLI::App* app;
    CommandRunner run;
  };
  std::vector<Parsed> commands;
  for (const CommandInfo& info : command_table()) {
    CLI::App* sub = app.add_subcommand(std::string(info.name), std::string(info.summary));
    const CommandSetup setup = command_setup(info.name);
    if (!setup) return failed(Kind::internal, 1, "internal error: the command '" + std::string(info.name) + "' has no setup");
    commands.push_back({sub, setup(sub)});
    // --help shows what each value is (every option is read as text and parsed by the
    // library's readers: the C++ type would say TEXT everywhere), and REQUIRED where the
    // command needs it (on the command line or in the --scene file, so CLI11 cannot enforce it).
    for (CLI::Option* opt : sub->get_options()) {
      if (opt->get_positional() || opt->get_items_expected_max() == 0 || opt->get_lnames().empty()) continue;
      std::string type = option_type_name(std::string(info.name), opt->get_lnames().front());
      if (opt->get_description().find("(required") != std::string::npos) type += " REQUIRED";
      opt->type_name(type);
    }
  }

  const std::string version = "bouncer " + build_info().version + " (commit " + build_info().commit + ")";
  app.set_version_flag("-V,--version", version);
  for (const Parsed& c : commands) c.app->set_version_flag("-V,--version", version);
  if (const std::string problem = check_command_line(app, argc, argv); !problem.empty()) {
    CommandOutcome o = failed(Kind::input, 2, problem);
    o.unknown_option = unknown_option_in(problem);
    return o;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {
      if (standalone) app.exit(e);
      CommandOutcome o;
      o.kind = Kind::help;
      return o;
    }
    // Point at the help of the command that was given, if one was.
    std::string help = "bouncer --help";
    for (const Parsed& c : commands)
      if (argc >= 2 && c.app->get_name() == argv[1]) help = "bouncer " + c.app->get_name() + " --help";
    return failed(Kind::input, 2, std::string(e.what()) + " (see " + help + ")");
  }
  if (standalone) install_interrupt_cleanup();  // SIGINT/SIGTERM/SIGHUP remove partial files (base/output.hpp)
  try {
    for (const Parsed& c : commands)
      if (c.app->parsed()) {
        CommandOutcome o;
        o.status = c.run(invocation(argc, argv));
        if (!command_capture()) check_stdout();  // whatever a command printed must have arrived
        return o;
      }
  } catch (const InputError& e) {
    return failed(Kind::input, 2, e.what());
  } catch (const OutputError& e) {
    return failed(Kind::output, 1, e.what());
  } catch (const ResourceError& e) {
    return failed(Kind::output, 1, e.what());
  } catch (const Cancelled& e) {
    return failed(Kind::cancelled, 130, e.what());
  } catch (const std::exception& e) {
    return failed(Kind::internal, 1, std::string("internal error: ") + e.what());
  }
  return {};
}

}  // namespace bouncer::cli

// The one output writer and the bounded readers (base/output.hpp, base/input.hpp) against hostile
// file systems: links and FIFOs planted at output and staging paths, a second writer of the
// same path in this process, stale staging files of a killed run, and TOML shaped to
// overflow a recursive parser. Each expectation is what the header promises, checked on real
// files in a fresh temporary directory.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <thread>

#include "bouncer/base/input.hpp"
#include "bouncer/base/output.hpp"
#include "bouncer/model/spec.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace bouncer;
using namespace bouncer::test_support;

// The InputError's message, or "" when none is thrown.
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(OutputSet, WritesEveryFileOnlyAtCommit) {
  TempDir d;
  OutputSet set;
  set.reserve("out", d / "a.csv");
  set.reserve("out", d / "a.json");
  EXPECT_TRUE(fs::exists(d / "a.csv.partial"));  // staged before the work
  set.write(d / "a.csv", text("rows\n"));
  set.write(d / "a.json", text("{}\n"));
  EXPECT_FALSE(fs::exists(d / "a.csv"));
  set.commit();
  EXPECT_EQ(slurp(d / "a.csv"), "rows\n");
  EXPECT_EQ(slurp(d / "a.json"), "{}\n");
  EXPECT_FALSE(fs::exists(d / "a.csv.partial"));
  EXPECT_FALSE(fs::exists(d / "a.json.partial"));
}

TEST(OutputSet, DestroyedBeforeCommitLeavesNothing) {
  TempDir d;
  put(d / "old.csv", "previous\n");
  {
    OutputSet set;
    set.reserve("out", d / "old.csv");
    set.reserve("out", d / "new.csv");
    set.write(d / "old.csv", text("half"));
  }
  EXPECT_EQ(slurp(d / "old.csv"), "previous\n");
  EXPECT_FALSE(fs::exists(d / "new.csv"));
  EXPECT_EQ(std::distance(fs::directory_iterator(d.path), fs::directory_iterator()), 1);  // old.csv alone
}

TEST(OutputSet, ASecondWriterOfOnePathIsRefusedEvenInThisProcess) {
  TempDir d;
  OutputSet first;
  first.reserve("out", d / "o.csv");
  OutputSet second;
  const std::string m = input_error([&] { second.reserve("out", d / "o.csv"); });
  EXPECT_NE(m.find("out: "), std::string::npos) << m;
  EXPECT_NE(m.find("in use by another command of this process"), std::string::npos) << m;
  first.write(d / "o.csv", text("first\n"));
  first.commit();
  EXPECT_EQ(slurp(d / "o.csv"), "first\n");
  // Free again once committed.
  OutputSet third;
  third.reserve("out", d / "o.csv");
}

TEST(OutputSet, AStagingFileLeftByAKilledRunIsReclaimed) {
  TempDir d;
  put(d / "o.csv.partial", "a run that was killed wrote this");
  write_output("out", d / "o.csv", text("fresh\n"));
  EXPECT_EQ(slurp(d / "o.csv"), "fresh\n");
  EXPECT_FALSE(fs::exists(d / "o.csv.partial"));
}

TEST(OutputSet, ALinkPlantedAtTheStagingNameIsNeverFollowed) {
  TempDir d;
  put(d / "victim", "precious\n");
  fs::create_symlink(d / "victim", d / "o.csv.partial");
  write_output("out", d / "o.csv", text("result\n"));
  EXPECT_EQ(slurp(d / "victim"), "precious\n");
  EXPECT_EQ(slurp(d / "o.csv"), "result\n");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(d / "o.csv")));
}

TEST(OutputSet, AFifoPlantedAtTheStagingNameDoesNotBlock) {
  TempDir d;
  ASSERT_EQ(::mkfifo((d / "o.csv.partial").c_str(), 0600), 0);
  auto done = std::async(std::launch::async, [&] { write_output("out", d / "o.csv", text("result\n")); });
  ASSERT_EQ(done.wait_for(std::chrono::seconds(20)), std::future_status::ready) << "blocked on a planted FIFO";
  done.get();
  EXPECT_EQ(slurp(d / "o.csv"), "result\n");
}

TEST(OutputSet, ADirectoryAtTheStagingNameIsBadInput) {
  TempDir d;
  fs::create_directory(d / "o.csv.partial");
  const std::string m = input_error([&] { write_output("out", d / "o.csv", text("x")); });
  EXPECT_NE(m.find("is a directory"), std::string::npos) << m;
  EXPECT_FALSE(fs::exists(d / "o.csv"));
}

TEST(OutputTarget, ALinkToARegularFileIsRefusedAndNothingChanges) {
  TempDir d;
  put(d / "victim", "precious\n");
  fs::create_symlink(d / "victim", d / "o.csv");
  const std::string m = input_error([&] { write_output("out", d / "o.csv", text("result\n")); });
  EXPECT_NE(m.find("is a symbolic link"), std::string::npos) << m;
  EXPECT_EQ(slurp(d / "victim"), "precious\n");
  EXPECT_TRUE(fs::is_symlink(d / "o.csv"));
  EXPECT_FALSE(fs::exists(d / "o.csv.partial"));
}

TEST(OutputTarget, AFifoAndALinkToADeviceAreWrittenThrough) {
  TempDir d;
  ASSERT_EQ(::mkfifo((d / "pipe").c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [&] { return slurp(d / "pipe"); });
  write_output("out", d / "pipe", text("through the pipe\n"));
  EXPECT_EQ(reader.get(), "through the pipe\n");
  struct stat st {};
  ASSERT_EQ(::lstat((d / "pipe").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  fs::create_symlink("/dev/null", d / "null");
  write_output("out", d / "null", text("gone\n"));
  EXPECT_TRUE(fs::is_symlink(d / "null"));
}

TEST(OutputTarget, NamesTheFileSystemCannotHoldAreBadInput) {
  TempDir d;
  EXPECT_NE(input_error([&] { output_target("out", d / std::string(250, 'x')); }).find("longer than"), std::string::npos);
  EXPECT_NE(input_error([&] { output_target("out", d / "no-such-folder/o.csv"); }).find("does not exist"), std::string::npos);
  EXPECT_NE(input_error([&] { output_target("out", d.path.string() + "/"); }).find("ends in '/'"), std::string::npos);
  EXPECT_NE(input_error([&] { output_target("out", d.path.string()); }).find("is a directory"), std::string::npos);
}

TEST(OwnDirectory, ALinkIsRefusedAndItsTargetKept) {
  TempDir d;
  fs::create_directory(d / "elsewhere");
  put(d / "elsewhere/job.key", "k\n");
  fs::create_directory_symlink(d / "elsewhere", d / "p.tiles");
  EXPECT_NE(input_error([&] { make_own_directory("out", d / "p.tiles"); }).find("symbolic link"), std::string::npos);
  EXPECT_TRUE(fs::exists(d / "elsewhere/job.key"));
  make_own_directory("out", d / "q.tiles");
  EXPECT_TRUE(fs::is_directory(d / "q.tiles"));
}

TEST(ReadInputFile, RefusesWhatIsNotARegularFileWithoutBlocking) {
  TempDir d;
  ASSERT_EQ(::mkfifo((d / "fifo.toml").c_str(), 0600), 0);
  auto r = std::async(std::launch::async, [&] { return input_error([&] { read_input_file("scene", d / "fifo.toml", 100); }); });
  ASSERT_EQ(r.wait_for(std::chrono::seconds(20)), std::future_status::ready) << "blocked on a FIFO";
  EXPECT_NE(r.get().find("named pipe"), std::string::npos);
  EXPECT_NE(input_error([&] { read_input_file("scene", d.path.string(), 100); }).find("directory"), std::string::npos);
  EXPECT_NE(input_error([&] { read_input_file("scene", "/dev/zero", 100); }).find("character device"), std::string::npos);
  put(d / "big", std::string(101, 'x'));
  EXPECT_NE(input_error([&] { read_input_file("scene", d / "big", 100); }).find("larger than"), std::string::npos);
  EXPECT_EQ(read_input_file("scene", d / "big", 101), std::string(101, 'x'));
  EXPECT_FALSE(read_input_file_if_present("scene", d / "missing", 100).has_value());
  EXPECT_NE(input_error([&] { read_input_file("scene", d / "missing", 100); }).find("not found"), std::string::npos);
}

// ---- the TOML shape check ----------------------------------------------------------------------

std::string toml_error(const std::string& t) {
  return input_error([&] { check_toml_text("scene", t, "s.toml", kMaxSceneBytes); });
}

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

TEST(TomlShape, RefusesTheNestingThatOverflowedTheParser) {
  // The audit's reproducer: 40,000 dotted parts in one key (toml++ recursed until SIGSEGV).
  std::string deep = "command = \"orbit\"\nk";
  for (int i = 1; i < 40000; ++i) deep += ".k";
  deep += " = 1\n";
  const std::string m = toml_error(deep);
  EXPECT_NE(m.find("s.toml line 2: tables or arrays nested more than 32 deep"), std::string::npos) << m;
  EXPECT_NE(toml_error("a = " + repeat("[", 40) + repeat("]", 40) + "\n"), "");
  EXPECT_NE(toml_error("a = " + repeat("{b = ", 40) + "1" + repeat("}", 40) + "\n"), "");
  EXPECT_NE(toml_error(std::string("[") + repeat("t.", 40) + "t]\n"), "");
  EXPECT_NE(toml_error(std::string("[[") + repeat("t.", 40) + "t]]\n"), "");
  // Depth adds up: a header's parts, a key's parts and inline tables' keys below it.
  EXPECT_NE(toml_error(std::string("[") + repeat("h.", 15) + "h]\n" + repeat("k.", 15) + "k = {" + repeat("i.", 5) + "i = 1}\n"), "");
  EXPECT_NE(toml_error("a = {" + repeat("b.", 20) + "b = {" + repeat("c.", 20) + "c = 1}}\n"), "");
}

TEST(TomlShape, CountsOnlyStructureNotStringsCommentsOrNumbers) {
  // 32 levels is allowed, 33 is not.
  EXPECT_EQ(toml_error(repeat("k.", 32) + "k = 1\n"), "");
  EXPECT_NE(toml_error(repeat("k.", 33) + "k = 1\n"), "");
  EXPECT_EQ(toml_error("a = " + repeat("[", 32) + repeat("]", 32) + "\n"), "");
  EXPECT_NE(toml_error("a = " + repeat("[", 33) + repeat("]", 33) + "\n"), "");
  // Dots and brackets inside strings, comments and values are not structure.
  const std::string dots = repeat(".", 200), brackets = repeat("[{", 100);
  EXPECT_EQ(toml_error("a = \"" + dots + brackets + "\"\n"), "");
  EXPECT_EQ(toml_error("a = '" + dots + brackets + "'\n"), "");
  EXPECT_EQ(toml_error("# " + dots + brackets + "\n"), "");
  EXPECT_EQ(toml_error("a = \"\"\"\n" + dots + "\n" + brackets + "\"\"\"\n"), "");
  EXPECT_EQ(toml_error("a = '''\n" + dots + brackets + "\n'''\n"), "");
  EXPECT_EQ(toml_error("a = \"\"\"x\"\"\"\"\"\nb = 1\n"), "");  // a multi-line string ending in two quotes
  EXPECT_EQ(toml_error("\"" + dots + "\" = 1\n"), "");       // a quoted key is one part
  EXPECT_EQ(toml_error("a = [" + repeat("1.5, ", 100) + "2.5]\n"), "");
  EXPECT_EQ(toml_error("a = \"escaped \\\" quote " + dots + "\"\n"), "");
  // The line of a problem is named.
  EXPECT_NE(toml_error("a = 1\nb = 2\n" + repeat("k.", 40) + "k = 1\n").find("line 3"), std::string::npos);
}

TEST(TomlShape, RefusesNulBytesAndOversizedText) {
  EXPECT_NE(toml_error(std::string("a = \"24\0junk\"\n", 15)).find("NUL"), std::string::npos);
  const std::string m = input_error([&] { check_toml_text("manifest", std::string(2000, '#'), "m.toml", 1000); });
  EXPECT_NE(m.find("manifest: m.toml: larger than 1000 bytes"), std::string::npos) << m;
}

TEST(TomlShape, AcceptsEveryFileBouncerShips) {
  const fs::path src = BOUNCER_SOURCE_DIR;
  int checked = 0;
  for (const auto& e : fs::directory_iterator(src / "data/scenes")) {
    EXPECT_EQ(toml_error(slurp(e.path().string())), "") << e.path();
    ++checked;
  }
  const std::string manifest = slurp((src / "data/paper/manifest.toml").string());
  EXPECT_EQ(input_error([&] { check_toml_text("manifest", manifest, "manifest.toml", kMaxManifestBytes); }), "");
  EXPECT_GE(checked, 10);
}

}  // namespace

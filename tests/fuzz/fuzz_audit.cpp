// libFuzzer target: audit's trust boundary (workflow/audit.hpp). Input: the bytes of a file given
// to `bouncer audit FILE`. plan_rerun reads its provenance and builds the rerun, without
// running anything. Property: it throws InputError, or returns a plan that
//   * runs this binary (argv[0]) with one of the computing commands (is_computing_command, workflow/commands.hpp),
//   * never names where to read tiles, a scene or a manifest, or a shard (--tiles-from,
//     --scene, --manifest, --shard, --keep-tiles, as a word or --NAME=VALUE),
//   * writes only into the directory it was given: every --out value, and the file it
//     compares, are inside it.
// The plan's command line is then validated as audit validates it (in this process,
// cancelled at its first step: fuzz_common.hpp): never an internal error.
// (A reproduce directory's claims.json is audited by audit_reproduce, which starts the rerun
// as soon as it has built it: no part of it is reachable without starting a process.)
#include <cstdint>

#include "bouncer/workflow/audit.hpp"
#include "bouncer/workflow/commands.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  bouncer::fuzz::enter_private_dir(argc, argv);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace bouncer::fuzz;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string dir = (private_dir() / "rerun").string();  // never created: nothing is written there
  bouncer::AuditPlan plan;
  try {
    plan = bouncer::plan_rerun("f", text, dir, "/self");
  } catch (const bouncer::InputError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) violated(std::string("plan_rerun: a message of several lines: ") + e.what());
    return 0;
  } catch (const std::exception& e) {
    violated(std::string("plan_rerun threw something else than InputError: ") + e.what());
  }
  const std::vector<std::string>& argv = plan.argv;
  if (argv.size() < 2 || argv[0] != "/self") violated("the plan does not run this binary: " + shown(argv));
  if (!bouncer::is_computing_command(argv[1]) || plan.command != argv[1])
    violated("the plan runs '" + argv[1] + "', not a computing command: " + shown(argv));
  const std::string inside = dir + "/";
  for (size_t i = 2; i < argv.size(); ++i) {
    const std::string& w = argv[i];
    for (const char* never : {"--tiles-from", "--scene", "--manifest", "--shard", "--keep-tiles"})
      if (w == never || w.rfind(std::string(never) + "=", 0) == 0) violated("the plan gives " + w + ": " + shown(argv));
    if (w.rfind("--out=", 0) == 0 && w.rfind("--out=" + inside, 0) != 0) violated("the plan writes outside its directory: " + shown(argv));
    if (w == "--out" && (i + 1 >= argv.size() || argv[i + 1].rfind(inside, 0) != 0))
      violated("the plan's --out is not inside its directory: " + shown(argv));
  }
  if (plan.compare_path.rfind(inside, 0) != 0) violated("the plan compares a file outside its directory: " + plan.compare_path);
  if (!plan.rerun_data_path.empty() && plan.rerun_data_path.rfind(inside, 0) != 0)
    violated("the plan reads the rerun's npy data outside its directory: " + plan.rerun_data_path);
  // The audited file's npy data is named by the file's own path ("f" has no .json: none).
  if (!plan.data_path.empty()) violated("the plan names npy data beside a file not named PATH.json: " + plan.data_path);
  // Validated as audit does before it starts the rerun.
  std::vector<std::string> words{"bouncer"};
  words.insert(words.end(), argv.begin() + 1, argv.end());
  for (const std::string& w : words)
    if (names_outside(w) && w.rfind(inside, 0) != 0) return 0;
  check_outcome(run_cancelled(words), words);
  clean_private_dir();
  return 0;
}

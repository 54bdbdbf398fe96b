// libFuzzer target: chaos certificates (io/chaos_certificate.hpp, verify/chaos_certificate.hpp).
// Input: the bytes of a file given to `bouncer check-certificate FILE`. parse_certificate
// refuses it (InputError, one line) or returns a certificate; a small one (at most 8 h-sets,
// k at most 4, at most 16 pieces per side: the fuzzer's time, not a property) is replayed in
// Arb at 64 bits. Property: nothing but InputError leaves the parser, and the replay never
// throws: whatever the file says, the answer is a verdict.
#include <cstdint>

#include "bouncer/io/chaos_certificate.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  bouncer::fuzz::enter_private_dir(argc, argv);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace bouncer::fuzz;
  const std::string text(reinterpret_cast<const char*>(data), size);
  bouncer::ChaosCertificate c;
  try {
    c = bouncer::parse_certificate(text);
  } catch (const bouncer::InputError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) violated(std::string("parse_certificate: a message of several lines: ") + e.what());
    return 0;
  } catch (const std::exception& e) {
    violated(std::string("parse_certificate threw something else than InputError: ") + e.what());
  }
  if (c.sets.size() > 8 || c.k > 4) return 0;
  for (const bouncer::CertifiedCovering& v : c.coverings)
    if (v.pieces > 16) return 0;
  try {
    const bouncer::ReplayResult r = bouncer::replay_certificate(c, 64);
    if (r.valid && r.problems.size() != 1) violated("a valid replay with problems");
  } catch (const std::exception& e) {
    violated(std::string("replay_certificate threw: ") + e.what());
  }
  return 0;
}

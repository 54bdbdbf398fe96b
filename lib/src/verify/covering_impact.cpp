// The impact map as a box map (verify/covering_impact.hpp).
#include "bouncer/verify/covering_impact.hpp"

#include <memory>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {

namespace {

// A step's branch: its event (step_event) without the indirect flag, which over a box may be
// undecided and is not part of a branch (chaos certificates record the branch without it),
// and its wraps. The covered steps are impacts on the triangle wall's segments.
BranchStep branch_step(const StepResult<Mpfi>& s) {
  BranchStep b;
  b.event = step_event(s, false);
  b.event.indirect = false;
  b.periods = s.periods;
  return b;
}

}  // namespace

std::vector<BranchStep> impact_branch(const ModelSpec& spec, long k, long bits, const mpq_class& theta,
                                      const mpq_class& v) {
  const Model<Mpfi> model = interval_model(spec, bits);
  std::vector<BranchStep> out;
  try {
    OrbitEnclosure orbit(model, State<Mpfi>{enclose(theta, theta, bits), enclose(v, v, bits)}, EnclosureMethod::naive);
    for (long i = 0; i < k; ++i) out.push_back(branch_step(orbit.step().event));
  } catch (const Undecided&) {
    return {};
  }
  return out;
}

std::string branch_text(const std::vector<BranchStep>& branch) {
  // event_text's token of each step, then its wraps.
  std::string text;
  for (const BranchStep& b : branch) {
    if (!text.empty()) text += ' ';
    text += event_text({b.event});
    text += '+';
    text += std::to_string(b.periods);
  }
  return text;
}

BoxMap2 impact_box_map(const ModelSpec& spec, const std::vector<BranchStep>& branch, long bits, EnclosureMethod method) {
  auto model = std::make_shared<const Model<Mpfi>>(interval_model(spec, bits));
  return [model, branch, method](const Box2& box) -> std::optional<Box2> {
    if (branch.empty()) return std::nullopt;
    try {
      OrbitEnclosure orbit(*model, State<Mpfi>{box[0], box[1]}, method);
      for (const BranchStep& want : branch) {
        const EnclosedStep s = orbit.step();
        if (s.event.kind != EventKind::impact || !(branch_step(s.event) == want)) return std::nullopt;
      }
      const State<Mpfi>& y = orbit.box();
      if (!ScalarTraits<Mpfi>::is_finite(y.theta) || !ScalarTraits<Mpfi>::is_finite(y.v)) return std::nullopt;
      return Box2{y.theta, y.v};
    } catch (const Undecided&) {
      return std::nullopt;
    }
  };
}

SetMap2 impact_set_map(const ModelSpec& spec, const std::vector<BranchStep>& branch, long bits) {
  auto model = std::make_shared<const Model<Mpfi>>(interval_model(spec, bits));
  return [model, branch](const Parallelogram& piece) -> std::optional<Parallelogram> {
    if (branch.empty()) return std::nullopt;
    try {
      OrbitEnclosure orbit(*model, piece);
      for (const BranchStep& want : branch) {
        const EnclosedStep s = orbit.step();
        if (s.event.kind != EventKind::impact || !(branch_step(s.event) == want)) return std::nullopt;
      }
      Parallelogram out = orbit.set();
      if (!ScalarTraits<Mpfi>::is_finite(out.r[0]) || !ScalarTraits<Mpfi>::is_finite(out.r[1])) return std::nullopt;
      return out;
    } catch (const Undecided&) {
      return std::nullopt;
    }
  };
}

}  // namespace bouncer

// Certified long-run answers for single starts (verify/certified_point.hpp).
#include "bouncer/verify/certified_point.hpp"

#include <algorithm>

namespace bouncer {

namespace {

StickingQuestion question(const ModelSpec& model, const InitialCondition& start, const CertifyPointOptions& opt) {
  StickingQuestion q;
  q.model = model;
  q.start = start;
  q.max_steps = opt.max_steps;
  q.schedule.double_first = true;
  q.schedule.start_bits = 64;
  q.schedule.max_bits = opt.max_bits;
  q.prove_attractor = model.law != Law::elastic;
  q.max_attractor_period = opt.max_attractor_period;
  q.a_range = opt.a_range;
  return q;
}

// The elastic model has no attractor to look for: its orbit is certified and nothing more
// (certify_orbit_steps); the dissipative models ask the sticking question.
StickingCertificate certify(const StickingQuestion& q) {
  return q.model.law == Law::elastic ? certify_orbit_steps(q) : certify_sticking(q);
}

// The class a non-sticking certificate states.
void set_from_trap_or_none(CertifiedPoint& p, const StickingCertificate& c, Law law) {
  switch (c.outcome) {
    case StickingOutcome::never_sticks:
      p.period = c.attractor->period;
      p.cls = p.period == 1 ? CertifiedClass::fixed : CertifiedClass::periodic;
      break;
    case StickingOutcome::no_sticking_within_max_steps:
      // Velocity-dependent: no orbit collapses, so "no sticking" says nothing; what is
      // certified is the orbit through every step, with no trapping set at its end (elastic:
      // none can exist).
      p.cls = law == Law::constant ? CertifiedClass::no_sticking : CertifiedClass::not_trapped;
      break;
    default:
      p.cls = CertifiedClass::undecided;
      p.reason = c.reason;
      break;
  }
}

}  // namespace

StickingCertificate ReleaseCache::get(const ModelSpec& model, const std::string& theta, const std::string& v,
                                      const CertifyPointOptions& opt) {
  // Appended piece by piece ("," + temporary trips GCC 12's -Wrestrict).
  std::string key = theta;
  key += ',';
  key += v;
  if (opt.a_range) {
    key += ',';
    key += opt.a_range->first.get_str();
    key += ',';
    key += opt.a_range->second.get_str();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = done_.find(key);
    if (it != done_.end()) return it->second;
  }
  // Computed outside the lock (two threads may both compute it: the same pure result).
  StickingQuestion q;
  if (theta.empty()) {
    q = question(model, InitialCondition{}, opt);
    q.from_release = true;
  } else {
    q = question(model, InitialCondition{*Decimal::parse(theta), *Decimal::parse(v)}, opt);
  }
  q.schedule.max_bits = std::max(opt.max_bits, 4096L);
  q.max_steps = std::max(opt.max_steps, 20000LL);
  StickingCertificate c = certify(q);
  std::lock_guard<std::mutex> lock(mutex_);
  return done_.emplace(key, std::move(c)).first->second;
}

StickingCertificate ReleaseCache::get_release(const ModelSpec& model, const CertifyPointOptions& opt) {
  return get(model, "", "", opt);  // the empty start names the release state
}

namespace {

// The class of an orbit after its first sticking at step `first`: the release orbit's.
void from_release_certificate(CertifiedPoint& p, const StickingCertificate& r, const ModelSpec& model,
                              const CertifyPointOptions& opt, long long first) {
  if (r.outcome == StickingOutcome::sticks) {
    p.cls = CertifiedClass::sticking;
    p.period = *r.period;
    return;
  }
  set_from_trap_or_none(p, r, model.law);
  p.free_steps = r.steps_checked;
  if (p.cls == CertifiedClass::undecided && r.steps_checked >= opt.max_steps) p.cls = CertifiedClass::no_sticking;
  if (p.cls == CertifiedClass::undecided)
    p.reason = (first ? "sticks at step " + std::to_string(first) + ", then " : std::string()) + "the release orbit: " + r.reason;
}

}  // namespace

CertifiedPoint certify_release_point(const ModelSpec& model, const CertifyPointOptions& opt, ReleaseCache& releases) {
  if (model.wall.shape != WallShape::sine)
    throw InputError("wall", "the release state as a start is for smooth walls (a piecewise wall's is an exact knot: give it as theta, v)");
  CertifiedPoint p;
  const StickingCertificate r = releases.get_release(model, opt);
  p.certified_steps = r.steps_checked;
  p.scalar = r.scalar;
  from_release_certificate(p, r, model, opt, 0);
  return p;
}

CertifiedPoint certify_point(const ModelSpec& model, const InitialCondition& start, const CertifyPointOptions& opt,
                             ReleaseCache& releases) {
  CertifiedPoint p;
  const StickingCertificate c = certify(question(model, start, opt));
  p.certified_steps = c.steps_checked;
  p.scalar = c.scalar;
  if (c.outcome != StickingOutcome::sticks) {
    set_from_trap_or_none(p, c, model.law);
    return p;
  }
  p.first_sticking = *c.period;
  const bool smooth = model.wall.shape == WallShape::sine;
  if (c.release_theta.empty() && !smooth) {
    p.cls = CertifiedClass::undecided;
    p.reason = "sticks at step " + std::to_string(*c.period) + "; the release state is not a single number";
    return p;
  }
  const StickingCertificate r = smooth ? releases.get_release(model, opt) : releases.get(model, c.release_theta, c.release_v, opt);
  from_release_certificate(p, r, model, opt, *c.period);
  return p;
}

void require_certified_model(const ModelSpec& m, const std::string& command) {
  if (m.law == Law::elastic) return;
  if (const std::string why = why_no_certified_answers(m); !why.empty())
    throw InputError("certify", command + " --certify needs --model constant, elastic or veldep (without "
                                          "--veldep-collapse): " + why);
}

Agreement compare_with_certified(const CertifiedPoint& c, OrbitClass double_class, long double_period) {
  using C = CertifiedClass;
  if (c.cls == C::outside) return Agreement::outside;
  if (c.cls == C::undecided) return Agreement::undecided;
  if (c.cls == C::sticking)
    return double_class == OrbitClass::sticking && double_period == c.period ? Agreement::agrees : Agreement::differs;
  if (c.cls == C::fixed || c.cls == C::periodic) {
    const bool periodic = double_class == OrbitClass::fixed || double_class == OrbitClass::periodic;
    return periodic && double_period == c.period ? Agreement::agrees : Agreement::differs;
  }
  // not_trapped (velocity-dependent): the orbit is certified, its attractor is not: double's
  // class can be neither confirmed nor refuted.
  if (c.cls == C::not_trapped) return Agreement::undecided;
  // no_sticking: the certified statement is only that it does not stick (again) for a while.
  if (double_class != OrbitClass::sticking) return Agreement::agrees;
  if (c.first_sticking == 0) return Agreement::differs;  // double stuck within max_steps, the exact orbit does not
  return double_period <= c.free_steps ? Agreement::differs : Agreement::undecided;
}

const char* name(CertifiedClass c) {
  switch (c) {
    case CertifiedClass::sticking: return "sticking";
    case CertifiedClass::fixed: return "fixed";
    case CertifiedClass::periodic: return "periodic";
    case CertifiedClass::no_sticking: return "no_sticking";
    case CertifiedClass::not_trapped: return "not_trapped";
    case CertifiedClass::undecided: return "undecided";
    case CertifiedClass::outside: return "outside";
  }
  return "?";
}

std::optional<CertifiedClass> certified_class_named(std::string_view text) {
  for (int i = 0; i < kCertifiedClassCount; ++i)
    if (text == name(static_cast<CertifiedClass>(i))) return static_cast<CertifiedClass>(i);
  return std::nullopt;
}

const char* name(Agreement a) {
  switch (a) {
    case Agreement::agrees: return "agrees";
    case Agreement::differs: return "differs";
    case Agreement::undecided: return "undecided";
    case Agreement::outside: return "outside";
  }
  return "?";
}

std::optional<Agreement> agreement_named(std::string_view text) {
  for (Agreement a : {Agreement::agrees, Agreement::differs, Agreement::undecided, Agreement::outside})
    if (text == name(a)) return a;
  return std::nullopt;
}

}  // namespace bouncer

// The file form of a chaos certificate (verify/chaos_certificate.hpp): JSON, format
// "bouncer-chaos-certificate", version 1. docs/guide/chaos.md describes every field.
#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/io/plot.hpp"
#include "bouncer/verify/chaos_certificate.hpp"

namespace bouncer {

// The certificate as JSON text: rationals as "p/q" strings (or integers), decimals as written,
// the model as a scene's model keys (model, a, eps, c, wall, downward-sticking,
// veldep-collapse), every field named, and a "summary" object (map, k, counts, the stated
// bound: for a reader; the replay does not read it); `provenance`, when given, is a Provenance::as_json()
// object written as the field "provenance" (what made the file, for audit and for humans;
// the replay does not read it); `files`, when given, is written as the object "files" (kind to
// path of the outputs written with it, as a picture command's JSON lists them: where they
// were written, which audit ignores).
std::string certificate_json(const ChaosCertificate& c, const std::string& provenance = "",
                             const std::vector<std::pair<std::string, std::string>>& files = {});

// Parses certificate_json's text, treating it as hostile ("provenance", "files" and "summary"
// objects are skipped). Throws InputError naming the field
// and what was expected on anything else: not JSON, a missing, unknown or mistyped field, a
// singular frame, a covering naming no h-set or given twice, an out-of-range parameter, or
// numbers beyond the limits (at most 1024 h-sets and 4096 coverings, rationals of at most
// 4096 characters, k at most 100000, pieces per side at most 4096, and at most 2^24
// evaluations of F in the replay: k (pieces^2 + 2 pieces) summed over the coverings).
ChaosCertificate parse_certificate(const std::string& text);

// The certificate's map in words, for reports and figure titles: "the impact map,
// velocity-dependent restitution, a = 27, c = 1000" (with ", wall W" when the wall is not the triangle), or
// "the Hénon map, a = 6, b = 0.3".
std::string map_text(const ChaosCertificate& c);

// The h-sets as CSV, for plotting: provenance comment lines (`provenance_lines`, "# ..."),
// then one row per h-set: set, theta, v (its centre), u_theta, u_v (the unstable column of
// its frame), s_theta, s_v (the stable column), each the double nearest the exact rational of
// the certificate (shortest round-trip digits); the exact values are the certificate's.
void write_hsets_csv(std::ostream& out, const ChaosCertificate& c, const std::string& provenance_lines);

// A picture of one covering N => M of a certificate (its index in `coverings`), in M's local
// coordinates (y_u, y_s): M is the square [-1, 1]^2, and the image under G of N's boundary is
// drawn from `samples` points per edge (the left edge's image in red, the right edge's in
// blue, the stable sides' in grey), each point mapped by the replay's map (replay_iterate)
// at its centre. An illustration: the proof is the interval check, not these points.
Figure covering_figure(const ChaosCertificate& c, std::size_t covering, int samples = 200);

// The h-sets of a certificate of the impact map in the phase plane (theta, v), over points
// of an orbit on the attractor (`attractor`, grey; e.g. from portrait()): each h-set's centre
// marked, N_0 in red, the others in blue joined in the chain's order (the homoclinic orbit
// the coverings follow). The h-sets themselves are far smaller than a pixel; the title says
// how small.
Figure horseshoe_figure(const ChaosCertificate& c, const std::vector<std::pair<double, double>>& attractor);

}  // namespace bouncer

// The pictures of the grid results (run/): basins, certified maps (basin and scan --certify)
// with their artefact maps, parameter scans and bifurcation diagrams, built from the typed
// results, and the class censuses their legends and summaries share. The commands add the
// provenance (PNG metadata) and write them.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/io/plot.hpp"
#include "bouncer/run/basin.hpp"
#include "bouncer/run/bifurcation.hpp"
#include "bouncer/run/scan.hpp"

namespace bouncer {

// "constant restitution", "velocity-dependent restitution", "elastic" (figure titles).
std::string model_title(Law law);
// "constant restitution model", with the wall named unless it is the paper's triangle
// (", sine wall"), for figure titles.
std::string model_name(const ModelSpec& m);
// A parameter's axis title, symbol and meaning: "a (dimensionless gravity)", "ε (restitution)",
// "c (restitution velocity scale)" (every figure with a parameter axis).
std::string parameter_label(Parameter p);
// "a = 23.1, c = 1000" (figure subtitles).
std::string parameters_text(const ModelSpec& m);
// Pixel of item i (column i mod nx, row i / nx from the bottom) in a raster (rows from the top).
size_t pixel_of(size_t i, long nx, long ny);

// The colour of an attractor type (basin, scan legends, exponent curves); `rank` orders the
// periodic types by their share, `sub_rank` the sticking periods and the periods transient
// chaos settles on. Palette safe (default): fixed points black, periodic types Okabe-Ito
// colours, sticking vermillion shades, chaos bluish green, unbounded blue. Palette paper: as
// the paper's figures, every periodic type (fixed points too) black, sticking red, chaos green.
Rgb attractor_color(OrbitClass cls, int rank, int sub_rank, Palette palette = Palette::safe);
// A legend's words for a class and period ("period 3", "sticking, k = 4", ...).
std::string attractor_label(OrbitClass cls, long period);

// How many cells have each (class, period), largest first (ties: by class name, then period).
struct ClassCount {
  OrbitClass cls = OrbitClass::undecided;
  long period = 0;
  long points = 0;
};
std::vector<ClassCount> attractor_census(const std::vector<AttractorCell>& cells);
struct CertifiedCount {
  CertifiedClass cls = CertifiedClass::undecided;
  long period = 0;
  long points = 0;
};
std::vector<CertifiedCount> certified_census(const std::vector<CertifiedCell>& cells);

// Basins: one pixel per start, coloured by its class and period; the legend gives each
// type's share of the starts in the phase space.
ImageFigure basin_figure(const BasinResult& b, Palette palette);

// A certified map's axes and words (basin --certify, scan --certify).
struct CertifiedMap {
  std::string x_name, y_name;  // CSV column names of the two coordinates
  long nx = 0, ny = 0;         // item i: column i mod nx, row i / nx (bottom row first)
  mpq_class x0, x1, y0, y1;    // the window
  std::string title, subtitle, xlabel, ylabel;
  long long max_steps = 0;
  long max_bits = 0;
  bool collapses = true;  // constant restitution (sticking exists); false: velocity-dependent or elastic
  bool area_preserving = false;  // elastic: no trapping set exists (not_trapped is all a point can be)
};
CertifiedMap certified_map(const CertifiedBasinResult& b);
CertifiedMap certified_map(const CertifiedScanResult& s);
// The legend's words for a certified class.
std::string certified_label(CertifiedClass cls, long period, long long max_steps, long max_bits, bool collapses,
                            bool area_preserving = false);
// The certified classes (PREFIX.png: grey = undecided) and the artefact map (where double's
// class is refuted: PREFIX-artefacts.png).
std::pair<ImageFigure, ImageFigure> certified_figures(const CertifiedMap& m, const std::vector<CertifiedCell>& cells,
                                                      Palette palette);
// An artefact map (PREFIX-artefacts.png of basin --certify, scan --certify and basin
// --confirm): `frame` (window, axes, size) with one pixel per cell i (column i mod nx, row
// i / nx) by its agreement: light grey agrees, vermillion differs (an artefact), dark grey
// undecided, white outside (not compared); the legend's shares are of the cells compared.
struct AgreementWords {
  std::string title, agrees, differs, undecided;
  std::string outside;  // a legend entry for the white cells; "" for none
};
ImageFigure agreement_figure(ImageFigure frame, const std::vector<Agreement>& cells, long nx, long ny,
                             const AgreementWords& words, Palette palette);
// basin --confirm's artefact map: basin_figure's frame, each start of the confirmation
// sample by its verdict (run/cells.hpp GridConfirm; analysis/classify.hpp check_precision).
ImageFigure basin_confirm_figure(const BasinResult& b, Palette palette);
// `scan --confirm`'s map of the parameter points: a point is red where some confirmed start
// of it is double's artefact, dark grey where one is precision dependent, light grey where
// all agree, white outside the sample (PREFIX-artefacts.png).
ImageFigure scan_confirm_figure(const ScanResult& s, Palette palette);
// A certified map's CSV, without its provenance lines: the header "X,Y,class,period,
// certified_steps,scalar,double_class,double_period,agreement" (X, Y: the map's x_name,
// y_name), then one row per cell (cell i at xs[i mod nx], ys[i / nx]).
std::string certified_map_csv(const CertifiedMap& m, const std::vector<Number>& xs, const std::vector<Number>& ys,
                              const std::vector<CertifiedCell>& cells);

// Scans: the share of the starts of class `show` (none: fixed + periodic, the paper's
// "regular") at each parameter point (viridis), or the paper's black/green look; with
// `fixed_point_curves` the paper's eq. 5 curves over the (a, eps) plane.
ImageFigure scan_figure(const ScanResult& s, std::optional<OrbitClass> show, bool fixed_point_curves, Palette palette);

// Bifurcation diagrams: the density of the orbit points of each column (theta, or v with
// show_theta false) in `bins` rows, the sticking releases in red, and with --certify the
// columns' backgrounds by what the certificate says of double there.
ImageFigure bifurcation_figure(const BifurcationResult& b, bool show_theta, long bins, Palette palette);

}  // namespace bouncer

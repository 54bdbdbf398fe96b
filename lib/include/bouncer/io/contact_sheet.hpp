// A contact sheet: one PNG of thumbnails of many figures, each captioned with its file
// name, so that a reader (or a referee) sees every figure of a run at a glance. Drawn with
// the figures' own Cairo code and font (io/plot.hpp); implemented in lib/src/io/plot.cpp.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace bouncer {

struct ContactSheetOptions {
  int columns = 4;        // thumbnails per row, 1..16
  int thumb_width = 360;  // pixels of each thumbnail's width (its height keeps the aspect), 64..2000
};

// The sheet of `pngs` (PNG files, in this order), left to right and top to bottom, captioned
// with each file's name; written to `out` (staged, then renamed into place). Returns the
// sheet's size in pixels. Throws OutputError when a file cannot be read as PNG or the sheet
// cannot be written, std::invalid_argument for no files or options out of range.
std::pair<int, int> write_contact_sheet(const std::vector<std::string>& pngs, const std::string& out,
                                        const ContactSheetOptions& o = {});

}  // namespace bouncer

// A basin, a parameter scan and a certified basin through the library alone, each written as
// its own small CSV (docs/guide/cmake.md). Built with the project (CI builds it);
// run from any directory, it writes basin.csv, scan.csv and certified.csv there.
#include <bouncer/run/basin.hpp>
#include <bouncer/run/scan.hpp>

#include <fstream>

int main() {
  using namespace bouncer;
  ModelSpec model;  // constant restitution eps = 1/2, a = 24 (the paper's eq. 5 fixed point)
  model.law = Law::constant, model.a = *Decimal::parse("24"), model.eps = *Decimal::parse("0.5");
  model.wall = parse_wall("wall", "triangle");

  BasinRequest b;  // starts over the trapping region, double
  b.model = model;
  b.nx = 40;
  b.ny = 30;
  const BasinResult basins = basin(b);
  std::ofstream basin_csv("basin.csv");
  for (size_t i = 0; i < basins.cells.size(); ++i)
    basin_csv << basins.theta[i % 40].digits << ',' << basins.v[i / 40].digits << ',' << name(basins.cells[i].cls) << '\n';

  // (a, eps) in [20, 30] x [0.3, 0.7]: 12 x 8 points, 4 x 4 starts each; chaotic starts counted
  ScanRequest s;
  s.model = model;
  s.a_lo = *Decimal::parse("20"), s.a_hi = *Decimal::parse("30");
  s.y_lo = *Decimal::parse("0.3"), s.y_hi = *Decimal::parse("0.7");
  s.p = 12, s.q = 8, s.k = 4;
  const ScanResult scans = scan(s);
  std::ofstream scan_csv("scan.csv");
  for (size_t i = 0; i < scans.cells.size(); ++i)
    scan_csv << scans.a[i % 12].digits << ',' << scans.y_values[i / 12].digits << ',' << scans.cells[i][OrbitClass::chaotic] << '\n';

  b.nx = b.ny = 6;  // every pixel a theorem: interval:double, then MPFI up to 256 bits
  const CertifiedBasinResult proved = certified_basin(b);
  std::ofstream certified_csv("certified.csv");
  for (size_t i = 0; i < proved.cells.size(); ++i)
    certified_csv << proved.theta[i % 6].digits << ',' << proved.v[i / 6].digits << ',' << name(proved.cells[i].cls) << ','
                  << name(proved.cells[i].agreement) << '\n';
}

// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
#include "reference.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace reftess {

namespace {

struct Candidate {
  int j, sx, sy;
  double dx, dy, d2;
};

struct Vert {
  double x, y;
  int label;  // candidate index of the side starting at this vertex, -1 = initial square
};

// Clip the convex polygon (relative to the cell's point at the origin) with the
// half-plane d . x <= |d|^2 / 2, the side of the bisector nearer the origin.
std::vector<Vert> clip(const std::vector<Vert> &poly, double dx, double dy, int label) {
  const double c = 0.5 * (dx * dx + dy * dy);
  const size_t n = poly.size();
  std::vector<double> f(n);
  bool any_out = false;
  for (size_t k = 0; k < n; ++k) {
    f[k] = dx * poly[k].x + dy * poly[k].y - c;
    if (f[k] > 0) any_out = true;
  }
  if (!any_out) return poly;
  std::vector<Vert> out;
  out.reserve(n + 1);
  for (size_t k = 0; k < n; ++k) {
    const Vert &a = poly[k];
    const Vert &b = poly[(k + 1) % n];
    const double fa = f[k], fb = f[(k + 1) % n];
    const bool ina = fa <= 0, inb = fb <= 0;
    if (ina) out.push_back(a);
    if (ina != inb) {
      const double t = fa / (fa - fb);
      Vert v{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), 0};
      // Leaving the half-plane: the new side runs along the bisector.
      // Entering it: the rest of the old side a->b starts here.
      v.label = ina ? label : a.label;
      out.push_back(v);
    }
  }
  return out;
}

}  // namespace

RefCell voronoi_cell(const RefBox &box, const std::vector<double> &xy, int i, int shifts) {
  const int n = static_cast<int>(xy.size() / 2);
  const double px = xy[2 * i], py = xy[2 * i + 1];
  std::vector<Candidate> cand;
  cand.reserve(static_cast<size_t>(n) * (2 * shifts + 1) * (2 * shifts + 1));
  for (int j = 0; j < n; ++j) {
    for (int sx = -shifts; sx <= shifts; ++sx) {
      for (int sy = -shifts; sy <= shifts; ++sy) {
        if (j == i && sx == 0 && sy == 0) continue;
        const double dx = xy[2 * j] + sx * box.lx - px;
        const double dy = xy[2 * j + 1] + sy * box.ly - py;
        const double d2 = dx * dx + dy * dy;
        if (!(d2 > 0)) {
          throw std::logic_error("reference: points " + std::to_string(i) + " and " +
                                 std::to_string(j) + " coincide");
        }
        cand.push_back({j, sx, sy, dx, dy, d2});
      }
    }
  }
  std::sort(cand.begin(), cand.end(),
            [](const Candidate &a, const Candidate &b) { return a.d2 < b.d2; });

  const double h = (shifts + 1) * std::max(box.lx, box.ly);
  std::vector<Vert> poly{{-h, -h, -1}, {h, -h, -1}, {h, h, -1}, {-h, h, -1}};
  double maxr2 = 2 * h * h;
  for (size_t c = 0; c < cand.size(); ++c) {
    // A bisector at distance sqrt(d2)/2 cannot cut a polygon within radius sqrt(maxr2).
    if (cand[c].d2 > 4.0 * maxr2 * (1 + 1e-9)) break;
    poly = clip(poly, cand[c].dx, cand[c].dy, static_cast<int>(c));
    maxr2 = 0;
    for (const Vert &v : poly) maxr2 = std::max(maxr2, v.x * v.x + v.y * v.y);
  }

  RefCell cell;
  const size_t m = poly.size();
  double a2 = 0;
  for (size_t k = 0; k < m; ++k) {
    const Vert &a = poly[k];
    const Vert &b = poly[(k + 1) % m];
    if (a.label < 0) {
      throw std::logic_error("reference: cell " + std::to_string(i) +
                             " not closed by its periodic images; use more shifts");
    }
    a2 += a.x * b.y - a.y * b.x;
    const Candidate &cd = cand[static_cast<size_t>(a.label)];
    RefEdge e;
    e.nbr = cd.j;
    e.sx = cd.sx;
    e.sy = cd.sy;
    e.length = std::hypot(b.x - a.x, b.y - a.y);
    cell.perimeter += e.length;
    cell.edges.push_back(e);
    cell.poly.push_back({a.x + px, a.y + py});
  }
  cell.area = 0.5 * a2;
  return cell;
}

std::vector<RefCell> voronoi(const RefBox &box, const std::vector<double> &xy, int shifts) {
  const int n = static_cast<int>(xy.size() / 2);
  std::vector<RefCell> cells;
  cells.reserve(n);
  for (int i = 0; i < n; ++i) cells.push_back(voronoi_cell(box, xy, i, shifts));
  return cells;
}

double cell_energy(const RefCell &c, int i, const std::vector<int> &type, const RefParams &p) {
  const int ti = type[i];
  const int nt = p.ntypes();
  const double da = c.area - p.A0[ti];
  double e = 0.5 * p.K[ti] * da * da + 0.5 * p.Gamma[ti] * c.perimeter * c.perimeter;
  const double w = p.cell_tension ? 1.0 : 0.5;
  for (const RefEdge &ed : c.edges) e += w * p.Lambda[ti * nt + type[ed.nbr]] * ed.length;
  return e;
}

double total_energy(const std::vector<RefCell> &cells, const std::vector<int> &type,
                    const RefParams &p) {
  double e = 0;
  for (size_t i = 0; i < cells.size(); ++i) e += cell_energy(cells[i], static_cast<int>(i), type, p);
  return e;
}

double partial_energy(const RefBox &box, const std::vector<double> &xy,
                      const std::vector<int> &type, const RefParams &p,
                      const std::vector<int> &cells) {
  double e = 0;
  for (int c : cells) e += cell_energy(voronoi_cell(box, xy, c), c, type, p);
  return e;
}

std::vector<int> affected_cells(const std::vector<RefCell> &cells, int i) {
  std::vector<int> out{i};
  for (const RefEdge &e : cells[i].edges) {
    out.push_back(e.nbr);
    for (const RefEdge &e2 : cells[e.nbr].edges) out.push_back(e2.nbr);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace reftess

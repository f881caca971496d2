// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Free-boundary loops of finite cells (tessera/loops.h).

#include "tessera/loops.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace tessera {

namespace {

void arc_end(const FreeArc &a, bool start, double *p)
{
  const double t = start ? a.phi : a.phi + a.theta;
  p[0] = a.cx + a.r * std::cos(t);
  p[1] = a.cy + a.r * std::sin(t);
}

}  // namespace

void append_free_arcs(const CellView &v, const std::int64_t *id, const char *skip,
                      std::vector<FreeArc> &arcs)
{
  auto name = [&](int i) { return id ? id[i] : static_cast<std::int64_t>(i); };
  for (int c = 0; c < v.n_owned(); c++) {
    if (skip && skip[c]) continue;
    const int begin = v.piece_begin(c), end = v.piece_end(c);
    double p[2];
    v.point(c, p);
    for (int k = begin; k < end; k++) {
      FreeArc a;
      if (!v.piece_arc(k, a.phi, a.theta)) continue;
      a.cell = name(c);
      a.cx = p[0];
      a.cy = p[1];
      a.r = v.arc_radius();
      // The junction after the arc in the counter-clockwise boundary (the
      // first piece that is not a free arc, cyclically).
      a.next = a.cell;
      for (int q = 1; q < end - begin; q++) {
        const int j = v.piece_neighbor(begin + (k - begin + q) % (end - begin));
        if (j >= 0) {
          a.next = name(j);
          break;
        }
      }
      arcs.push_back(a);
    }
  }
}

std::vector<FreeLoop> free_loops(const std::vector<FreeArc> &arcs, const MinimumImage &image,
                                 double tol, int *unmatched)
{
  const int n = static_cast<int>(arcs.size());
  std::unordered_map<std::int64_t, std::vector<int>> of_cell;
  for (int a = 0; a < n; a++) of_cell[arcs[a].cell].push_back(a);
  std::vector<char> used(n, 0);
  std::vector<FreeLoop> loops;
  int bad = 0;

  // The arc b nearest to continuing from point e (minimum image) among
  // candidates that are unused or the chain's first arc: its index, the
  // distance and the shift (a box vector, 0 in an open box) that brings b's
  // start next to e.
  auto nearest = [&](const std::vector<int> &cand, const double *e, int first, double &dist,
                     double *shift) {
    int best = -1;
    dist = std::numeric_limits<double>::infinity();
    for (int b : cand) {
      if (used[b] && b != first) continue;
      double s[2], d[2];
      arc_end(arcs[b], true, s);
      d[0] = s[0] - e[0];
      d[1] = s[1] - e[1];
      double m[2] = {d[0], d[1]};
      if (image) image(m);
      const double r = std::hypot(m[0], m[1]);
      if (r < dist) {
        dist = r;
        best = b;
        shift[0] = m[0] - d[0];
        shift[1] = m[1] - d[1];
      }
    }
    return best;
  };

  std::vector<int> everything(n);
  for (int a = 0; a < n; a++) everything[a] = a;
  std::vector<int> chain;
  std::vector<double> offset;    // per chain member, its shift (2 values)
  for (int first = 0; first < n; first++) {
    if (used[first]) continue;
    chain.assign(1, first);
    offset.assign(2, 0.0);
    used[first] = 1;
    double closing[2] = {0.0, 0.0};
    while (true) {
      const int a = chain.back();
      const double oa[2] = {offset[offset.size() - 2], offset[offset.size() - 1]};
      double e[2];
      arc_end(arcs[a], false, e);
      double dist, shift[2];
      int b = -1;
      auto it = of_cell.find(arcs[a].next);
      if (it != of_cell.end()) b = nearest(it->second, e, first, dist, shift);
      if (b < 0 || dist > tol) {
        b = nearest(everything, e, first, dist, shift);
        if (b < 0 || dist > tol) {
          bad++;
          break;
        }
      }
      if (b == first) {
        closing[0] = oa[0] + shift[0];
        closing[1] = oa[1] + shift[1];
        break;
      }
      used[b] = 1;
      chain.push_back(b);
      offset.push_back(oa[0] + shift[0]);
      offset.push_back(oa[1] + shift[1]);
    }

    FreeLoop loop;
    loop.n_arcs = static_cast<int>(chain.size());
    std::vector<std::int64_t> cells;
    // Shoelace over the corners (start and end of each arc, unwrapped), plus
    // each arc's circular segment beyond its chord: the signed area and
    // first moments of the region the loop encloses.
    double area = 0.0, mx = 0.0, my = 0.0, sx = 0.0, sy = 0.0;
    std::vector<double> corner;
    for (size_t k = 0; k < chain.size(); k++) {
      const FreeArc &c = arcs[chain[k]];
      double s[2], e[2];
      arc_end(c, true, s);
      arc_end(c, false, e);
      for (int d = 0; d < 2; d++) {
        s[d] += offset[2 * k + d];
        e[d] += offset[2 * k + d];
      }
      corner.insert(corner.end(), {s[0], s[1], e[0], e[1]});
      loop.length += c.r * c.theta;
      cells.push_back(c.cell);
      const double seg = 0.5 * c.r * c.r * (c.theta - std::sin(c.theta));
      const double h = std::sin(0.5 * c.theta);
      const double arm = 2.0 / 3.0 * c.r * c.r * c.r * h * h * h;
      const double mid = c.phi + 0.5 * c.theta;
      const double ccx = c.cx + offset[2 * k], ccy = c.cy + offset[2 * k + 1];
      area += seg;
      mx += seg * ccx + arm * std::cos(mid);
      my += seg * ccy + arm * std::sin(mid);
      sx += ccx + c.r * std::cos(mid);
      sy += ccy + c.r * std::sin(mid);
    }
    const size_t m = corner.size() / 2;
    for (size_t q = 0; q < m; q++) {
      const double *p = &corner[2 * q], *r = &corner[2 * ((q + 1) % m)];
      const double cr = p[0] * r[1] - r[0] * p[1];
      area += 0.5 * cr;
      mx += (p[0] + r[0]) * cr / 6.0;
      my += (p[1] + r[1]) * cr / 6.0;
    }
    std::sort(cells.begin(), cells.end());
    loop.n_cells = static_cast<int>(std::unique(cells.begin(), cells.end()) - cells.begin());
    const double r0 = arcs[first].r;
    if (std::hypot(closing[0], closing[1]) > 1e-3 * r0) {
      loop.kind = LoopKind::Wrapping;
      loop.area = 0.0;
      loop.cx = sx / loop.n_arcs;
      loop.cy = sy / loop.n_arcs;
    } else {
      loop.kind = area >= 0.0 ? LoopKind::Outer : LoopKind::Hole;
      loop.area = std::fabs(area);
      loop.cx = area != 0.0 ? mx / area : sx / loop.n_arcs;
      loop.cy = area != 0.0 ? my / area : sy / loop.n_arcs;
    }
    loops.push_back(loop);
  }
  if (unmatched) *unmatched = bad;
  return loops;
}

}  // namespace tessera

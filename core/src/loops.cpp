// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Free-boundary loops of finite cells (tessera/loops.h).

#include "tessera/loops.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

namespace tessera {

namespace {

void arc_end(const FreeArc &a, bool start, double *p)
{
  const double t = start ? a.phi : a.phi + a.theta;
  p[0] = a.cx + a.r * std::cos(t);
  p[1] = a.cy + a.r * std::sin(t);
}

// > 0 when p is left of the line from a to b.
double side(const double *a, const double *b, const double *p)
{
  return (b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1]);
}

// The edge a -> b's share of the winding number about p: it crosses the ray
// from p towards +x upwards with p on its left (+1) or downwards with p on
// its right (-1); half-open in y, so that a vertex on the ray counts once.
int crossing(const double *a, const double *b, const double *p)
{
  if (a[1] <= p[1]) return (b[1] > p[1] && side(a, b, p) > 0.0) ? 1 : 0;
  return (b[1] <= p[1] && side(a, b, p) < 0.0) ? -1 : 0;
}

// Arc a's share: its chord, the link from its end to the next arc's start
// (a round-off gap), and +1 when p lies between the arc and its chord.  An
// arc runs counter-clockwise about its centre, so it lies right of its
// chord; a whole circle (an isolated cell) has no chord and encloses its disc.
int arc_winding(const FreeArc &a, const FreeArc &next, const double *p)
{
  double s[2], e[2], t[2];
  arc_end(a, true, s);
  arc_end(a, false, e);
  arc_end(next, true, t);
  int w = crossing(s, e, p) + crossing(e, t, p);
  const double dx = p[0] - a.cx, dy = p[1] - a.cy;
  if (dx * dx + dy * dy < a.r * a.r) {
    constexpr double two_pi = 6.283185307179586;
    if (a.theta >= two_pi * (1.0 - 1e-14) || side(s, e, p) < 0.0) w += 1;
  }
  return w;
}

// The y range an arc's share can be non-zero in: its disc and the link's end.
void arc_y_range(const FreeArc &a, const FreeArc &next, double &lo, double &hi)
{
  double t[2];
  arc_end(next, true, t);
  lo = std::min(a.cy - a.r, t[1]);
  hi = std::max(a.cy + a.r, t[1]);
}

// floor(v) as an int, v clamped to a range that cannot overflow.
int floor_int(double v)
{
  return static_cast<int>(std::floor(std::max(-1e9, std::min(1e9, v))));
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
    loop.arcs = chain;
    loop.shift = offset;
    loops.push_back(std::move(loop));
  }
  if (unmatched) *unmatched = bad;
  return loops;
}

std::vector<FreeArc> unwrapped_arcs(const std::vector<FreeArc> &arcs, const FreeLoop &loop)
{
  std::vector<FreeArc> out;
  out.reserve(loop.arcs.size());
  for (size_t k = 0; k < loop.arcs.size(); k++) {
    FreeArc a = arcs[loop.arcs[k]];
    a.cx += loop.shift[2 * k];
    a.cy += loop.shift[2 * k + 1];
    out.push_back(a);
  }
  return out;
}

int loop_winding(const FreeArc *arcs, int n, const double *p)
{
  int w = 0;
  for (int k = 0; k < n; k++) w += arc_winding(arcs[k], arcs[(k + 1) % n], p);
  return w;
}

void LoopLocator::add(const FreeArc *arcs, int n, double area, bool wrapping)
{
  Loop l;
  l.arcs.assign(arcs, arcs + n);
  l.area = area;
  l.wrapping = wrapping;
  if (n == 0) {
    l.wrapping = true;    // nothing to enclose with
    loops_.push_back(std::move(l));
    return;
  }
  std::vector<double> ylo(n), yhi(n);
  l.lo[0] = l.lo[1] = std::numeric_limits<double>::infinity();
  l.hi[0] = l.hi[1] = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < n; k++) {
    const FreeArc &a = arcs[k];
    arc_y_range(a, arcs[(k + 1) % n], ylo[k], yhi[k]);
    l.lo[0] = std::min(l.lo[0], a.cx - a.r);
    l.hi[0] = std::max(l.hi[0], a.cx + a.r);
    l.lo[1] = std::min(l.lo[1], ylo[k]);
    l.hi[1] = std::max(l.hi[1], yhi[k]);
  }
  // (the links' x: within round-off of a disc; widen by a hair)
  const double pad = 1e-9 * (l.hi[0] - l.lo[0]);
  l.lo[0] -= pad;
  l.hi[0] += pad;
  // Bands of y, about two arcs each for a round loop.
  l.nband = std::max(1, std::min(4096, n / 2));
  const double h = (l.hi[1] - l.lo[1]) / l.nband;
  auto band = [&](double y) {
    return h > 0.0 ? std::max(0, std::min(l.nband - 1, floor_int((y - l.lo[1]) / h))) : 0;
  };
  l.band_start.assign(l.nband + 1, 0);
  for (int k = 0; k < n; k++)
    for (int b = band(ylo[k]); b <= band(yhi[k]); b++) l.band_start[b + 1]++;
  for (int b = 0; b < l.nband; b++) l.band_start[b + 1] += l.band_start[b];
  l.band_arcs.resize(l.band_start[l.nband]);
  std::vector<int> fill(l.band_start.begin(), l.band_start.end() - 1);
  for (int k = 0; k < n; k++)
    for (int b = band(ylo[k]); b <= band(yhi[k]); b++) l.band_arcs[fill[b]++] = k;
  loops_.push_back(std::move(l));
}

int LoopLocator::winding(int index, const double *p) const
{
  const Loop &l = loops_[index - 1];
  const int n = static_cast<int>(l.arcs.size());
  if (n == 0 || p[0] < l.lo[0] || p[0] > l.hi[0] || p[1] < l.lo[1] || p[1] > l.hi[1]) return 0;
  const double h = (l.hi[1] - l.lo[1]) / l.nband;
  const int b = h > 0.0 ? std::max(0, std::min(l.nband - 1, floor_int((p[1] - l.lo[1]) / h))) : 0;
  int w = 0;
  for (int q = l.band_start[b]; q < l.band_start[b + 1]; q++) {
    const int k = l.band_arcs[q];
    w += arc_winding(l.arcs[k], l.arcs[(k + 1) % n], p);
  }
  return w;
}

void LoopLocator::fraction(const double *p, double *s) const
{
  s[1] = (p[1] - box_.lo[1]) / box_.len[1];
  s[0] = (p[0] - box_.lo[0] - box_.xy * s[1]) / box_.len[0];
}

void LoopLocator::bin_range(double s0, double s1, int d, std::vector<int> &out) const
{
  const int nb = nbin_[d];
  int i0 = floor_int(s0 * nb), i1 = floor_int(s1 * nb);
  out.clear();
  if (box_.periodic[d]) {
    if (i1 - i0 + 1 >= nb) {
      i0 = 0;
      i1 = nb - 1;
    }
    for (int i = i0; i <= i1; i++) out.push_back(((i % nb) + nb) % nb);
  } else {
    i0 = std::max(0, std::min(nb - 1, i0));
    i1 = std::max(0, std::min(nb - 1, i1));
    for (int i = i0; i <= i1; i++) out.push_back(i);
  }
}

void LoopLocator::finish()
{
  const int n = size();
  const int nb = std::max(1, std::min(1024, static_cast<int>(std::ceil(std::sqrt(n)))));
  nbin_[0] = nbin_[1] = nb;
  // Each loop in the bins its bounding box covers, in fractional
  // coordinates of the box (for a tilted box: the hull of its corners').
  std::vector<std::vector<int>> bins(static_cast<size_t>(nb) * nb);
  std::vector<int> rx, ry;
  for (int l = 0; l < n; l++) {
    const Loop &loop = loops_[l];
    if (loop.wrapping) continue;
    double slo[2] = {std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::infinity()};
    double shi[2] = {-slo[0], -slo[1]};
    for (int c = 0; c < 4; c++) {
      const double corner[2] = {c & 1 ? loop.hi[0] : loop.lo[0], c & 2 ? loop.hi[1] : loop.lo[1]};
      double s[2];
      fraction(corner, s);
      for (int d = 0; d < 2; d++) {
        slo[d] = std::min(slo[d], s[d]);
        shi[d] = std::max(shi[d], s[d]);
      }
    }
    bin_range(slo[0], shi[0], 0, rx);
    bin_range(slo[1], shi[1], 1, ry);
    for (int j : ry)
      for (int i : rx) bins[static_cast<size_t>(j) * nb + i].push_back(l);
  }
  bin_start_.assign(bins.size() + 1, 0);
  for (size_t b = 0; b < bins.size(); b++)
    bin_start_[b + 1] = bin_start_[b] + static_cast<int>(bins[b].size());
  bin_loops_.clear();
  bin_loops_.reserve(bin_start_.back());
  for (const auto &b : bins) bin_loops_.insert(bin_loops_.end(), b.begin(), b.end());
}

int LoopLocator::innermost(const double *p) const
{
  double s[2];
  fraction(p, s);
  int idx[2];
  for (int d = 0; d < 2; d++) {
    if (box_.periodic[d]) s[d] -= std::floor(s[d]);
    idx[d] = std::max(0, std::min(nbin_[d] - 1, floor_int(s[d] * nbin_[d])));
  }
  const int b = idx[1] * nbin_[0] + idx[0];
  int best = 0;
  double best_area = 0.0;
  for (int q = bin_start_[b]; q < bin_start_[b + 1]; q++) {
    const int l = bin_loops_[q];
    const Loop &loop = loops_[l];
    if (best && !(loop.area < best_area)) continue;
    // The images of p in the loop's bounding box (a loop that does not wrap
    // holds at most one of them).
    int m0 = 0, m1 = 0;
    if (box_.periodic[1]) {
      m0 = floor_int(std::ceil((loop.lo[1] - p[1]) / box_.len[1]));
      m1 = floor_int(std::floor((loop.hi[1] - p[1]) / box_.len[1]));
    }
    bool inside = false;
    for (int m = m0; m <= m1 && m - m0 < 64 && !inside; m++) {
      const double y = p[1] + m * box_.len[1], x0 = p[0] + m * box_.xy;
      int n0 = 0, n1 = 0;
      if (box_.periodic[0]) {
        n0 = floor_int(std::ceil((loop.lo[0] - x0) / box_.len[0]));
        n1 = floor_int(std::floor((loop.hi[0] - x0) / box_.len[0]));
      }
      for (int k = n0; k <= n1 && k - n0 < 64 && !inside; k++) {
        const double image[2] = {x0 + k * box_.len[0], y};
        inside = winding(l + 1, image) != 0;
      }
    }
    if (inside) {
      best = l + 1;
      best_area = loop.area;
    }
  }
  return best;
}

}  // namespace tessera

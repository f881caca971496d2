// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Finite Voronoi cells by clipping: each cell starts as its disc and is cut by
// the bisector half-plane of every point closer than 2 r, nearest first.  The
// boundary is kept as counter-clockwise pieces (contact edges on a bisector,
// arcs of the cell's circle kept as angle intervals, so an arc's span never
// wraps by round-off).  Forces: every corner of the boundary is fixed by two
// constraints (two bisectors: a Voronoi vertex; or a bisector and the circle:
// where two circles of radius r cross), and the gradient on a corner is
// pushed onto the centres through the transpose of its 2x2 constraint system
// (doc/model.md, "Finite Voronoi cells").

#include "tessera/finite.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <utility>

namespace tessera {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline Vec2 sub(Vec2 a, Vec2 b) { return Vec2{a.x - b.x, a.y - b.y}; }
inline Vec2 add(Vec2 a, Vec2 b) { return Vec2{a.x + b.x, a.y + b.y}; }
inline Vec2 scale(Vec2 a, double s) { return Vec2{a.x * s, a.y * s}; }

// Angle offset of `angle` from `from`, in [0, 2 pi).
inline double offset(double angle, double from) {
  double t = std::fmod(angle - from, kTwoPi);
  if (t < 0.0) t += kTwoPi;
  if (t >= kTwoPi) t = 0.0;
  return t;
}

// t is an offset in [0, 2 pi) that should lie in [lo, hi] (round-off may
// have put it just outside, possibly wrapped): the nearer end.
inline double clamp_offset(double t, double lo, double hi) {
  if (t >= lo && t <= hi) return t;
  // Distances on the circle to lo and hi.
  auto circ = [](double a, double b) {
    double d = std::fabs(a - b);
    return std::min(d, kTwoPi - d);
  };
  return circ(t, lo) <= circ(t, hi) ? lo : hi;
}

std::string point_name(int i, const long *ids) {
  std::ostringstream s;
  if (ids)
    s << "id " << ids[i];
  else
    s << "point " << i;
  return s.str();
}

// Cut the cell (pieces relative to its centre) by the bisector half-plane
// of a point at relative position D with index j.  Returns false if the
// pieces did not give one exit and one entry (round-off at a degenerate
// corner); the caller then retries with another tolerance.
bool clip(std::vector<FinitePiece> &cell, int j, Vec2 D, double r, double tol_s,
          std::vector<FinitePiece> &out) {
  const double d2 = dot(D, D);
  const double h2 = 0.25 * (4.0 * r * r - d2);
  if (!(h2 > kFiniteTouchTol * kFiniteTouchTol * r * r)) return true;  // too far to touch
  const double d = std::sqrt(d2), half = 0.5 * d, h = std::sqrt(h2);
  const Vec2 e{D.x / d, D.y / d};
  const Vec2 tp{-e.y, e.x};
  const Vec2 u1 = sub(scale(e, half), scale(tp, h));  // the circle leaves the half-plane
  const Vec2 u2 = add(scale(e, half), scale(tp, h));  // and re-enters it
  const double phi_e = std::atan2(e.y, e.x);
  const double alpha = std::atan2(h, half);
  const double phi1 = phi_e - alpha, phi2 = phi_e + alpha;

  if (cell.size() == 1 && cell[0].neighbor < 0) {  // the whole disc
    out.clear();
    FinitePiece seg;
    seg.neighbor = j;
    seg.start = u1;
    FinitePiece arc;
    arc.start = u2;
    arc.phi = phi2;
    arc.theta = kTwoPi - 2.0 * alpha;
    out.push_back(seg);
    out.push_back(arc);
    cell.swap(out);
    return true;
  }

  const int n = static_cast<int>(cell.size());
  auto s_of = [&](Vec2 u) { return dot(u, e) - half; };
  out.clear();
  int exits = 0, entries = 0, exit_after = -1, entry_index = -1;
  Vec2 exit_point{};
  auto mark_exit = [&](Vec2 q) {
    exits++;
    exit_after = static_cast<int>(out.size()) - 1;
    exit_point = q;
  };
  auto push_entry = [&](FinitePiece p) {
    entries++;
    out.push_back(p);
    entry_index = static_cast<int>(out.size()) - 1;
  };
  for (int k = 0; k < n; ++k) {
    const FinitePiece &p = cell[k];
    const Vec2 a = p.start, b = cell[(k + 1) % n].start;
    const double sa = s_of(a), sb = s_of(b);
    const bool ina = sa <= tol_s, inb = sb <= tol_s;
    if (p.neighbor >= 0) {
      if (ina && inb) {
        out.push_back(p);
      } else if (ina != inb) {
        double f = sa / (sa - sb);
        f = std::min(1.0, std::max(0.0, f));
        const Vec2 q = add(a, scale(sub(b, a), f));
        if (ina) {
          out.push_back(p);
          mark_exit(q);
        } else {
          FinitePiece np = p;
          np.start = q;
          push_entry(np);
        }
      }
      continue;
    }
    // An arc from angle phi over theta.
    const double phi = p.phi, th = p.theta;
    auto sub_arc = [&](Vec2 start, double t0, double t1) {
      FinitePiece np;
      np.start = start;
      np.phi = phi + t0;
      np.theta = std::max(0.0, t1 - t0);
      return np;
    };
    if (ina && !inb) {
      const double t1 = clamp_offset(offset(phi1, phi), 0.0, th);
      out.push_back(sub_arc(a, 0.0, t1));
      mark_exit(u1);
    } else if (!ina && inb) {
      const double t2 = clamp_offset(offset(phi2, phi), 0.0, th);
      push_entry(sub_arc(u2, t2, th));
    } else if (ina && inb) {
      const double tc = offset(phi_e, phi);
      if (tc < th) {  // the arc bulges across the line: cut the bulge off
        const double t1 = clamp_offset(offset(phi1, phi), 0.0, tc);
        const double t2 = clamp_offset(offset(phi2, phi), tc, th);
        out.push_back(sub_arc(a, 0.0, t1));
        mark_exit(u1);
        push_entry(sub_arc(u2, t2, th));
      } else {
        out.push_back(p);
      }
    } else {
      const double ti = offset(phi_e + 0.5 * kTwoPi, phi);
      if (ti < th) {  // both ends outside, the middle inside
        const double t2 = clamp_offset(offset(phi2, phi), 0.0, ti);
        const double t1 = clamp_offset(offset(phi1, phi), ti, th);
        push_entry(sub_arc(u2, t2, t1));
        mark_exit(u1);
      }
    }
  }
  if (exits == 0 && entries == 0) {
    if (out.empty()) return false;  // cannot happen: the centre is inside
    return true;                    // untouched (out == cell)
  }
  const int m = static_cast<int>(out.size());
  if (exits != 1 || entries != 1 || m == 0 || entry_index != (exit_after + 1) % m) return false;
  FinitePiece chord;
  chord.neighbor = j;
  chord.start = exit_point;
  out.insert(out.begin() + (exit_after + 1), chord);
  // Neighbouring arcs (a chord that vanished) become one.
  cell.clear();
  for (const FinitePiece &p : out) {
    if (!cell.empty() && p.neighbor < 0 && cell.back().neighbor < 0)
      cell.back().theta += p.theta;
    else
      cell.push_back(p);
  }
  if (cell.size() > 1 && cell.front().neighbor < 0 && cell.back().neighbor < 0) {
    cell.back().theta += cell.front().theta;
    cell.erase(cell.begin());
  }
  return true;
}

// Points binned on a grid of spacing at least 2 r (sorted by bin), for the
// neighbours within 2 r.  Any finite input is safe: the bin size grows so
// that there are at most kMaxBins bins along an axis (points far apart then
// share bins, which costs time, not correctness: two points within 2 r are
// still in the same or adjacent bins), bin indices are clamped to
// [0, kMaxBins] before the conversion to an integer, and keys are unsigned.
struct Grid {
  static constexpr double kMaxBins = 1 << 20;
  double x0 = 0.0, y0 = 0.0, sx = 1.0, sy = 1.0;
  std::vector<std::pair<uint64_t, int>> keyed;
  // Bins -1 .. kMaxBins + 1 (near() looks one beyond) shifted to 0 ..
  static uint64_t key(long long bx, long long by) {
    return (static_cast<uint64_t>(bx + 1) << 32) | static_cast<uint64_t>(by + 1);
  }
  // Bin size along one axis for coordinates lo .. hi (halved first, so
  // that hi - lo cannot overflow).
  static double spacing(double lo, double hi, double s) {
    const double per_bin = (0.5 * hi - 0.5 * lo) / (0.5 * kMaxBins);
    return std::max(s, per_bin);
  }
  void build(const Points &pts, double s) {
    x0 = pts.x(0);
    y0 = pts.y(0);
    double x1 = x0, y1 = y0;
    for (int i = 1; i < pts.n; ++i) {
      x0 = std::min(x0, pts.x(i));
      y0 = std::min(y0, pts.y(i));
      x1 = std::max(x1, pts.x(i));
      y1 = std::max(y1, pts.y(i));
    }
    sx = spacing(x0, x1, s);
    sy = spacing(y0, y1, s);
    keyed.resize(pts.n);
    for (int i = 0; i < pts.n; ++i)
      keyed[i] = {key(bin(pts.x(i), x0, sx), bin(pts.y(i), y0, sy)), i};
    std::sort(keyed.begin(), keyed.end());
  }
  static long long bin(double v, double v0, double s) {
    // v - v0 may overflow to +inf (then the last bin); s may be +inf (bin 0).
    const double q = std::floor((v - v0) / s);
    if (!(q > 0.0)) return 0;  // also NaN (inf / inf)
    return static_cast<long long>(std::min(q, kMaxBins));
  }
  template <class F>
  void near(double x, double y, F &&visit) const {
    const long long bx = bin(x, x0, sx), by = bin(y, y0, sy);
    for (long long ix = bx - 1; ix <= bx + 1; ++ix)
      for (long long iy = by - 1; iy <= by + 1; ++iy) {
        const uint64_t k = key(ix, iy);
        auto it = std::lower_bound(keyed.begin(), keyed.end(), std::make_pair(k, -1));
        for (; it != keyed.end() && it->first == k; ++it) visit(it->second);
      }
  }
};

// Input limits, as for the confluent model (doc/model.md, "Limits of the
// input"): lengths within [kMinLength, kMaxLength] so that squares and
// products of lengths neither underflow nor overflow, and two centres closer
// than kMinSeparation times their coordinates' magnitude refused (the
// bisector between them is round-off).  The magnitude is that of the pair
// itself, not of the whole input: a finite cell depends only on points
// within 2 r, which are translated exactly (an image or ghost is rounded to
// its own coordinates' precision).
constexpr double kMinSeparation = 1e-10;
constexpr double kMinLength = 1e-100;
constexpr double kMaxLength = 1e100;

void check_radius(double radius) {
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    std::ostringstream s;
    s << "tessera: finite Voronoi radius must be positive and finite, got " << radius;
    throw Error(s.str());
  }
  if (radius < kMinLength || radius > kMaxLength) {
    std::ostringstream s;
    s << "tessera: finite Voronoi radius " << radius << " is outside [" << kMinLength << ", "
      << kMaxLength
      << "]: areas (r^2) would underflow or overflow double precision; rescale the length unit";
    throw Error(s.str());
  }
}

[[noreturn]] void throw_too_close(const Points &pts, int c, int j, const long *ids, double lim) {
  std::ostringstream s;
  s.precision(17);
  s << "tessera: two cell centres nearly coincide: " << point_name(c, ids) << " at (" << pts.x(c)
    << ", " << pts.y(c) << ") and " << point_name(j, ids) << " at (" << pts.x(j) << ", "
    << pts.y(j) << ") are " << std::hypot(pts.x(j) - pts.x(c), pts.y(j) - pts.y(c))
    << " apart, closer than " << lim;
  if (lim > kMinLength)
    s << " (" << kMinSeparation
      << " times their coordinates' magnitude): double precision cannot resolve the cell "
         "boundary between them; move or delete one of them";
  else
    s << ": lengths this small underflow in double precision; rescale the length unit";
  throw Error(s.str());
}

}  // namespace

FiniteTessellation finite_tessellate(const Points &pts, int n_owned, double radius,
                                     const long *ids) {
  check_radius(radius);
  if (n_owned < 0 || n_owned > pts.n) throw Error("tessera: n_owned out of range");
  for (int i = 0; i < pts.n; ++i) {
    if (!std::isfinite(pts.x(i)) || !std::isfinite(pts.y(i)))
      throw Error("tessera: non-finite coordinates of " + point_name(i, ids));
    if (std::max(std::fabs(pts.x(i)), std::fabs(pts.y(i))) > kMaxLength) {
      std::ostringstream s;
      s.precision(17);
      s << "tessera: " << point_name(i, ids) << " at (" << pts.x(i) << ", " << pts.y(i)
        << ") is beyond " << kMaxLength
        << " in magnitude: squares of lengths would overflow double precision; rescale the "
           "length unit";
      throw Error(s.str());
    }
  }

  const double r = radius;
  FiniteTessellation t;
  t.n_points = pts.n;
  t.n_owned = n_owned;
  t.radius = r;
  t.cell_offset.assign(1, 0);
  t.area.resize(n_owned);
  t.perimeter.resize(n_owned);
  t.free_length.resize(n_owned);
  if (pts.n == 0) return t;

  Grid grid;
  grid.build(pts, 2.0 * r);
  std::vector<std::pair<double, int>> cand;
  std::vector<FinitePiece> cell, scratch, backup;
  const double reach2 = 4.0 * r * r;
  for (int c = 0; c < n_owned; ++c) {
    const double cx = pts.x(c), cy = pts.y(c);
    cand.clear();
    grid.near(cx, cy, [&](int j) {
      if (j == c) return;
      const double dx = pts.x(j) - cx, dy = pts.y(j) - cy;
      const double d2 = dx * dx + dy * dy;
      if (d2 < reach2) {
        const double mag = std::max({std::fabs(cx), std::fabs(cy), std::fabs(pts.x(j)),
                                     std::fabs(pts.y(j))});
        const double lim = std::max(kMinSeparation * mag, kMinLength);
        if (d2 < lim * lim) throw_too_close(pts, c, j, ids, lim);
        cand.push_back({d2, j});
      }
    });
    std::sort(cand.begin(), cand.end());
    cell.assign(1, FinitePiece{});
    cell[0].start = Vec2{r, 0.0};
    cell[0].phi = 0.0;
    cell[0].theta = kTwoPi;
    for (const auto &dj : cand) {
      const int j = dj.second;
      const Vec2 D{pts.x(j) - cx, pts.y(j) - cy};
      backup = cell;
      if (clip(cell, j, D, r, 1e-12 * r, scratch)) continue;
      cell = backup;
      if (clip(cell, j, D, r, 0.0, scratch)) continue;
      cell = backup;
      if (clip(cell, j, D, r, 1e-9 * r, scratch)) continue;
      throw Error("tessera: finite Voronoi cell of " + point_name(c, ids) +
                  " could not be cut consistently by " + point_name(j, ids));
    }
    // Lengths, area, perimeter, free length; starts to absolute positions.
    const int m = static_cast<int>(cell.size());
    double area = 0.0, per = 0.0, free = 0.0;
    for (int k = 0; k < m; ++k) {
      FinitePiece &p = cell[k];
      const Vec2 a = p.start, b = cell[(k + 1) % m].start;
      if (p.neighbor >= 0) {
        p.length = std::hypot(b.x - a.x, b.y - a.y);
        area += 0.5 * cross(a, b);
      } else {
        p.length = r * p.theta;
        area += 0.5 * r * r * p.theta;
        free += p.length;
      }
      per += p.length;
    }
    for (FinitePiece &p : cell) p.start = Vec2{p.start.x + cx, p.start.y + cy};
    t.area[c] = area;
    t.perimeter[c] = per;
    t.free_length[c] = free;
    t.pieces.insert(t.pieces.end(), cell.begin(), cell.end());
    t.cell_offset.push_back(static_cast<int>(t.pieces.size()));
  }
  return t;
}

FiniteTessellation finite_tessellate_periodic(const Box &box, const Points &pts, double radius,
                                              const long *ids) {
  box.validate();
  check_radius(radius);
  const double lx = box.length(0), ly = box.length(1), xy = box.xy;
  // Margins in fractional coordinates: 2 r over the distance between the
  // lattice lines of each family.
  const double my = 2.0 * radius / ly;
  const double mx = 2.0 * radius * std::sqrt(ly * ly + xy * xy) / (lx * ly);
  const int nx = static_cast<int>(std::ceil(mx)) + 1, ny = static_cast<int>(std::ceil(my)) + 1;
  std::vector<double> all;
  std::vector<int> origin;
  all.reserve(2 * static_cast<size_t>(pts.n));
  for (int i = 0; i < pts.n; ++i) {
    all.push_back(pts.x(i));
    all.push_back(pts.y(i));
    origin.push_back(i);
  }
  for (int i = 0; i < pts.n; ++i) {
    const double fy = (pts.y(i) - box.lo[1]) / ly;
    const double fx = (pts.x(i) - box.lo[0] - fy * xy) / lx;
    for (int a = -nx; a <= nx; ++a)
      for (int b = -ny; b <= ny; ++b) {
        if (a == 0 && b == 0) continue;
        const double gx = fx + a, gy = fy + b;
        if (gx < -mx || gx > 1.0 + mx || gy < -my || gy > 1.0 + my) continue;
        all.push_back(pts.x(i) + a * lx + b * xy);
        all.push_back(pts.y(i) + b * ly);
        origin.push_back(i);
      }
  }
  std::vector<long> report;
  if (ids) {
    report.resize(origin.size());
    for (size_t k = 0; k < origin.size(); ++k) report[k] = ids[origin[k]];
  }
  const Points p{all.data(), static_cast<int>(origin.size()), 2};
  FiniteTessellation t = finite_tessellate(p, pts.n, radius, ids ? report.data() : nullptr);
  t.origin = std::move(origin);
  t.position.resize(t.origin.size());
  for (size_t k = 0; k < t.origin.size(); ++k) t.position[k] = Vec2{all[2 * k], all[2 * k + 1]};
  return t;
}

std::vector<double> positions_of(const FiniteTessellation &t) {
  std::vector<double> xy(2 * t.position.size());
  for (size_t k = 0; k < t.position.size(); ++k) {
    xy[2 * k] = t.position[k].x;
    xy[2 * k + 1] = t.position[k].y;
  }
  return xy;
}

namespace {

[[noreturn]] void throw_total_overflow(double e) {
  std::ostringstream s;
  s << "tessera: the total energy or virial of the finite cells is not finite (" << e
    << ", every cell's being finite): the parameters are far outside reduced units; rescale "
       "the units (length, energy)";
  throw Error(s.str());
}

// Energies or forces beyond double's range: an Error naming the cell (its
// owner for an image) and the value, never inf or NaN.
[[noreturn]] void throw_overflow(const FiniteTessellation &t, int c, const char *what,
                                 double value) {
  std::ostringstream s;
  s.precision(17);
  const int o = t.origin.empty() ? c : t.origin[c];
  s << "tessera: the " << what << " of the finite cell of point " << o << " is not finite ("
    << value << "; its area " << t.area[c] << ", perimeter " << t.perimeter[c]
    << "): the parameters are far outside reduced units; rescale the units (length, energy) "
       "so that K A0^2, Gamma P^2, Lambda P and F P stay well below 1e300";
  throw Error(s.str());
}

double cell_energy_of(const FiniteTessellation &t, int c, const int *type, const Model &m,
                      const double *free_tension) {
  const Model::CellParams ct = m.cell_params(c, type[c]);
  const double dA = t.area[c] - ct.A0;
  double e = 0.5 * ct.K * dA * dA + 0.5 * ct.Gamma * t.perimeter[c] * t.perimeter[c] +
             ct.shift * t.perimeter[c];
  double tension = 0.0;
  for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k) {
    const FinitePiece &p = t.pieces[k];
    if (p.neighbor >= 0) tension += m.lambda_of(type[c], type[p.neighbor]) * p.length;
  }
  e += m.tension_weight() * tension;
  if (free_tension) e += free_tension[type[c]] * t.free_length[c];
  if (!std::isfinite(e)) throw_overflow(t, c, "energy", e);
  return e;
}

}  // namespace

double finite_energy(const FiniteTessellation &t, const int *type, const Model &model,
                     const double *free_tension, double *cell_energy) {
  double e = 0.0;
  for (int c = 0; c < t.n_owned; ++c) {
    const double ec = cell_energy_of(t, c, type, model, free_tension);
    if (cell_energy) cell_energy[c] = ec;
    e += ec;
  }
  if (!std::isfinite(e)) throw_total_overflow(e);
  return e;
}

ForceOutput finite_forces(const FiniteTessellation &t, const Points &pts, const int *type,
                          const Model &model, const double *free_tension, double *f,
                          int f_stride, double *cell_energy, double *cell_virial) {
  ForceOutput out;
  const double r = t.radius;
  const double w = model.tension_weight();
  std::vector<Vec2> u, G;
  // Gradient of the cell's energy on the points it depends on: (point, dE/dx).
  std::vector<std::pair<int, Vec2>> grad;
  for (int c = 0; c < t.n_owned; ++c) {
    const int o = t.cell_offset[c], m = t.cell_size(c);
    const double ec = cell_energy_of(t, c, type, model, free_tension);
    if (cell_energy) cell_energy[c] = ec;
    out.energy += ec;
    if (cell_virial)
      for (int q = 0; q < 4; ++q) cell_virial[4 * c + q] = 0.0;
    if (m <= 1) continue;  // a whole disc: its energy does not depend on its position

    const Vec2 xc{pts.x(c), pts.y(c)};
    // Per-cell KA, KP, P0 (Model::cell_params): shift_c P over the whole
    // perimeter, so contact edges and free arcs both carry it.
    const Model::CellParams ct = model.cell_params(c, type[c]);
    const double wA = ct.K * (t.area[c] - ct.A0);
    const double wP = ct.Gamma * t.perimeter[c] + ct.shift;
    const double wF = wP + (free_tension ? free_tension[type[c]] : 0.0);
    u.resize(m);
    G.assign(m, Vec2{});
    for (int k = 0; k < m; ++k) u[k] = sub(t.pieces[o + k].start, xc);
    // dE/du_k for the corners u_k relative to the centre.
    for (int k = 0; k < m; ++k) {
      const FinitePiece &p = t.pieces[o + k];
      const int k1 = (k + 1) % m;
      const Vec2 a = u[k], b = u[k1];
      if (p.neighbor >= 0) {
        const double ws = wP + w * model.lambda_of(type[c], type[p.neighbor]);
        const Vec2 ab = sub(b, a);
        const double l = std::sqrt(dot(ab, ab));
        if (l > 0.0) {
          const Vec2 tt = scale(ab, ws / l);
          G[k] = sub(G[k], tt);
          G[k1] = add(G[k1], tt);
        }
        G[k] = add(G[k], scale(Vec2{b.y, -b.x}, 0.5 * wA));
        G[k1] = add(G[k1], scale(Vec2{-a.y, a.x}, 0.5 * wA));
      } else {
        // theta = angle(b) - angle(a): d theta/du = perp(u)/|u|^2.
        const double coef = wF * r + 0.5 * wA * r * r;
        const double na = dot(a, a), nb = dot(b, b);
        G[k] = add(G[k], scale(Vec2{a.y, -a.x}, coef / na));
        G[k1] = add(G[k1], scale(Vec2{-b.y, b.x}, coef / nb));
      }
    }
    grad.clear();
    Vec2 gc{};
    for (int k = 0; k < m; ++k) gc = sub(gc, G[k]);
    // Each corner: two constraints a_q . dv = sum_p b_qp . dx_p.
    for (int k = 0; k < m; ++k) {
      const FinitePiece &prev = t.pieces[o + (k + m - 1) % m];
      const FinitePiece &next = t.pieces[o + k];
      if (prev.neighbor < 0 && next.neighbor < 0) continue;
      Vec2 row[2], bc[2], bj[2];
      int jj[2];
      const FinitePiece *side[2] = {&prev, &next};
      for (int q = 0; q < 2; ++q) {
        const int j = side[q]->neighbor;
        jj[q] = j;
        if (j >= 0) {
          const Vec2 D{pts.x(j) - xc.x, pts.y(j) - xc.y};
          row[q] = D;
          bc[q] = u[k];
          bj[q] = scale(sub(u[k], D), -1.0);
        } else {
          row[q] = u[k];
          bc[q] = u[k];
          bj[q] = Vec2{};
        }
      }
      const double det = cross(row[0], row[1]);
      if (det == 0.0 || !std::isfinite(det)) continue;
      const double l0 = cross(G[k], row[1]) / det, l1 = cross(row[0], G[k]) / det;
      const double lam[2] = {l0, l1};
      for (int q = 0; q < 2; ++q) {
        gc = add(gc, scale(bc[q], lam[q]));
        if (jj[q] >= 0) grad.push_back({jj[q], scale(bj[q], lam[q])});
      }
    }
    grad.push_back({c, gc});
    for (const auto &pg : grad) {
      const int p = pg.first;
      const double fx = -pg.second.x, fy = -pg.second.y;
      if (!std::isfinite(fx) || !std::isfinite(fy))
        throw_overflow(t, c, "force on a point from the energy", std::isfinite(fx) ? fy : fx);
      f[static_cast<long>(p) * f_stride] += fx;
      f[static_cast<long>(p) * f_stride + 1] += fy;
      const double rx = pts.x(p) - xc.x, ry = pts.y(p) - xc.y;
      const double wv[4] = {rx * fx, ry * fy, rx * fy, ry * fx};
      for (int q = 0; q < 4; ++q) {
        out.virial[q] += wv[q];
        if (cell_virial) cell_virial[4 * c + q] += wv[q];
      }
    }
  }
  if (!std::isfinite(out.energy) || !std::isfinite(out.virial[0]) ||
      !std::isfinite(out.virial[1]) || !std::isfinite(out.virial[2]) ||
      !std::isfinite(out.virial[3]))
    throw_total_overflow(std::isfinite(out.energy) ? out.virial[0] : out.energy);
  return out;
}

ForceOutput finite_periodic_forces(const Box &box, const Points &pts, double radius,
                                   const int *type, const Model &model,
                                   const double *free_tension, std::vector<double> &f) {
  const FiniteTessellation t = finite_tessellate_periodic(box, pts, radius);
  const std::vector<double> xy = positions_of(t);
  std::vector<int> all_type(t.n_points);
  for (int k = 0; k < t.n_points; ++k) all_type[k] = type[t.origin[k]];
  std::vector<double> fall(2 * static_cast<size_t>(t.n_points), 0.0);
  const Points p{xy.data(), t.n_points, 2};
  const ForceOutput out =
      finite_forces(t, p, all_type.data(), model, free_tension, fall.data(), 2);
  f.assign(2 * static_cast<size_t>(pts.n), 0.0);
  for (int k = 0; k < t.n_points; ++k) {
    f[2 * t.origin[k]] += fall[2 * k];
    f[2 * t.origin[k] + 1] += fall[2 * k + 1];
  }
  return out;
}

void finite_contacts(const FiniteTessellation &ft, Tessellation &t) {
  t = Tessellation();
  t.n_points = ft.n_points;
  t.n_owned = ft.n_owned;
  t.cell_offset.assign(1, 0);
  for (int c = 0; c < ft.n_owned; ++c) {
    for (int k = ft.cell_offset[c]; k < ft.cell_offset[c + 1]; ++k) {
      const FinitePiece &p = ft.pieces[k];
      if (p.neighbor < 0) continue;
      t.cell_vertex.push_back(-1);
      t.cell_neighbor.push_back(p.neighbor);
      t.edge_length.push_back(p.length);
    }
    t.cell_offset.push_back(static_cast<int>(t.cell_neighbor.size()));
  }
  t.area = ft.area;
  t.perimeter = ft.perimeter;
}

}  // namespace tessera

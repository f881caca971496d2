// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The vertex model's topology: T1 and T2 candidates, the rule that chooses
// which are carried out (doc/model.md, "Topology in parallel"), their
// application with a validity check of the result, and division.

#include "tessera/vertex_model.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace tessera {

namespace {

int index_in(const std::vector<int> &r, int v) {
  const auto it = std::find(r.begin(), r.end(), v);
  return it == r.end() ? -1 : static_cast<int>(it - r.begin());
}

int ring_next(const std::vector<int> &r, int k) {
  return r[k + 1 == static_cast<int>(r.size()) ? 0 : k + 1];
}
int ring_prev(const std::vector<int> &r, int k) {
  return r[k == 0 ? r.size() - 1 : k - 1];
}

// Whether cells c and o share an edge (c holds u -> v, o holds v -> u).
bool share_edge(const VertexTissue &t, int c, int o) {
  const std::vector<int> &rc = t.rings[c], &ro = t.rings[o];
  for (size_t k = 0; k < rc.size(); ++k) {
    const int u = rc[k], v = ring_next(rc, static_cast<int>(k));
    const int j = index_in(ro, v);
    if (j >= 0 && ring_next(ro, j) == u)
      return true;
  }
  return false;
}

bool cell_valid(const VertexTissue &t, int c, std::vector<double> &xy, std::vector<long> &ids) {
  const std::vector<int> &r = t.rings[c];
  t.polygon(c, xy);
  ids.resize(r.size());
  for (size_t k = 0; k < r.size(); ++k)
    ids[k] = t.vid(r[k]);
  return polygon_defect(xy.data(), static_cast<int>(r.size()), ids.data()) == PolygonDefect::None;
}

// How close edge (a, b) of cell c comes to folding onto c's other edges at
// its ends: the smallest of l and, for each of those edges sharper than 90
// degrees to it, the distance from the far end to that edge's line.
double fold_length(const VertexTissue &t, int c, int a, int b, double l) {
  const std::vector<int> &r = t.rings[c];
  double s = l;
  for (int end = 0; end < 2; ++end) {
    const int v = end ? b : a, o = end ? a : b;
    const int k = index_in(r, v);
    const int q = ring_next(r, k) == o ? ring_prev(r, k) : ring_next(r, k);
    const Vec2 u = t.delta(v, o), w = t.delta(v, q);
    const double lw = std::sqrt(w.x * w.x + w.y * w.y);
    if (u.x * w.x + u.y * w.y > 0.0 && lw > 0.0)
      s = std::min(s, std::fabs(u.x * w.y - u.y * w.x) / lw);
  }
  return s;
}

// Every cell of the event, and every cell across an edge of one of those, is
// complete: the rule's reads (doc/model.md).
bool decidable(const VertexTissue &t, const EdgeMap &m, const TopologyEvent &e) {
  for (int c : e.cells) {
    if (!t.complete(c))
      return false;
    for (int k = 0; k < static_cast<int>(t.rings[c].size()); ++k)
      if (!t.complete(twin_cell(t, m, c, k)))
        return false;
  }
  return true;
}

// The complete cells that may hold a T1 candidate (an edge of a candidate
// has it as X or Y), with the cells across their edges: an edge shorter than
// l_T1, a corner sharper than 90 degrees whose far ends come within l_T1 of
// the other edge's line (fold_length at X's or Y's corners), or, with T2s,
// an area below the T2 area.  The bounds are loosened by 1e-6 relative so
// that no rounding difference from find_events' own arithmetic leaves out a
// cell it would take.
std::vector<char> t1_cells(const VertexTissue &t, const EdgeMap &m, const TopologyParams &p) {
  const int nc = t.n_cells();
  std::vector<char> flag(nc, 0), look(nc, 0);
  const double l2 = p.t1_length * p.t1_length * (1.0 + 1e-6);
  std::vector<Vec2> d;
  std::vector<double> xy;
  for (int c = 0; c < nc; ++c) {
    if (!t.complete(c))
      continue;
    const std::vector<int> &r = t.rings[c];
    const int n = static_cast<int>(r.size());
    if (p.t2_area > 0.0 && n >= 4) {
      t.polygon(c, xy);
      if (polygon_measures(xy.data(), n).area < p.t2_area) {
        flag[c] = 1;
        continue;
      }
    }
    d.resize(n);
    for (int k = 0; k < n; ++k)
      d[k] = t.delta(r[k], ring_next(r, k));
    for (int k = 0; k < n && !flag[c]; ++k) {
      // The corner at the end of edge k: u back along edge k, w along k + 1.
      const Vec2 w = d[k + 1 == n ? 0 : k + 1];
      const double ux = -d[k].x, uy = -d[k].y;
      const double lu2 = ux * ux + uy * uy, lw2 = w.x * w.x + w.y * w.y;
      const double cr = ux * w.y - uy * w.x;
      if (lu2 < l2 ||
          (ux * w.x + uy * w.y > -1e-6 * (lu2 + lw2) && (cr * cr < l2 * lw2 || cr * cr < l2 * lu2)))
        flag[c] = 1;
    }
  }
  for (int c = 0; c < nc; ++c) {
    if (!flag[c])
      continue;
    look[c] = 1;
    for (int k = 0; k < static_cast<int>(t.rings[c].size()); ++k) {
      const int o = twin_cell(t, m, c, k);
      if (o >= 0)
        look[o] = 1;
    }
  }
  return look;
}

} // namespace

std::vector<TopologyEvent> find_events(const VertexTissue &t, const EdgeMap &m,
                                       const TopologyParams &p, bool every_cell) {
  std::vector<TopologyEvent> events;
  if (p.t2_area > 0.0)
    for (int c = 0; c < t.n_cells(); ++c) {
      if (t.rings[c].size() != 3 || !t.complete(c))
        continue;
      const double area = t.measures(c).area;
      if (!(area < p.t2_area))
        continue;
      TopologyEvent e;
      e.kind = TopologyEvent::T2;
      e.size = area;
      e.id0 = t.cid(c);
      e.cells[0] = c;
      for (int k = 0; k < 3; ++k)
        e.cells[k + 1] = twin_cell(t, m, c, k);
      e.decidable = decidable(t, m, e);
      events.push_back(e);
    }
  if (p.t1_length > 0.0) {
    // Only the cells that may hold a candidate, and the cells across their
    // edges, are looked at (every_cell: all of them, the oracle); in the
    // order of the whole scan, so the events come in the same order.
    std::vector<char> look;
    if (!every_cell)
      look = t1_cells(t, m, p);
    std::unordered_set<std::uint64_t> seen;
    for (int c = 0; c < t.n_cells(); ++c) {
      if ((!every_cell && !look[c]) || !t.complete(c))
        continue;
      const std::vector<int> &r = t.rings[c];
      const int n = static_cast<int>(r.size());
      // A cell of four or more sides below the T2 area (a dying cell that
      // shrinks) loses its shortest edge whose far side has four or more
      // sides, however long, so that it becomes a triangle for a T2.
      int forced = -1;
      if (p.t2_area > 0.0 && n >= 4 && t.measures(c).area < p.t2_area) {
        double shortest = 0.0;
        for (int k = 0; k < n; ++k) {
          const int o = twin_cell(t, m, c, k);
          if (o < 0 || t.rings[o].size() < 4)
            continue;
          const Vec2 d = t.delta(r[k], ring_next(r, k));
          const double l = d.x * d.x + d.y * d.y;
          if (forced < 0 || l < shortest) {
            forced = k;
            shortest = l;
          }
        }
      }
      for (int k = 0; k < n; ++k) {
        int a = r[k], b = ring_next(r, k);
        if (t.vid(a) > t.vid(b))
          std::swap(a, b);
        const Vec2 d = t.delta(a, b);
        const double l = std::sqrt(d.x * d.x + d.y * d.y);
        const int X = m.cell(a, b), Y = m.cell(b, a);
        // The edge's size: its length, or less if it nearly folds onto
        // another edge at its ends (the corners of X and Y there).
        double size = l;
        for (int cell : {X, Y})
          if (t.complete(cell))
            size = fold_length(t, cell, a, b, size);
        if (!(size < p.t1_length) && k != forced)
          continue;
        const std::uint64_t key =
            (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
            static_cast<std::uint32_t>(b);
        if (!seen.insert(key).second)
          continue;
        // A T1 would leave a three-sided neighbour with two sides: no candidate.
        if (X >= 0 && t.rings[X].size() < 4)
          continue;
        if (Y >= 0 && t.rings[Y].size() < 4)
          continue;
        TopologyEvent e;
        e.kind = TopologyEvent::T1;
        e.size = size;
        e.id0 = t.vid(a);
        e.id1 = t.vid(b);
        e.a = a;
        e.b = b;
        e.cells[0] = X;
        e.cells[1] = Y;
        if (X >= 0) {
          const std::vector<int> &rx = t.rings[X];
          const int ka = index_in(rx, a), kb = index_in(rx, b);
          e.cells[2] = m.cell(a, ring_prev(rx, ka));
          e.cells[3] = m.cell(ring_next(rx, kb), b);
        }
        e.decidable = X >= 0 && Y >= 0 && decidable(t, m, e);
        events.push_back(e);
      }
    }
  }
  return events;
}

std::vector<EventStatus> decide_events(const VertexTissue &t, const EdgeMap &m,
                                       const std::vector<TopologyEvent> &events) {
  (void)t;
  (void)m;
  std::unordered_map<int, std::vector<int>> by_cell;
  for (int i = 0; i < static_cast<int>(events.size()); ++i)
    for (int c : events[i].cells)
      if (c >= 0)
        by_cell[c].push_back(i);
  std::vector<EventStatus> status(events.size(), EventStatus::Undecidable);
  for (int i = 0; i < static_cast<int>(events.size()); ++i) {
    if (!events[i].decidable)
      continue;
    status[i] = EventStatus::Carry;
    for (int c : events[i].cells)
      for (int j : by_cell[c])
        if (j != i && events[j].before(events[i]))
          status[i] = EventStatus::Wait;
  }
  return status;
}

namespace {

// Interior angle (radians, in (0, 2 pi)) of cell c at its vertex v.
double corner_angle(const VertexTissue &t, int c, int v) {
  const std::vector<int> &r = t.rings[c];
  const int k = index_in(r, v);
  const Vec2 u = t.delta(v, ring_next(r, k)), w = t.delta(v, ring_prev(r, k));
  double a = std::atan2(u.x * w.y - u.y * w.x, u.x * w.x + u.y * w.y);
  if (a < 0.0)
    a += 2.0 * std::acos(-1.0);
  return a;
}

// The directions the T1's new edge may take, in order of preference.
std::vector<Vec2> t1_directions(const VertexTissue &t, const TopologyEvent &e) {
  std::vector<Vec2> dirs;
  auto add = [&](double x, double y) {
    const double l = std::sqrt(x * x + y * y);
    if (l > 0.0)
      dirs.push_back(Vec2{x / l, y / l});
  };
  const Vec2 cx = t.measures(e.cells[0]).centroid, cy = t.measures(e.cells[1]).centroid;
  const Vec2 cw = t.measures(e.cells[2]).centroid, cz = t.measures(e.cells[3]).centroid;
  const Vec2 xy = t.image(cx.x - cy.x, cx.y - cy.y), wz = t.image(cz.x - cw.x, cz.y - cw.y);
  const Vec2 d = t.delta(e.a, e.b);
  add(xy.x, xy.y); // from Y towards X
  add(-d.y, d.x);  // perpendicular to the old edge, into X
  const double s = -wz.y * xy.x + wz.x * xy.y >= 0.0 ? 1.0 : -1.0;
  add(-s * wz.y, s * wz.x); // perpendicular to the line W-Z, towards X
  const double pi = std::acos(-1.0);
  for (int k = 0; k < 24; ++k)
    add(std::cos(k * pi / 12), std::sin(k * pi / 12));
  return dirs;
}

} // namespace

bool apply_event(VertexTissue &t, const TopologyEvent &e, const TopologyParams &p) {
  std::vector<double> xy;
  std::vector<long> ids;
  if (e.kind == TopologyEvent::T1) {
    const int X = e.cells[0], Y = e.cells[1], W = e.cells[2], Z = e.cells[3];
    if (X < 0 || Y < 0 || W < 0 || Z < 0)
      return false;
    if (X == Y || W == Z || X == W || X == Z || Y == W || Y == Z)
      return false;
    if (t.rings[X].size() < 4 || t.rings[Y].size() < 4)
      return false;
    if (share_edge(t, W, Z))
      return false;
    const int a = e.a, b = e.b;
    const std::vector<int> old[4] = {t.rings[X], t.rings[Y], t.rings[W], t.rings[Z]};
    const Vec2 old_a = t.pos[a], old_b = t.pos[b];
    const Vec2 d = t.delta(a, b);
    const std::vector<Vec2> dirs = t1_directions(t, e);
    std::vector<int> &rx = t.rings[X], &ry = t.rings[Y], &rw = t.rings[W], &rz = t.rings[Z];
    rx.erase(rx.begin() + index_in(rx, b));
    ry.erase(ry.begin() + index_in(ry, a));
    rw.insert(rw.begin() + index_in(rw, a), b);
    rz.insert(rz.begin() + index_in(rz, b), a);
    // Of the directions that leave the four cells valid, the one whose
    // sharpest corner at a' or b' is widest.
    const double h = 0.5 * p.t1_new;
    double best = -1.0;
    Vec2 best_a, best_b;
    for (const Vec2 &n : dirs) {
      t.pos[a] = Vec2{old_a.x + 0.5 * d.x + h * n.x, old_a.y + 0.5 * d.y + h * n.y};
      t.pos[b] = Vec2{old_b.x - 0.5 * d.x - h * n.x, old_b.y - 0.5 * d.y - h * n.y};
      bool ok = true;
      for (int c : {X, Y, W, Z})
        if (ok)
          ok = cell_valid(t, c, xy, ids);
      if (!ok)
        continue;
      double sharpest = 1e300;
      for (int c : {X, W, Z})
        sharpest = std::min(sharpest, corner_angle(t, c, a));
      for (int c : {Y, W, Z})
        sharpest = std::min(sharpest, corner_angle(t, c, b));
      if (sharpest > best) {
        best = sharpest;
        best_a = t.pos[a];
        best_b = t.pos[b];
      }
    }
    if (best < 0.0) {
      t.rings[X] = old[0];
      t.rings[Y] = old[1];
      t.rings[W] = old[2];
      t.rings[Z] = old[3];
      t.pos[a] = old_a;
      t.pos[b] = old_b;
      return false;
    }
    t.pos[a] = best_a;
    t.pos[b] = best_b;
    return true;
  }
  // T2
  const int T = e.cells[0];
  if (T < 0 || t.rings[T].size() != 3)
    return false;
  const std::vector<int> tri = t.rings[T];
  int nb[3];
  for (int k = 0; k < 3; ++k) {
    nb[k] = e.cells[k + 1];
    if (nb[k] < 0 || nb[k] == T || t.rings[nb[k]].size() < 4)
      return false;
  }
  if (nb[0] == nb[1] || nb[1] == nb[2] || nb[0] == nb[2])
    return false;
  int s = tri[0];
  for (int v : tri)
    if (t.vid(v) < t.vid(s))
      s = v;
  const Vec2 d1 = t.delta(s, tri[0]), d2 = t.delta(s, tri[1]), d3 = t.delta(s, tri[2]);
  const Vec2 centre{t.pos[s].x + (d1.x + d2.x + d3.x) / 3.0,
                    t.pos[s].y + (d1.y + d2.y + d3.y) / 3.0};
  const std::vector<int> old[3] = {t.rings[nb[0]], t.rings[nb[1]], t.rings[nb[2]]};
  const Vec2 old_s = t.pos[s];
  for (int k = 0; k < 3; ++k) {
    // nb[k] holds tri[k+1] -> tri[k]: the pair becomes s.
    std::vector<int> &r = t.rings[nb[k]];
    const int j = index_in(r, tri[(k + 1) % 3]);
    const int j1 = j + 1 == static_cast<int>(r.size()) ? 0 : j + 1;
    if (j < 0 || r[j1] != tri[k]) {
      for (int i = 0; i < k; ++i)
        t.rings[nb[i]] = old[i];
      return false;
    }
    r[j] = s;
    r.erase(r.begin() + j1);
  }
  t.pos[s] = centre;
  bool ok = true;
  for (int k = 0; k < 3 && ok; ++k)
    ok = cell_valid(t, nb[k], xy, ids);
  if (!ok) {
    for (int k = 0; k < 3; ++k)
      t.rings[nb[k]] = old[k];
    t.pos[s] = old_s;
    return false;
  }
  t.rings[T].clear();
  if (t.vertex_removed.empty())
    t.vertex_removed.assign(t.n_vertices(), 0);
  for (int v : tri)
    if (v != s)
      t.vertex_removed[v] = 1;
  return true;
}

int topology_step(VertexTissue &t, const TopologyParams &p, int *refused) {
  const EdgeMap m(t);
  const std::vector<TopologyEvent> events = find_events(t, m, p);
  const std::vector<EventStatus> status = decide_events(t, m, events);
  int done = 0, no = 0;
  for (size_t i = 0; i < events.size(); ++i)
    if (status[i] == EventStatus::Carry) {
      if (apply_event(t, events[i], p))
        ++done;
      else
        ++no;
    }
  if (refused)
    *refused = no;
  return done;
}

int divide_cell(VertexTissue &t, int c, Vec2 axis, long new_cell_id, long new_vertex_id) {
  const std::vector<int> r = t.rings[c];
  const int n = static_cast<int>(r.size());
  const double la = std::sqrt(axis.x * axis.x + axis.y * axis.y);
  if (n < 3 || !(la > 0.0))
    return -1;
  const Vec2 u{axis.x / la, axis.y / la};
  std::vector<double> xy;
  t.polygon(c, xy);
  const Vec2 cm = polygon_measures(xy.data(), n).centroid;
  std::vector<double> g(n);
  for (int k = 0; k < n; ++k)
    g[k] = (xy[2 * k] - cm.x) * u.x + (xy[2 * k + 1] - cm.y) * u.y;
  int e1 = -1, e2 = -1, crossings = 0;
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    const bool neg = g[k] < 0.0, neg1 = g[k1] < 0.0;
    if (neg == neg1)
      continue;
    ++crossings;
    if (neg)
      e1 = k; // from the side -axis to +axis
    else
      e2 = k;
  }
  if (crossings != 2 || e1 < 0 || e2 < 0)
    return -1;
  const EdgeMap m(t);
  const int n1 = twin_cell(t, m, c, e1), n2 = twin_cell(t, m, c, e2);
  if (n1 < 0 || n2 < 0 || n1 == c || n2 == c)
    return -1;
  auto cut = [&](int k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    double s = g[k] / (g[k] - g[k1]);
    s = std::min(0.9, std::max(0.1, s));
    return Vec2{xy[2 * k] + s * (xy[2 * k1] - xy[2 * k]),
                xy[2 * k + 1] + s * (xy[2 * k1 + 1] - xy[2 * k + 1])};
  };
  // New IDs: the given ones, or after the largest in use.
  long max_v = 0, max_c = 0;
  for (int v = 0; v < t.n_vertices(); ++v)
    max_v = std::max(max_v, t.vid(v));
  for (int o = 0; o < t.n_cells(); ++o)
    max_c = std::max(max_c, t.cid(o));
  const long id_v = new_vertex_id > 0 ? new_vertex_id : max_v + 1;
  const long id_c = new_cell_id > 0 ? new_cell_id : max_c + 1;
  const int v1 = t.n_vertices(), v2 = v1 + 1;
  const std::vector<int> old_n1 = t.rings[n1], old_n2 = t.rings[n2];
  t.pos.push_back(cut(e1));
  t.pos.push_back(cut(e2));
  if (!t.vertex_id.empty()) {
    t.vertex_id.push_back(id_v);
    t.vertex_id.push_back(id_v + 1);
  } else if (new_vertex_id > 0 && new_vertex_id != v1 + 1) {
    // Indices stand for IDs: give every vertex its ID explicitly.
    t.vertex_id.resize(v1);
    for (int v = 0; v < v1; ++v)
      t.vertex_id[v] = v + 1;
    t.vertex_id.push_back(id_v);
    t.vertex_id.push_back(id_v + 1);
  }
  if (!t.vertex_known.empty())
    t.vertex_known.insert(t.vertex_known.end(), 2, 1);
  if (!t.vertex_removed.empty())
    t.vertex_removed.insert(t.vertex_removed.end(), 2, 0);
  std::vector<int> mother, daughter;
  for (int k = (e2 + 1) % n;; k = (k + 1) % n) {
    mother.push_back(r[k]);
    if (k == e1)
      break;
  }
  mother.push_back(v1);
  mother.push_back(v2);
  for (int k = (e1 + 1) % n;; k = (k + 1) % n) {
    daughter.push_back(r[k]);
    if (k == e2)
      break;
  }
  daughter.push_back(v2);
  daughter.push_back(v1);
  // The neighbours across the cut edges gain the new vertex between the ends.
  auto insert_between = [&](int cell, int before, int after, int v) {
    std::vector<int> &rr = t.rings[cell];
    const int j = index_in(rr, before);
    if (j < 0 || ring_next(rr, j) != after)
      return false;
    rr.insert(rr.begin() + j + 1, v);
    return true;
  };
  const int d = t.n_cells();
  t.rings[c] = mother;
  t.rings.push_back(daughter);
  t.type.push_back(t.type[c]);
  if (!t.cell_id.empty())
    t.cell_id.push_back(id_c);
  bool ok = insert_between(n1, r[(e1 + 1) % n], r[e1], v1) &&
            insert_between(n2, r[(e2 + 1) % n], r[e2], v2);
  std::vector<long> ids;
  for (int o : {c, d, n1, n2})
    if (ok)
      ok = cell_valid(t, o, xy, ids);
  if (!ok) {
    t.rings[c] = r;
    t.rings[n1] = old_n1;
    t.rings[n2] = old_n2;
    t.rings.pop_back();
    t.type.pop_back();
    if (!t.cell_id.empty())
      t.cell_id.pop_back();
    t.pos.resize(v1);
    if (!t.vertex_id.empty())
      t.vertex_id.resize(v1);
    if (!t.vertex_known.empty())
      t.vertex_known.resize(v1);
    if (!t.vertex_removed.empty())
      t.vertex_removed.resize(v1);
    return -1;
  }
  if (t.cell_id.empty() && new_cell_id > 0 && new_cell_id != d + 1) {
    t.cell_id.resize(d + 1);
    for (int o = 0; o < d; ++o)
      t.cell_id[o] = o + 1;
    t.cell_id[d] = id_c;
  }
  return d;
}

} // namespace tessera

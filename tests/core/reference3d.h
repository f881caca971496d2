// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// A slow, independent 3D Voronoi reference: each cell is a box around its
// centre clipped by the bisector half-spaces of every other point and of
// every periodic image (27 copies of the box).  No triangulation, no
// circumcentres: only plane clipping of convex polyhedra.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace ref3d {

struct P {
  double x, y, z;
};
inline P operator+(P a, P b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline P operator-(P a, P b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline P operator*(double s, P a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(P a, P b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline P cross(P a, P b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

struct Face {
  P neighbour;  // position of the point across the face (unused for box faces)
  bool box = false;
  std::vector<P> poly;  // convex, counter-clockwise seen from outside
};

struct Cell {
  std::vector<Face> faces;
  double volume = 0, surface = 0;
};

// Keep the half-space n.x <= c of polyhedron faces.
inline void clip(std::vector<Face> &faces, P n, double c, P neighbour) {
  std::vector<Face> out;
  std::vector<P> cap;
  const double eps = 1e-13;
  for (Face &f : faces) {
    std::vector<P> poly;
    const int m = static_cast<int>(f.poly.size());
    for (int k = 0; k < m; ++k) {
      const P a = f.poly[k], b = f.poly[(k + 1) % m];
      const double da = dot(n, a) - c, db = dot(n, b) - c;
      if (da <= eps) poly.push_back(a);
      if ((da < -eps && db > eps) || (da > eps && db < -eps)) {
        const P x = a + (da / (da - db)) * (b - a);
        poly.push_back(x);
        cap.push_back(x);
      }
      if (std::fabs(da) <= eps) cap.push_back(a);
    }
    if (poly.size() >= 3) {
      f.poly = poly;
      out.push_back(f);
    }
  }
  if (cap.size() >= 3) {
    P g{0, 0, 0};
    for (const P &p : cap) g = g + p;
    g = (1.0 / cap.size()) * g;
    P e1 = cap[0] - g;
    for (const P &p : cap)
      if (dot(p - g, p - g) > dot(e1, e1)) e1 = p - g;
    e1 = (1.0 / std::sqrt(dot(e1, e1))) * e1;
    const P nn = (1.0 / std::sqrt(dot(n, n))) * n;
    const P e2 = cross(nn, e1);
    std::sort(cap.begin(), cap.end(), [&](P a, P b) {
      return std::atan2(dot(a - g, e2), dot(a - g, e1)) < std::atan2(dot(b - g, e2), dot(b - g, e1));
    });
    Face f;
    f.neighbour = neighbour;
    f.poly = cap;
    out.push_back(f);
  }
  faces = out;
}

inline P vector_area(const std::vector<P> &poly) {
  P a{0, 0, 0};
  for (size_t k = 0; k < poly.size(); ++k) a = a + 0.5 * cross(poly[k], poly[(k + 1) % poly.size()]);
  return a;
}

// Cells of points xyz (stride 3) in the periodic box with edge vectors
// e[0], e[1], e[2] (periodic images: the 27 shifts by -1, 0, 1 of each).
inline std::vector<Cell> cells(const std::vector<double> &xyz, const P e[3]) {
  const int n = static_cast<int>(xyz.size() / 3);
  std::vector<Cell> res(n);
  const double span = std::sqrt(dot(e[0], e[0])) + std::sqrt(dot(e[1], e[1])) + std::sqrt(dot(e[2], e[2]));
  for (int i = 0; i < n; ++i) {
    const P xi{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    std::vector<Face> faces;
    const double h[3] = {span, span, span};
    // A box of half-width L around xi (surely contains the cell).
    P c[8];
    for (int k = 0; k < 8; ++k)
      c[k] = {xi.x + ((k & 1) ? h[0] : -h[0]), xi.y + ((k & 2) ? h[1] : -h[1]), xi.z + ((k & 4) ? h[2] : -h[2])};
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto &q : quads) {
      Face f;
      f.box = true;
      for (int k = 0; k < 4; ++k) f.poly.push_back(c[q[k]]);
      faces.push_back(f);
    }
    for (int j = 0; j < n; ++j)
      for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b)
          for (int d = -1; d <= 1; ++d) {
            if (j == i && a == 0 && b == 0 && d == 0) continue;
            const P xj = P{xyz[3 * j], xyz[3 * j + 1], xyz[3 * j + 2]} + (1.0 * a) * e[0] +
                         (1.0 * b) * e[1] + (1.0 * d) * e[2];
            const P nrm = xj - xi;
            clip(faces, nrm, dot(nrm, 0.5 * (xi + xj)), xj);
          }
    Cell &cell = res[i];
    for (Face &f : faces) {
      const P av = vector_area(f.poly);
      const double area = std::sqrt(dot(av, av));
      cell.surface += area;
      cell.volume += dot(av, f.poly[0] - xi) / 3.0;
    }
    cell.faces = faces;
  }
  return res;
}

// Orthogonal box [lo, lo + L).
inline std::vector<Cell> cells(const std::vector<double> &xyz, const double /*lo*/[3], const double L[3]) {
  const P e[3] = {{L[0], 0, 0}, {0, L[1], 0}, {0, 0, L[2]}};
  return cells(xyz, e);
}

}  // namespace ref3d

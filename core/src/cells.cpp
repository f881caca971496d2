// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The cell views (tessera/cells.h): the three models' arrays read as one
// list of pieces per cell, and what every model derives from its pieces in
// the same way (neighbour count, shape index, centroid, second moments and
// principal axes).  Moments are integrated over a fan from the cell's own
// point, which lies inside every cell of every model (a Voronoi cell holds
// its generator; a finite cell is that cell cut by a disc around it):
// triangles to straight edges, circular sectors to free arcs (whose circle
// is centred on the point), tetrahedra to the triangles of each face.

#include "tessera/cells.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {

namespace {

// Moments of a region, relative to an origin: m0 = area/volume, m1[a] =
// integral of x_a, m2[a][b] = integral of x_a x_b.
struct Moments {
  double m0 = 0.0, m1[3] = {0, 0, 0}, m2[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

// Triangle (0, a, b) in 2D.
void add_triangle(Moments &m, const double *a, const double *b) {
  const double cr = a[0] * b[1] - b[0] * a[1];
  m.m0 += 0.5 * cr;
  m.m1[0] += cr * (a[0] + b[0]) / 6.0;
  m.m1[1] += cr * (a[1] + b[1]) / 6.0;
  m.m2[0][0] += cr * (a[0] * a[0] + a[0] * b[0] + b[0] * b[0]) / 12.0;
  m.m2[1][1] += cr * (a[1] * a[1] + a[1] * b[1] + b[1] * b[1]) / 12.0;
  const double xy = cr * (2 * a[0] * a[1] + a[0] * b[1] + b[0] * a[1] + 2 * b[0] * b[1]) / 24.0;
  m.m2[0][1] += xy;
  m.m2[1][0] += xy;
}

// Circular sector around the origin, radius r, angles [phi, phi + theta].
void add_sector(Moments &m, double r, double phi, double theta) {
  const double p1 = phi + theta;
  const double r2 = r * r, r3 = r2 * r, r4 = r2 * r2;
  m.m0 += 0.5 * r2 * theta;
  m.m1[0] += r3 / 3.0 * (std::sin(p1) - std::sin(phi));
  m.m1[1] += r3 / 3.0 * (std::cos(phi) - std::cos(p1));
  const double s2 = std::sin(2.0 * p1) - std::sin(2.0 * phi);
  m.m2[0][0] += 0.25 * r4 * (0.5 * theta + 0.25 * s2);
  m.m2[1][1] += 0.25 * r4 * (0.5 * theta - 0.25 * s2);
  const double xy = 0.125 * r4 * (std::sin(p1) * std::sin(p1) - std::sin(phi) * std::sin(phi));
  m.m2[0][1] += xy;
  m.m2[1][0] += xy;
}

// Tetrahedron (0, a, b, c) in 3D.
void add_tet(Moments &m, const double *a, const double *b, const double *c) {
  const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                     a[2] * (b[0] * c[1] - b[1] * c[0]);
  const double v = det / 6.0;
  const double s[3] = {a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]};
  m.m0 += v;
  for (int i = 0; i < 3; ++i) {
    m.m1[i] += v * s[i] / 4.0;
    for (int j = 0; j < 3; ++j)
      m.m2[i][j] += v / 20.0 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
  }
}

Moments cell_moments(const CellView &v, int c) {
  Moments m;
  const int dim = v.dimension();
  double p[3] = {0, 0, 0};
  v.point(c, p);
  std::vector<double> xyz;
  for (int k = v.piece_begin(c); k < v.piece_end(c); ++k) {
    double phi, theta;
    if (dim == 2 && v.piece_arc(k, phi, theta)) {
      add_sector(m, v.arc_radius(), phi, theta);
      continue;
    }
    xyz.clear();
    const int n = v.piece_corners(k, xyz);
    for (int q = 0; q < n; ++q)
      for (int d = 0; d < dim; ++d) xyz[dim * q + d] -= p[d];
    if (dim == 2) {
      if (n == 2) add_triangle(m, &xyz[0], &xyz[2]);
    } else {
      for (int q = 1; q + 1 < n; ++q) add_tet(m, &xyz[0], &xyz[3 * q], &xyz[3 * q + 3]);
    }
  }
  return m;
}

// Eigen decomposition of a symmetric 3x3 matrix by Jacobi rotations:
// eigenvalues w, eigenvectors the columns of z.
void jacobi3(double a[3][3], double w[3], double z[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) z[i][j] = i == j ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > 1e-30 * diag)) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        const double th = 0.5 * (a[q][q] - a[p][p]) / a[p][q];
        const double t = (th >= 0 ? 1.0 : -1.0) / (std::fabs(th) + std::sqrt(th * th + 1.0));
        const double cs = 1.0 / std::sqrt(t * t + 1.0), sn = t * cs;
        for (int k = 0; k < 3; ++k) {  // columns p, q
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = cs * akp - sn * akq;
          a[k][q] = sn * akp + cs * akq;
        }
        for (int k = 0; k < 3; ++k) {  // rows p, q
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = cs * apk - sn * aqk;
          a[q][k] = sn * apk + cs * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double zkp = z[k][p], zkq = z[k][q];
          z[k][p] = cs * zkp - sn * zkq;
          z[k][q] = sn * zkp + cs * zkq;
        }
      }
  }
  for (int i = 0; i < 3; ++i) w[i] = a[i][i];
}

}  // namespace

int CellView::coordination_number(int c, double rel_tol) const {
  // The threshold is the pair's own (rel_tol times the distance between the
  // two centres, squared in 3D), so that both cells of a pair agree: a
  // threshold relative to each cell's own size counted a short edge from one
  // side and not from the other.
  const int b = piece_begin(c), e = piece_end(c);
  const int sd = space_dimension();
  double xc[3] = {0.0, 0.0, 0.0}, xq[3] = {0.0, 0.0, 0.0};
  point(c, xc);
  int z = 0;
  for (int k = b; k < e; ++k) {
    const int q = piece_neighbor(k);
    if (q < 0) continue;
    point(q, xq);
    double d2 = 0.0;
    for (int a = 0; a < sd; ++a) d2 += (xq[a] - xc[a]) * (xq[a] - xc[a]);
    const double scale = dimension() == 3 ? d2 : std::sqrt(d2);
    z += piece_size(k) > rel_tol * scale;
  }
  return z;
}

double CellView::shape_index(int c) const {
  const double m = measure(c), s = boundary(c);
  if (!(m > 0.0)) return 0.0;
  return dimension() == 3 ? s / std::cbrt(m * m) : s / std::sqrt(m);
}

void CellView::centroid(int c, double *x) const {
  const Moments m = cell_moments(*this, c);
  const int dim = dimension();
  point(c, x);
  if (!(m.m0 > 0.0)) return;
  for (int d = 0; d < dim; ++d) x[d] += m.m1[d] / m.m0;
}

void CellView::second_moments(int c, double *out) const {
  const Moments m = cell_moments(*this, c);
  const int dim = dimension();
  for (int a = 0; a < dim; ++a)
    for (int b = 0; b < dim; ++b)
      out[dim * a + b] = m.m0 > 0.0 ? m.m2[a][b] - m.m0 * (m.m1[a] / m.m0) * (m.m1[b] / m.m0) : 0.0;
}

bool CellView::principal_axis(int c, bool longest, double *x) const {
  const int dim = dimension();
  double s[9];
  second_moments(c, s);
  if (dim == 2) {
    const double sxx = s[0], syy = s[3], sxy = s[1];
    if (!(sxx + syy > 0.0) || !(std::hypot(sxx - syy, 2.0 * sxy) > 1e-12 * (sxx + syy)))
      return false;
    double th = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // the long axis
    if (!longest) th += 0.5 * 3.14159265358979323846;
    x[0] = std::cos(th);
    x[1] = std::sin(th);
    return true;
  }
  double a[3][3], w[3], z[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[i][j] = s[3 * i + j];
  const double tr = s[0] + s[4] + s[8];
  if (!(tr > 0.0)) return false;
  jacobi3(a, w, z);
  int hi = 0, lo = 0;
  for (int i = 1; i < 3; ++i) {
    if (w[i] > w[hi]) hi = i;
    if (w[i] < w[lo]) lo = i;
  }
  const int pick = longest ? hi : lo;
  // The chosen axis must stand out from the other two.
  double gap = std::numeric_limits<double>::max();
  for (int i = 0; i < 3; ++i)
    if (i != pick) gap = std::min(gap, std::fabs(w[pick] - w[i]));
  if (!(gap > 1e-12 * tr)) return false;
  for (int d = 0; d < 3; ++d) x[d] = z[d][pick];
  return true;
}

// ---- confluent 2D ----

int ConfluentCells::piece_corners(int k, std::vector<double> &xyz) const {
  // Edge k runs from vertex k to the next vertex of the same cell.
  const int c = static_cast<int>(std::upper_bound(t_->cell_offset.begin(), t_->cell_offset.end(), k) -
                                 t_->cell_offset.begin()) - 1;
  const int o = t_->cell_offset[c], m = t_->cell_size(c);
  const Vec2 &a = t_->vertices[t_->cell_vertex[k]];
  const Vec2 &b = t_->vertices[t_->cell_vertex[o + (k - o + 1) % m]];
  xyz.insert(xyz.end(), {a.x, a.y, b.x, b.y});
  return 2;
}

Contacts ConfluentCells::contacts() const {
  Contacts c;
  if (!t_) return c;
  c.n_owned = t_->n_owned;
  c.offset = t_->cell_offset.data();
  c.neighbor = t_->cell_neighbor.data();
  c.size = t_->edge_length.data();
  return c;
}

int ConfluentCells::multifold_count() const {
  return t_ && !t_->group_offset.empty() ? static_cast<int>(t_->group_offset.size()) - 1 : 0;
}

void ConfluentCells::multifold_ring(int g, std::vector<int> &ring) const {
  ring.assign(t_->group_point.begin() + t_->group_offset[g],
              t_->group_point.begin() + t_->group_offset[g + 1]);
}

bool ConfluentCells::short_edge_clusters(double min_length, std::vector<int> &offset,
                                         std::vector<int> &members) const {
  t_->short_edge_clusters(min_length, offset, members);
  return true;
}

// ---- finite 2D ----

int FiniteCells::cell_of(int k) const {
  return static_cast<int>(std::upper_bound(t_->cell_offset.begin(), t_->cell_offset.end(), k) -
                          t_->cell_offset.begin()) - 1;
}

int FiniteCells::piece_corners(int k, std::vector<double> &xyz) const {
  const int c = cell_of(k);
  const int o = t_->cell_offset[c], m = t_->cell_size(c);
  const Vec2 &a = t_->pieces[k].start;
  const Vec2 &b = t_->pieces[o + (k - o + 1) % m].start;
  xyz.insert(xyz.end(), {a.x, a.y, b.x, b.y});
  return 2;
}

bool FiniteCells::piece_arc(int k, double &phi, double &theta) const {
  const FinitePiece &p = t_->pieces[k];
  if (p.neighbor >= 0) return false;
  phi = p.phi;
  theta = p.theta;
  return true;
}

Contacts FiniteCells::contacts() const {
  Contacts c;
  if (!c_) return c;
  c.n_owned = c_->n_owned;
  c.offset = c_->cell_offset.data();
  c.neighbor = c_->cell_neighbor.data();
  c.size = c_->edge_length.data();
  return c;
}

// ---- 3D ----

int Cells3::piece_corners(int k, std::vector<double> &xyz) const {
  const int b = t_->face_offset[k], e = t_->face_offset[k + 1];
  for (int q = b; q < e; ++q) {
    const Vec3 &v = t_->vertices[t_->face_vertex[q]];
    xyz.insert(xyz.end(), {v.x, v.y, v.z});
  }
  return e - b;
}

Contacts Cells3::contacts() const {
  Contacts c;
  if (!t_) return c;
  c.n_owned = t_->n_owned;
  c.offset = t_->cell_offset.data();
  c.neighbor = t_->face_neighbor.data();
  c.size = t_->face_area.data();
  return c;
}

}  // namespace tessera

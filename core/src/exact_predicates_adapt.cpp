// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Stages B-D of the exact predicates (the scheme is described at the top of
// exact_predicates.cpp): the error-free transformations and expansion
// arithmetic, the exact determinants over expansions or big integers, the
// range check that scales the coordinates or falls back to big integers, and
// the adaptive stages themselves.  Apart from stage A (exact_predicates.cpp)
// because only the calls the filter cannot decide come here, out of line.
// Compiled, like stage A, with -ffp-contract=off (core/CMakeLists.txt).

#include "exact_bigint.h"
#include "exact_predicates_detail.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tessera::exact {

namespace {

// ---------------------------------------------------------------------------
// Error-free transformations.

// a + b = x + y exactly, x = fl(a + b).
inline void two_sum(double a, double b, double &x, double &y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

// The same for |a| >= |b| (or a = 0), in three operations.
inline void fast_two_sum(double a, double b, double &x, double &y) {
  x = a + b;
  y = b - (x - a);
}

// a - b = x + y exactly, x = fl(a - b).
inline void two_diff(double a, double b, double &x, double &y) {
  x = a - b;
  const double bv = a - x;
  const double av = x + bv;
  y = (a - av) + (bv - b);
}

// The error of x = fl(a - b).
inline double diff_tail(double a, double b, double x) {
  const double bv = a - x;
  const double av = x + bv;
  return (a - av) + (bv - b);
}

#if defined(__FMA__) || defined(FP_FAST_FMA)
// a b = x + y exactly, x = fl(a b): the fused multiply-add rounds only once.
inline void two_product(double a, double b, double &x, double &y) {
  x = a * b;
  y = std::fma(a, b, -x);
}
#else
// Dekker's splitting: a = hi + lo with both halves of at most 26 bits, so
// that the products of halves are exact.
inline void split(double a, double &hi, double &lo) {
  constexpr double kSplitter = 0x1p27 + 1.0;
  const double c = kSplitter * a;
  const double big = c - a;
  hi = c - big;
  lo = a - hi;
}

inline void two_product(double a, double b, double &x, double &y) {
  x = a * b;
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  y = al * bl - (((x - ah * bh) - al * bh) - ah * bl);
}
#endif

// (x1 + x0) - (y1 + y0), two two-component expansions, exactly as a
// four-component expansion h[0..3] (h[3] the largest).
inline void two_two_diff(double x1, double x0, double y1, double y0, double *h) {
  double i, j, k, l, m, n;
  two_diff(x0, y0, i, h[0]);
  two_sum(x1, i, j, k);
  two_diff(k, y1, l, h[1]);
  two_sum(j, l, m, n);
  h[2] = n;
  h[3] = m;
}

// ---------------------------------------------------------------------------
// Expansions: components in increasing magnitude, nonoverlapping.  The
// functions return the number of components written; zero components are
// left out.

// h = e + f (Fast-Expansion-Sum with zero elimination).  e and f strongly
// nonoverlapping; h may not alias them.
int sum(int elen, const double *e, int flen, const double *f, double *h) {
  double Q, Qn, q, enow = e[0], fnow = f[0];
  int ei = 0, fi = 0, hn = 0;
  // The smaller of the next components of e and f goes first.
  auto e_first = [&]() { return (fnow > enow) == (fnow > -enow); };
  if (e_first()) {
    Q = enow;
    enow = ++ei < elen ? e[ei] : 0.0;
  } else {
    Q = fnow;
    fnow = ++fi < flen ? f[fi] : 0.0;
  }
  if (ei < elen && fi < flen) {
    if (e_first()) {
      fast_two_sum(enow, Q, Qn, q);
      enow = ++ei < elen ? e[ei] : 0.0;
    } else {
      fast_two_sum(fnow, Q, Qn, q);
      fnow = ++fi < flen ? f[fi] : 0.0;
    }
    Q = Qn;
    if (q != 0.0)
      h[hn++] = q;
    while (ei < elen && fi < flen) {
      if (e_first()) {
        two_sum(Q, enow, Qn, q);
        enow = ++ei < elen ? e[ei] : 0.0;
      } else {
        two_sum(Q, fnow, Qn, q);
        fnow = ++fi < flen ? f[fi] : 0.0;
      }
      Q = Qn;
      if (q != 0.0)
        h[hn++] = q;
    }
  }
  while (ei < elen) {
    two_sum(Q, enow, Qn, q);
    enow = ++ei < elen ? e[ei] : 0.0;
    Q = Qn;
    if (q != 0.0)
      h[hn++] = q;
  }
  while (fi < flen) {
    two_sum(Q, fnow, Qn, q);
    fnow = ++fi < flen ? f[fi] : 0.0;
    Q = Qn;
    if (q != 0.0)
      h[hn++] = q;
  }
  if (Q != 0.0 || hn == 0)
    h[hn++] = Q;
  return hn;
}

// h = b e (Scale-Expansion with zero elimination); h may not alias e.
int scale(int elen, const double *e, double b, double *h) {
  double Q, q, T, t, Q2;
  int hn = 0;
  two_product(e[0], b, Q, q);
  if (q != 0.0)
    h[hn++] = q;
  for (int i = 1; i < elen; ++i) {
    two_product(e[i], b, T, t);
    two_sum(Q, t, Q2, q);
    if (q != 0.0)
      h[hn++] = q;
    fast_two_sum(T, Q2, Q, q);
    if (q != 0.0)
      h[hn++] = q;
  }
  if (Q != 0.0 || hn == 0)
    h[hn++] = Q;
  return hn;
}

// The expansion as few nonadjacent components as its value needs
// (Compress), in place.
int compress(int elen, double *e) {
  int bottom = elen - 1;
  double Q = e[bottom];
  for (int i = elen - 2; i >= 0; --i) {
    double Qn, q;
    fast_two_sum(Q, e[i], Qn, q);
    if (q != 0.0) {
      e[bottom--] = Qn;
      Q = q;
    } else {
      Q = Qn;
    }
  }
  int top = 0;
  for (int i = bottom + 1; i < elen; ++i) {
    double Qn, q;
    fast_two_sum(e[i], Q, Qn, q);
    if (q != 0.0)
      e[top++] = q;
    Q = Qn;
  }
  e[top++] = Q;
  return top;
}

// An approximation of the expansion's value, and its exact sign (that of
// its largest component).
double estimate(int elen, const double *e) {
  double s = e[0];
  for (int i = 1; i < elen; ++i)
    s += e[i];
  return s;
}

// ---------------------------------------------------------------------------
// Exact numbers for stage D and the wide-range fallback (BigInt,
// exact_bigint.h): the determinants are written once (below) over either.

// An expansion on the heap, kept compressed.
class Expansion {
public:
  Expansion() : c_(1, 0.0) {}
  explicit Expansion(double x) : c_(1, x) {}
  friend Expansion operator+(const Expansion &a, const Expansion &b) {
    Expansion r;
    r.c_.resize(a.c_.size() + b.c_.size());
    r.c_.resize(sum(a.len(), a.c_.data(), b.len(), b.c_.data(), r.c_.data()));
    r.tidy();
    return r;
  }
  friend Expansion operator-(const Expansion &a, const Expansion &b) { return a + (-b); }
  Expansion operator-() const {
    Expansion r = *this;
    for (double &x : r.c_)
      x = -x;
    return r;
  }
  friend Expansion operator*(const Expansion &a, const Expansion &b) {
    // Sum over b's components of a scaled by each.
    Expansion r;
    std::vector<double> part(2 * a.c_.size()), acc;
    for (double bk : b.c_) {
      const int pn = scale(a.len(), a.c_.data(), bk, part.data());
      acc.resize(r.c_.size() + pn);
      acc.resize(sum(r.len(), r.c_.data(), pn, part.data(), acc.data()));
      r.c_.swap(acc);
    }
    r.tidy();
    return r;
  }
  int sign() const { return sign_of(c_.back()); }

private:
  int len() const { return static_cast<int>(c_.size()); }
  void tidy() { c_.resize(compress(len(), c_.data())); }
  std::vector<double> c_;
};

// The determinants, exactly, over a number type N (rows relative to the
// last point, as in the stages).  orient3d and insphere here are
// det[a-d; b-d; c-d] and the lifted 4x4 determinant of rows p - e; the
// callers turn them into the API's conventions.
template <class N> int orient2d_exact(const N *a, const N *b, const N *c) {
  const N acx = a[0] - c[0], acy = a[1] - c[1], bcx = b[0] - c[0], bcy = b[1] - c[1];
  return (acx * bcy - acy * bcx).sign();
}

template <class N> int incircle_exact(const N *a, const N *b, const N *c, const N *d) {
  const N adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
  const N cdx = c[0] - d[0], cdy = c[1] - d[1];
  const N alift = adx * adx + ady * ady, blift = bdx * bdx + bdy * bdy;
  const N clift = cdx * cdx + cdy * cdy;
  const N bc = bdx * cdy - cdx * bdy, ca = cdx * ady - adx * cdy, ab = adx * bdy - bdx * ady;
  return (alift * bc + blift * ca + clift * ab).sign();
}

template <class N> N det3(const N *p, const N *q, const N *r) {
  // p_z (q_x r_y - r_x q_y) - q_z (p_x r_y - r_x p_y) + r_z (p_x q_y - q_x p_y)
  return p[2] * (q[0] * r[1] - r[0] * q[1]) - q[2] * (p[0] * r[1] - r[0] * p[1]) +
         r[2] * (p[0] * q[1] - q[0] * p[1]);
}

template <class N> int orient3d_exact(const N *a, const N *b, const N *c, const N *d) {
  N ad[3], bd[3], cd[3];
  for (int k = 0; k < 3; ++k) {
    ad[k] = a[k] - d[k];
    bd[k] = b[k] - d[k];
    cd[k] = c[k] - d[k];
  }
  return det3(ad, bd, cd).sign();
}

template <class N> int insphere_exact(const N *a, const N *b, const N *c, const N *d, const N *e) {
  N ae[3], be[3], ce[3], de[3];
  for (int k = 0; k < 3; ++k) {
    ae[k] = a[k] - e[k];
    be[k] = b[k] - e[k];
    ce[k] = c[k] - e[k];
    de[k] = d[k] - e[k];
  }
  auto lift = [](const N *p) { return p[0] * p[0] + p[1] * p[1] + p[2] * p[2]; };
  // Along the lift column: -L_a |b c d| + L_b |a c d| - L_c |a b d| + L_d |a b c|.
  const N det = (lift(de) * det3(ae, be, ce) - lift(ce) * det3(ae, be, de)) +
                (lift(be) * det3(ae, ce, de) - lift(ae) * det3(be, ce, de));
  return det.sign();
}

// ---------------------------------------------------------------------------
// The range check before stages B-D.

// How the coordinates of one call must be treated for exact expansion
// arithmetic: scaled by 2^k (k = 0: as they are), or, when wide, by big
// integers in units of 2^m.
struct Range {
  bool wide = false;
  int k = 0, m = 0;
};

Range range_of(const double *x, int nx, int degree) {
  int m = 1 << 20, E = -(1 << 20);
  for (int i = 0; i < nx; ++i) {
    if (x[i] == 0.0)
      continue;
    int e;
    const double f = std::frexp(std::fabs(x[i]), &e);
    const uint64_t mant = static_cast<uint64_t>(std::ldexp(f, 53));
    m = std::min(m, e - 53 + __builtin_ctzll(mant));
    E = std::max(E, e);
  }
  Range r;
  if (E == -(1 << 20))
    return r; // all zero
  r.m = m;
  // k must satisfy degree (m + k) >= -1074 and degree (E + k + 1) <= 983.
  const int kmin = -(1074 / degree) - m; // ceil(-1074 / degree) - m
  const int kmax = 983 / degree - E - 1; // floor(983 / degree) - E - 1
  if (kmin > kmax) {
    r.wide = true;
    return r;
  }
  r.k = std::min(std::max(0, kmin), kmax);
  return r;
}

// ---------------------------------------------------------------------------
// The stages, for coordinates within range (see the top of the file).

int orient2d_adapt(const double *a, const double *b, const double *c) {
  const double acx = a[0] - c[0], bcx = b[0] - c[0], acy = a[1] - c[1], bcy = b[1] - c[1];
  const double l = acx * bcy, r = acy * bcx;
  double det = l - r;
  const double detsum = std::fabs(l) + std::fabs(r);
  if (std::fabs(det) >= kO2A * detsum)
    return sign_of(det); // (A, for scaled input)
  // B
  double l1, l0, r1, r0, B[4];
  two_product(acx, bcy, l1, l0);
  two_product(acy, bcx, r1, r0);
  two_two_diff(l1, l0, r1, r0, B);
  det = estimate(4, B);
  double bound = kO2B * detsum;
  if (det >= bound || -det >= bound)
    return sign_of(det);
  const double acxt = diff_tail(a[0], c[0], acx), bcxt = diff_tail(b[0], c[0], bcx);
  const double acyt = diff_tail(a[1], c[1], acy), bcyt = diff_tail(b[1], c[1], bcy);
  if (acxt == 0.0 && acyt == 0.0 && bcxt == 0.0 && bcyt == 0.0)
    return sign_of(compress(4, B), B);
  // C
  bound = kO2C * detsum + kResultErr * std::fabs(det);
  det += (acx * bcyt + bcy * acxt) - (acy * bcxt + bcx * acyt);
  if (det >= bound || -det >= bound)
    return sign_of(det);
  // D
  const Expansion A[2] = {Expansion(a[0]), Expansion(a[1])};
  const Expansion Bx[2] = {Expansion(b[0]), Expansion(b[1])};
  const Expansion C[2] = {Expansion(c[0]), Expansion(c[1])};
  return orient2d_exact(A, Bx, C);
}

int incircle_adapt(const double *a, const double *b, const double *c, const double *d) {
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double alift = adx * adx + ady * ady, blift = bdx * bdx + bdy * bdy;
  const double clift = cdx * cdx + cdy * cdy;
  double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  if (std::fabs(det) > kICA * permanent)
    return sign_of(det);
  // B: each term lift * minor as (dx^2 + dy^2) * minor, all exact.
  auto minor = [](double px, double qy, double qx, double py, double *h) {
    double x1, x0, y1, y0;
    two_product(px, qy, x1, x0);
    two_product(qx, py, y1, y0);
    two_two_diff(x1, x0, y1, y0, h);
  };
  auto term = [](const double *m4, double dx, double dy, double *h) {
    double t8[8], t16a[16], t16b[16];
    int n8 = scale(4, m4, dx, t8);
    const int na = scale(n8, t8, dx, t16a);
    n8 = scale(4, m4, dy, t8);
    const int nb = scale(n8, t8, dy, t16b);
    return sum(na, t16a, nb, t16b, h);
  };
  double bc[4], ca[4], ab[4], adet[32], bdet[32], cdet[32], abdet[64], fin[96];
  minor(bdx, cdy, cdx, bdy, bc);
  minor(cdx, ady, adx, cdy, ca);
  minor(adx, bdy, bdx, ady, ab);
  const int an = term(bc, adx, ady, adet), bn = term(ca, bdx, bdy, bdet);
  const int cn = term(ab, cdx, cdy, cdet);
  const int abn = sum(an, adet, bn, bdet, abdet);
  const int finn = sum(abn, abdet, cn, cdet, fin);
  det = estimate(finn, fin);
  double bound = kICB * permanent;
  if (det >= bound || -det >= bound)
    return sign_of(det);
  const double adxt = diff_tail(a[0], d[0], adx), adyt = diff_tail(a[1], d[1], ady);
  const double bdxt = diff_tail(b[0], d[0], bdx), bdyt = diff_tail(b[1], d[1], bdy);
  const double cdxt = diff_tail(c[0], d[0], cdx), cdyt = diff_tail(c[1], d[1], cdy);
  if (adxt == 0.0 && adyt == 0.0 && bdxt == 0.0 && bdyt == 0.0 && cdxt == 0.0 && cdyt == 0.0)
    return sign_of(finn, fin);
  // C: the first-order terms of each lift * minor in the tails.
  bound = kICC * permanent + kResultErr * std::fabs(det);
  det += ((adx * adx + ady * ady) * ((bdx * cdyt + cdy * bdxt) - (bdy * cdxt + cdx * bdyt)) +
          2.0 * (adx * adxt + ady * adyt) * (bdx * cdy - bdy * cdx)) +
         ((bdx * bdx + bdy * bdy) * ((cdx * adyt + ady * cdxt) - (cdy * adxt + adx * cdyt)) +
          2.0 * (bdx * bdxt + bdy * bdyt) * (cdx * ady - cdy * adx)) +
         ((cdx * cdx + cdy * cdy) * ((adx * bdyt + bdy * adxt) - (ady * bdxt + bdx * adyt)) +
          2.0 * (cdx * cdxt + cdy * cdyt) * (adx * bdy - ady * bdx));
  if (det >= bound || -det >= bound)
    return sign_of(det);
  // D
  const Expansion A[2] = {Expansion(a[0]), Expansion(a[1])};
  const Expansion Bx[2] = {Expansion(b[0]), Expansion(b[1])};
  const Expansion C[2] = {Expansion(c[0]), Expansion(c[1])};
  const Expansion D[2] = {Expansion(d[0]), Expansion(d[1])};
  return incircle_exact(A, Bx, C, D);
}

// Returns the sign of det[a-d; b-d; c-d].
int orient3d_adapt(const double *a, const double *b, const double *c, const double *d) {
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
  if (std::fabs(det) > kO3A * permanent)
    return sign_of(det);
  // B
  auto minor = [](double px, double qy, double qx, double py, double *h) {
    double x1, x0, y1, y0;
    two_product(px, qy, x1, x0);
    two_product(qx, py, y1, y0);
    two_two_diff(x1, x0, y1, y0, h);
  };
  double bc[4], ca[4], ab[4], adet[8], bdet[8], cdet[8], abdet[16], fin[24];
  minor(bdx, cdy, cdx, bdy, bc);
  minor(cdx, ady, adx, cdy, ca);
  minor(adx, bdy, bdx, ady, ab);
  const int an = scale(4, bc, adz, adet), bn = scale(4, ca, bdz, bdet);
  const int cn = scale(4, ab, cdz, cdet);
  const int abn = sum(an, adet, bn, bdet, abdet);
  const int finn = sum(abn, abdet, cn, cdet, fin);
  det = estimate(finn, fin);
  double bound = kO3B * permanent;
  if (det >= bound || -det >= bound)
    return sign_of(det);
  const double adxt = diff_tail(a[0], d[0], adx), bdxt = diff_tail(b[0], d[0], bdx);
  const double cdxt = diff_tail(c[0], d[0], cdx), adyt = diff_tail(a[1], d[1], ady);
  const double bdyt = diff_tail(b[1], d[1], bdy), cdyt = diff_tail(c[1], d[1], cdy);
  const double adzt = diff_tail(a[2], d[2], adz), bdzt = diff_tail(b[2], d[2], bdz);
  const double cdzt = diff_tail(c[2], d[2], cdz);
  if (adxt == 0.0 && bdxt == 0.0 && cdxt == 0.0 && adyt == 0.0 && bdyt == 0.0 && cdyt == 0.0 &&
      adzt == 0.0 && bdzt == 0.0 && cdzt == 0.0)
    return sign_of(finn, fin);
  // C
  bound = kO3C * permanent + kResultErr * std::fabs(det);
  det += (adz * ((bdx * cdyt + cdy * bdxt) - (bdy * cdxt + cdx * bdyt)) +
          adzt * (bdx * cdy - bdy * cdx)) +
         (bdz * ((cdx * adyt + ady * cdxt) - (cdy * adxt + adx * cdyt)) +
          bdzt * (cdx * ady - cdy * adx)) +
         (cdz * ((adx * bdyt + bdy * adxt) - (ady * bdxt + bdx * adyt)) +
          cdzt * (adx * bdy - ady * bdx));
  if (det >= bound || -det >= bound)
    return sign_of(det);
  // D
  Expansion A[3], Bx[3], C[3], D[3];
  for (int k = 0; k < 3; ++k) {
    A[k] = Expansion(a[k]);
    Bx[k] = Expansion(b[k]);
    C[k] = Expansion(c[k]);
    D[k] = Expansion(d[k]);
  }
  return orient3d_exact(A, Bx, C, D);
}

// Returns the sign of the 4x4 determinant of rows (p - e, |p - e|^2), p = a, b, c, d.
int insphere_adapt(const double *a, const double *b, const double *c, const double *d,
                   const double *e) {
  const double *P[4] = {a, b, c, d};
  double h[4][3]; // the differences p - e (heads)
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      h[i][k] = P[i][k] - e[k];
  // xy minors of rows i, j: h_i.x h_j.y - h_j.x h_i.y, and their permanents.
  auto xy = [&](int i, int j) { return h[i][0] * h[j][1] - h[j][0] * h[i][1]; };
  auto pxy = [&](int i, int j) {
    return std::fabs(h[i][0] * h[j][1]) + std::fabs(h[j][0] * h[i][1]);
  };
  // 3x3 minor of rows i, j, k along z (det3 above) and its permanent.
  auto m3 = [&](int i, int j, int k) {
    return h[i][2] * xy(j, k) - h[j][2] * xy(i, k) + h[k][2] * xy(i, j);
  };
  auto p3 = [&](int i, int j, int k) {
    return std::fabs(h[i][2]) * pxy(j, k) + std::fabs(h[j][2]) * pxy(i, k) +
           std::fabs(h[k][2]) * pxy(i, j);
  };
  double L[4];
  for (int i = 0; i < 4; ++i)
    L[i] = h[i][0] * h[i][0] + h[i][1] * h[i][1] + h[i][2] * h[i][2];
  double det =
      (L[3] * m3(0, 1, 2) - L[2] * m3(0, 1, 3)) + (L[1] * m3(0, 2, 3) - L[0] * m3(1, 2, 3));
  const double permanent =
      L[3] * p3(0, 1, 2) + L[2] * p3(0, 1, 3) + L[1] * p3(0, 2, 3) + L[0] * p3(1, 2, 3);
  if (std::fabs(det) > kISA * permanent)
    return sign_of(det);
  // B: the same determinant of the heads, exactly.
  double mxy[4][4][4]; // exact xy minors (4 components, padded with zeros)
  int nxy[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      double x1, x0, y1, y0;
      two_product(h[i][0], h[j][1], x1, x0);
      two_product(h[j][0], h[i][1], y1, y0);
      two_two_diff(x1, x0, y1, y0, mxy[i][j]);
      nxy[i][j] = 4;
    }
  // exact 3x3 minor of rows i < j < k: up to 24 components.
  auto em3 = [&](int i, int j, int k, double *out) {
    double t1[8], t2[8], t3[8], t12[16];
    const int n1 = scale(nxy[j][k], mxy[j][k], h[i][2], t1);
    const int n2 = scale(nxy[i][k], mxy[i][k], -h[j][2], t2);
    const int n3 = scale(nxy[i][j], mxy[i][j], h[k][2], t3);
    const int n12 = sum(n1, t1, n2, t2, t12);
    return sum(n12, t12, n3, t3, out);
  };
  // exact L_i * minor (L = x^2 + y^2 + z^2 of row i): up to 288 components.
  auto lterm = [&](int i, const double *m, int mn, double sgn, double *out) {
    double s1[48], s2[96], acc[288], t[288];
    int an = 0;
    for (int k = 0; k < 3; ++k) {
      const int n1 = scale(mn, m, sgn * h[i][k], s1);
      const int n2 = scale(n1, s1, h[i][k], s2);
      if (an == 0) {
        std::copy(s2, s2 + n2, acc);
        an = n2;
      } else {
        an = sum(an, acc, n2, s2, t);
        std::copy(t, t + an, acc);
      }
    }
    std::copy(acc, acc + an, out);
    return an;
  };
  double mabc[24], mabd[24], macd[24], mbcd[24];
  const int nabc = em3(0, 1, 2, mabc), nabd = em3(0, 1, 3, mabd);
  const int nacd = em3(0, 2, 3, macd), nbcd = em3(1, 2, 3, mbcd);
  double t1[288], t2[288], t3[288], t4[288], t12[576], t34[576], fin[1152];
  const int n1 = lterm(3, mabc, nabc, 1.0, t1), n2 = lterm(2, mabd, nabd, -1.0, t2);
  const int n3 = lterm(1, macd, nacd, 1.0, t3), n4 = lterm(0, mbcd, nbcd, -1.0, t4);
  const int n12 = sum(n1, t1, n2, t2, t12), n34 = sum(n3, t3, n4, t4, t34);
  const int finn = sum(n12, t12, n34, t34, fin);
  det = estimate(finn, fin);
  double bound = kISB * permanent;
  if (det >= bound || -det >= bound)
    return sign_of(det);
  double t[4][3]; // the differences' tails
  bool exact = true;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      t[i][k] = diff_tail(P[i][k], e[k], h[i][k]);
      exact = exact && t[i][k] == 0.0;
    }
  if (exact)
    return sign_of(finn, fin);
  // C: det + sum of (d det / d h) t, the first order in the tails, in
  // floating point: each quantity carried with its first-order change.
  auto dxy = [&](int i, int j) {
    return (t[i][0] * h[j][1] + h[i][0] * t[j][1]) - (t[j][0] * h[i][1] + h[j][0] * t[i][1]);
  };
  auto dm3 = [&](int i, int j, int k) {
    return (t[i][2] * xy(j, k) + h[i][2] * dxy(j, k)) - (t[j][2] * xy(i, k) + h[j][2] * dxy(i, k)) +
           (t[k][2] * xy(i, j) + h[k][2] * dxy(i, j));
  };
  auto dL = [&](int i) {
    return 2.0 * (h[i][0] * t[i][0] + h[i][1] * t[i][1] + h[i][2] * t[i][2]);
  };
  bound = kISC * permanent + kResultErr * std::fabs(det);
  det +=
      ((dL(3) * m3(0, 1, 2) + L[3] * dm3(0, 1, 2)) - (dL(2) * m3(0, 1, 3) + L[2] * dm3(0, 1, 3))) +
      ((dL(1) * m3(0, 2, 3) + L[1] * dm3(0, 2, 3)) - (dL(0) * m3(1, 2, 3) + L[0] * dm3(1, 2, 3)));
  if (det >= bound || -det >= bound)
    return sign_of(det);
  // D
  Expansion X[5][3];
  const double *Q[5] = {a, b, c, d, e};
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 3; ++k)
      X[i][k] = Expansion(Q[i][k]);
  return insphere_exact(X[0], X[1], X[2], X[3], X[4]);
}

// ---------------------------------------------------------------------------
// Outside stage A: the range check, then the adaptive stages on the
// (scaled) coordinates or the big integers.

template <int NP, int DIM, class Adapt, class Exact>
int slow_path(const double *const *p, int degree, Adapt adapt, Exact exact_big) {
  double x[NP * DIM];
  for (int i = 0; i < NP; ++i)
    for (int k = 0; k < DIM; ++k)
      x[DIM * i + k] = p[i][k];
  const Range r = range_of(x, NP * DIM, degree);
  if (r.wide) {
    BigInt big[NP][DIM];
    for (int i = 0; i < NP; ++i)
      for (int k = 0; k < DIM; ++k)
        big[i][k] = BigInt(x[DIM * i + k], r.m);
    return exact_big(big);
  }
  if (r.k != 0)
    for (double &v : x)
      v = std::ldexp(v, r.k);
  return adapt(x);
}

} // namespace

__attribute__((noinline)) int orient2d_slow(const double *a, const double *b, const double *c) {
  const double *p[3] = {a, b, c};
  return slow_path<3, 2>(
      p, 2, [](const double *x) { return orient2d_adapt(x, x + 2, x + 4); },
      [](BigInt(*B)[2]) { return orient2d_exact(B[0], B[1], B[2]); });
}

__attribute__((noinline)) int incircle_slow(const double *a, const double *b, const double *c,
                                            const double *d) {
  const double *p[4] = {a, b, c, d};
  return slow_path<4, 2>(
      p, 4, [](const double *x) { return incircle_adapt(x, x + 2, x + 4, x + 6); },
      [](BigInt(*B)[2]) { return incircle_exact(B[0], B[1], B[2], B[3]); });
}

__attribute__((noinline)) int orient3d_slow(const double *a, const double *b, const double *c,
                                            const double *d) {
  const double *p[4] = {a, b, c, d};
  return slow_path<4, 3>(
      p, 3, [](const double *x) { return orient3d_adapt(x, x + 3, x + 6, x + 9); },
      [](BigInt(*B)[3]) { return orient3d_exact(B[0], B[1], B[2], B[3]); });
}

__attribute__((noinline)) int insphere_slow(const double *a, const double *b, const double *c,
                                            const double *d, const double *e) {
  const double *p[5] = {a, b, c, d, e};
  return slow_path<5, 3>(
      p, 5, [](const double *x) { return insphere_adapt(x, x + 3, x + 6, x + 9, x + 12); },
      [](BigInt(*B)[3]) { return insphere_exact(B[0], B[1], B[2], B[3], B[4]); });
}

} // namespace tessera::exact

// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The big integers of the exact predicates' wide-range fallback
// (exact_predicates_adapt.cpp): plain sign-and-magnitude arithmetic, apart
// from the expansion arithmetic of the adaptive stages, which it shares
// nothing with.  Internal to the core (not installed).
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace tessera::exact {

// A signed integer of any size (sign and magnitude in 32-bit limbs, least
// significant first): the fallback for coordinates whose exponents span
// more than expansions can hold without underflow.
class BigInt {
public:
  BigInt() = default;
  // x 2^-m, for x a multiple of 2^m.
  BigInt(double x, int m) {
    if (x == 0.0)
      return;
    int e;
    const double f = std::frexp(std::fabs(x), &e); // |x| = f 2^e, f in [0.5, 1)
    uint64_t mant = static_cast<uint64_t>(std::ldexp(f, 53));
    int shift = e - 53 - m; // >= 0 for x a multiple of 2^m
    while (shift < 0) {     // (only trailing zero bits drop)
      mant >>= 1;
      ++shift;
    }
    mag_.assign(shift / 32 + 3, 0);
    const int w = shift / 32, b = shift % 32;
    const unsigned __int128 v = static_cast<unsigned __int128>(mant) << b;
    for (int k = 0; k < 3; ++k)
      mag_[w + k] = static_cast<uint32_t>(v >> (32 * k));
    neg_ = x < 0.0;
    trim();
  }
  friend BigInt operator+(const BigInt &a, const BigInt &b) {
    if (a.neg_ == b.neg_)
      return with_sign(add(a.mag_, b.mag_), a.neg_);
    if (cmp(a.mag_, b.mag_) >= 0)
      return with_sign(subtract(a.mag_, b.mag_), a.neg_);
    return with_sign(subtract(b.mag_, a.mag_), b.neg_);
  }
  friend BigInt operator-(const BigInt &a, const BigInt &b) { return a + (-b); }
  BigInt operator-() const {
    BigInt r = *this;
    if (!r.mag_.empty())
      r.neg_ = !r.neg_;
    return r;
  }
  friend BigInt operator*(const BigInt &a, const BigInt &b) {
    if (a.mag_.empty() || b.mag_.empty())
      return BigInt();
    std::vector<uint32_t> r(a.mag_.size() + b.mag_.size(), 0);
    for (size_t i = 0; i < a.mag_.size(); ++i) {
      uint64_t carry = 0;
      for (size_t j = 0; j < b.mag_.size(); ++j) {
        const uint64_t t = static_cast<uint64_t>(a.mag_[i]) * b.mag_[j] + r[i + j] + carry;
        r[i + j] = static_cast<uint32_t>(t);
        carry = t >> 32;
      }
      r[i + b.mag_.size()] = static_cast<uint32_t>(carry);
    }
    return with_sign(std::move(r), a.neg_ != b.neg_);
  }
  int sign() const { return mag_.empty() ? 0 : (neg_ ? -1 : 1); }

private:
  using Mag = std::vector<uint32_t>;
  static BigInt with_sign(Mag m, bool neg) {
    BigInt r;
    r.mag_ = std::move(m);
    r.trim();
    r.neg_ = !r.mag_.empty() && neg;
    return r;
  }
  void trim() {
    while (!mag_.empty() && mag_.back() == 0)
      mag_.pop_back();
  }
  static int cmp(const Mag &a, const Mag &b) {
    if (a.size() != b.size())
      return a.size() < b.size() ? -1 : 1;
    for (size_t i = a.size(); i-- > 0;)
      if (a[i] != b[i])
        return a[i] < b[i] ? -1 : 1;
    return 0;
  }
  static Mag add(const Mag &a, const Mag &b) {
    const Mag &l = a.size() >= b.size() ? a : b, &s = a.size() >= b.size() ? b : a;
    Mag r(l.size() + 1, 0);
    uint64_t carry = 0;
    for (size_t i = 0; i < l.size(); ++i) {
      const uint64_t t = static_cast<uint64_t>(l[i]) + (i < s.size() ? s[i] : 0) + carry;
      r[i] = static_cast<uint32_t>(t);
      carry = t >> 32;
    }
    r[l.size()] = static_cast<uint32_t>(carry);
    return r;
  }
  static Mag subtract(const Mag &a, const Mag &b) { // |a| >= |b|
    Mag r(a.size(), 0);
    int64_t borrow = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      int64_t t = static_cast<int64_t>(a[i]) - (i < b.size() ? b[i] : 0) - borrow;
      borrow = t < 0;
      if (t < 0)
        t += static_cast<int64_t>(1) << 32;
      r[i] = static_cast<uint32_t>(t);
    }
    return r;
  }
  Mag mag_;
  bool neg_ = false;
};

} // namespace tessera::exact

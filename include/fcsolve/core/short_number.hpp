// A double as three significant digits, in the form printf's "%.3g" uses
// ("0.0123", "4.56e-07", "12", "1e+03"), for reports that are built on every
// solve (auto's stage report). snprintf takes about a thousand instructions
// per number (its exact decimal conversion); this takes about a hundred, and
// unlike std::to_chars it brings no large table-driven code that a fresh
// process would run cold. The digits are those of x rounded to three
// significant digits in double arithmetic: they can differ from printf's in
// the last digit only when x lies within a few ulps of a rounding tie.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

namespace fcsolve {

namespace detail {

/// a 10^k: one correctly rounded product or quotient by an exact power of
/// ten (10^0 to 10^22 are exact doubles), else std::pow in two factors
/// (10^k alone overflows below 10^-308).
inline double times_power_of_ten(double a, int k) {
  static constexpr double exact[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  if (k >= 0 && k <= 22) return a * exact[k];
  if (k < 0 && k >= -22) return a / exact[-k];
  return k > 300 ? a * 1e300 * std::pow(10.0, k - 300) : a * std::pow(10.0, k);
}

}  // namespace detail

/// Characters write_short_number writes at most ("-d.dde-308").
inline constexpr std::size_t kShortNumberChars = 10;

/// Writes x at c as "%.3g" writes it, "null" when x is not finite (the
/// reports are JSON); returns the end. At most kShortNumberChars.
inline char* write_short_number(char* c, double x) {
  if (!std::isfinite(x)) {
    for (const char* t = "null"; *t; ++t) *c++ = *t;
    return c;
  }
  if (x == 0) {
    if (std::signbit(x)) *c++ = '-';
    *c++ = '0';
    return c;
  }
  if (x < 0) *c++ = '-';
  const double a = std::fabs(x);
  // a = digits * 10^(e - 2) with 100 <= digits <= 999: e from the binary
  // exponent (log10 2 = 0.30103), then corrected so that 100 <= a 10^(2-e) < 1000
  int e = int(std::floor(std::ilogb(a) * 0.30102999566398120));
  double scaled = detail::times_power_of_ten(a, 2 - e);
  while (scaled >= 1000) scaled = detail::times_power_of_ten(a, 2 - ++e);
  while (scaled < 100) scaled = detail::times_power_of_ten(a, 2 - --e);
  int n = int(std::nearbyint(scaled));
  if (n >= 1000) {  // 999.5 rounds up to the next decade
    n = 100;
    ++e;
  }
  const char d[3] = {char('0' + n / 100), char('0' + n / 10 % 10), char('0' + n % 10)};
  const int kept = d[2] != '0' ? 3 : d[1] != '0' ? 2 : 1;  // %g drops trailing zeros
  if (e < -4 || e >= 3) {  // %g's scientific form: d.dde+XX
    *c++ = d[0];
    if (kept > 1) {
      *c++ = '.';
      for (int k = 1; k < kept; ++k) *c++ = d[k];
    }
    *c++ = 'e';
    *c++ = e < 0 ? '-' : '+';
    const int p = e < 0 ? -e : e;
    if (p >= 100) *c++ = char('0' + p / 100);
    *c++ = char('0' + p / 10 % 10);
    *c++ = char('0' + p % 10);
  } else if (e >= 0) {  // e + 1 digits before the point
    const int whole = e + 1;
    for (int k = 0; k < whole; ++k) *c++ = d[k];
    if (kept > whole) {
      *c++ = '.';
      for (int k = whole; k < kept; ++k) *c++ = d[k];
    }
  } else {  // -4 <= e <= -1: 0.000ddd
    *c++ = '0';
    *c++ = '.';
    for (int k = -1; k > e; --k) *c++ = '0';
    for (int k = 0; k < kept; ++k) *c++ = d[k];
  }
  return c;
}

/// Appends x to out as "%.3g" writes it; "null" when x is not finite.
inline void append_short_number(std::string& out, double x) {
  char buf[kShortNumberChars];
  out.append(buf, std::size_t(write_short_number(buf, x) - buf));
}

}  // namespace fcsolve

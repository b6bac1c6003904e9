// The stage reports' number format (core/short_number.hpp) against
// printf's "%.3g", which it stands in for.
#include <fcsolve/core/short_number.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

using fcsolve::append_short_number;

namespace {

std::string ours(double x) {
  std::string s;
  append_short_number(s, x);
  return s;
}

std::string printf_3g(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

/// x lies within a few ulps of the midpoint of two three-digit decimals
/// (the one case where double arithmetic may round the other way).
bool near_a_tie(double x, const std::string& a, const std::string& b) {
  const double va = std::strtod(a.c_str(), nullptr), vb = std::strtod(b.c_str(), nullptr);
  return std::fabs(x - 0.5 * (va + vb)) <= 1e-13 * std::fabs(x);
}

}  // namespace

TEST_CASE("short numbers are printf's %.3g", "[report]") {
  for (double x : {1.0, -1.0, 10.0, 100.0, 999.0, 999.4, 999.6, 1000.0, 12345.0, 0.1, 0.5, 0.01234,
                   1e-4, 9.99e-5, 1.5e-5, 1e-300, 5e-324, 2.2250738585072014e-308, 1e300, 1.7e308,
                   99.96, 0.000999, 123.0, 120.0, 1.2e-7, -4.56e-7})
    CHECK(ours(x) == printf_3g(x));
  CHECK(ours(0.0) == "0");
  // the longest forms fit in kShortNumberChars
  for (double x : {-1.23e-308, -4.9e-324, -9.99e-100, -0.000123})
    CHECK(ours(x).size() <= fcsolve::kShortNumberChars);
  CHECK(ours(-1.23e-308) == "-1.23e-308");
  CHECK(ours(std::numeric_limits<double>::infinity()) == "null");
  CHECK(ours(std::numeric_limits<double>::quiet_NaN()) == "null");

  // every decade of the double range, both signs, subnormals included
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> mantissa(1.0, 10.0);
  std::uniform_int_distribution<int> exponent(-323, 307);
  int differ = 0;
  for (int k = 0; k < 200000; ++k) {
    double x = mantissa(random) * std::pow(10.0, exponent(random));
    if (k % 2) x = -x;
    const std::string a = ours(x), b = printf_3g(x);
    CHECK(a.size() <= fcsolve::kShortNumberChars);  // MessageWriter reserves no more
    if (a == b) continue;
    ++differ;
    INFO(x << ": " << a << " against " << b);
    CHECK(near_a_tie(x, a, b));
  }
  CHECK(differ <= 2);
}

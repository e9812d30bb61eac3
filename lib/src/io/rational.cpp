// Decimal rationals of any length to the exact double they denote
// (docs/design.md §9: every coordinate of the data is num / 2^k with |num| < 2^53).

#include <cmath>
#include <stdexcept>
#include <string>

#include "batchccd/io.hpp"
#include "exact/integer.hpp"
#include "io/text_input.hpp"

namespace batchccd {

namespace {

using exact::Integer;
using io_detail::all_digits;
using io_detail::in_quotes;
using io_detail::trim;

// Parses [+-]digits; GMP's own parser would also accept inner whitespace.
void parse_decimal(std::string_view text, const char* role, Integer& out) {
  const std::string_view trimmed = trim(text);
  std::string_view digits = trimmed;
  const bool negative = !digits.empty() && digits.front() == '-';
  if (!digits.empty() && (digits.front() == '-' || digits.front() == '+')) digits.remove_prefix(1);
  if (!all_digits(digits))
    throw std::invalid_argument(std::string(role) + " " + in_quotes(trimmed) + " is not a decimal integer");
  mpz_set_str(out.get(), std::string(digits).c_str(), 10);
  if (negative) mpz_neg(out.get(), out.get());
}

std::string fraction_text(std::string_view numerator, std::string_view denominator) {
  return in_quotes(std::string(trim(numerator)) + "/" + std::string(trim(denominator)), 100);
}

// Smallest and largest binary exponents a bit of a finite double can have.
constexpr long lowest_bit_exponent = -1074;  // the least subnormal, 2^-1074
constexpr long highest_bit_exponent = 1023;  // the leading bit of DBL_MAX
constexpr unsigned long significand_bits = 53;

}  // namespace

double exact_double_from_rational(std::string_view numerator, std::string_view denominator) {
  Integer num;
  Integer den;
  parse_decimal(numerator, "numerator", num);
  parse_decimal(denominator, "denominator", den);
  const std::string value = fraction_text(numerator, denominator);
  if (mpz_sgn(den.get()) <= 0) throw std::invalid_argument(value + ": the denominator must be positive");
  if (mpz_sgn(num.get()) == 0) return 0.0;

  Integer divisor;
  mpz_gcd(divisor.get(), num.get(), den.get());
  mpz_divexact(num.get(), num.get(), divisor.get());
  mpz_divexact(den.get(), den.get(), divisor.get());
  if (mpz_popcount(den.get()) != 1)
    throw std::invalid_argument(value + " is not a double: the reduced denominator is not a power of two");

  // Reduced, the value is odd * 2^exponent.
  const long trailing_zeros = static_cast<long>(mpz_scan1(num.get(), 0));
  mpz_tdiv_q_2exp(num.get(), num.get(), static_cast<mp_bitcnt_t>(trailing_zeros));
  const long exponent = trailing_zeros - static_cast<long>(mpz_scan1(den.get(), 0));
  const unsigned long bits = static_cast<unsigned long>(mpz_sizeinbase(num.get(), 2));
  if (bits > significand_bits)
    throw std::invalid_argument(value + " is not a double: it needs " + std::to_string(bits) +
                                " significant bits (at most 53)");
  if (exponent < lowest_bit_exponent)
    throw std::invalid_argument(value + " is not a double: it has bits below 2^-1074, the smallest subnormal");
  if (exponent + static_cast<long>(bits) - 1 > highest_bit_exponent)
    throw std::invalid_argument(value + " is not a double: it is beyond the double range");

  // Both steps are exact: the odd part fits 53 bits, the scaled value is a double.
  return std::ldexp(mpz_get_d(num.get()), static_cast<int>(exponent));
}

}  // namespace batchccd

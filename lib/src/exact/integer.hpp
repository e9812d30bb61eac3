#pragma once

#include <cstddef>
#include <utility>

#include <gmp.h>

// An arbitrary-precision integer: a small owning wrapper over GMP's mpz_t
// (the C library only, so a static libbatchccd needs nothing beyond -lgmp).
// The exact stage (docs/design.md §6) computes on these alone.
namespace batchccd::exact {

class Integer {
 public:
  Integer() { mpz_init(value_); }  // no allocation until a value is stored
  Integer(long value) { mpz_init_set_si(value_, value); }  // implicit: Integer(0) reads like 0
  Integer(const Integer& other) { mpz_init_set(value_, other.value_); }
  Integer(Integer&& other) noexcept {
    mpz_init(value_);
    mpz_swap(value_, other.value_);
  }
  Integer& operator=(const Integer& other) {
    mpz_set(value_, other.value_);
    return *this;
  }
  Integer& operator=(Integer&& other) noexcept {
    mpz_swap(value_, other.value_);
    return *this;
  }
  ~Integer() { mpz_clear(value_); }

  mpz_ptr get() { return value_; }
  mpz_srcptr get() const { return value_; }

  int sign() const { return mpz_sgn(value_); }
  bool is_zero() const { return sign() == 0; }
  // Bits of |value| (1 for zero): |value| < 2^bits.
  std::size_t bits() const { return mpz_sizeinbase(value_, 2); }

  Integer& operator+=(const Integer& other) {
    mpz_add(value_, value_, other.value_);
    return *this;
  }
  Integer& operator-=(const Integer& other) {
    mpz_sub(value_, value_, other.value_);
    return *this;
  }
  Integer& operator*=(const Integer& other) {
    mpz_mul(value_, value_, other.value_);
    return *this;
  }
  // this += a * b, without a temporary.
  void add_product(const Integer& a, const Integer& b) { mpz_addmul(value_, a.value_, b.value_); }
  void subtract_product(const Integer& a, const Integer& b) {
    mpz_submul(value_, a.value_, b.value_);
  }
  void shift_left(unsigned long bits) { mpz_mul_2exp(value_, value_, bits); }
  void negate() { mpz_neg(value_, value_); }

  friend Integer operator+(Integer a, const Integer& b) { return std::move(a += b); }
  friend Integer operator-(Integer a, const Integer& b) { return std::move(a -= b); }
  friend Integer operator*(const Integer& a, const Integer& b) {
    Integer product;
    mpz_mul(product.value_, a.value_, b.value_);
    return product;
  }
  friend Integer operator-(Integer a) {
    a.negate();
    return a;
  }
  friend bool operator==(const Integer& a, const Integer& b) {
    return mpz_cmp(a.value_, b.value_) == 0;
  }

 private:
  mpz_t value_;
};

inline Integer shifted_left(Integer value, unsigned long bits) {
  value.shift_left(bits);
  return value;
}

// a / b where b divides a exactly.
inline Integer exact_quotient(const Integer& a, const Integer& b) {
  Integer quotient;
  mpz_divexact(quotient.get(), a.get(), b.get());
  return quotient;
}

inline Integer greatest_common_divisor(const Integer& a, const Integer& b) {
  Integer divisor;
  mpz_gcd(divisor.get(), a.get(), b.get());
  return divisor;
}

}  // namespace batchccd::exact

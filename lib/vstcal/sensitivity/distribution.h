// The distribution of one scalar parameter, given as its inverse CDF (quantile function) of a
// uniform u ∈ (0, 1): θ = Q(u). One form serves Monte Carlo (u from Philox) and quasi-Monte Carlo
// (u from a Sobol sequence) alike, and keeps the Sobol estimators' "resample a column" meaning.
#pragma once

#include <string>
#include <variant>

namespace vstcal {

class Distribution {
 public:
  struct Normal {
    double mean;
    double sigma;  // ≥ 0; 0 behaves as Fixed(mean)
  };
  struct Uniform {
    double lo;
    double hi;  // lo ≤ hi
  };
  // A bias: always the same value; it contributes to the mean of the outputs, not to their spread.
  struct Fixed {
    double value;
  };

  // Throw InputError for non-finite arguments, σ < 0 or lo > hi.
  static Distribution MakeNormal(double mean, double sigma);
  static Distribution MakeUniform(double lo, double hi);
  static Distribution MakeFixed(double value);

  // Q(u) for u ∈ (0, 1) (InputError outside). Normal uses AS 241 (normal_quantile.h).
  double Quantile(double u) const;
  double Mean() const;
  double Variance() const;
  double StandardDeviation() const;
  // True when every draw is the same value (Fixed, σ = 0, lo = hi).
  bool IsConstant() const;
  // "normal(0, 0.5)", "uniform(-3.14159, 3.14159)", "fixed(2)": for messages and reports.
  std::string Describe() const;

  const std::variant<Normal, Uniform, Fixed>& form() const { return form_; }

 private:
  explicit Distribution(std::variant<Normal, Uniform, Fixed> form) : form_(form) {}
  std::variant<Normal, Uniform, Fixed> form_;
};

}  // namespace vstcal

#include "vstcal/sensitivity/moments.h"

#include <algorithm>
#include <cmath>

namespace vstcal {

void Moments::Add(double x) {
  const double n1 = static_cast<double>(count);
  ++count;
  const double n = static_cast<double>(count);
  const double delta = x - mean;
  const double delta_n = delta / n;
  const double delta_n2 = delta_n * delta_n;
  const double term1 = delta * delta_n * n1;
  mean += delta_n;
  m4 += term1 * delta_n2 * (n * n - 3 * n + 3) + 6 * delta_n2 * m2 - 4 * delta_n * m3;
  m3 += term1 * delta_n * (n - 2) - 3 * delta_n * m2;
  m2 += term1;
  min = std::min(min, x);
  max = std::max(max, x);
}

void Moments::Merge(const Moments& other) {
  if (other.count == 0) return;
  if (count == 0) {
    *this = other;
    return;
  }
  const double na = static_cast<double>(count), nb = static_cast<double>(other.count);
  const double n = na + nb;
  const double delta = other.mean - mean;
  const double delta2 = delta * delta;
  const double m2_new = m2 + other.m2 + delta2 * na * nb / n;
  const double m3_new = m3 + other.m3 + delta * delta2 * na * nb * (na - nb) / (n * n) +
                        3 * delta * (na * other.m2 - nb * m2) / n;
  const double m4_new = m4 + other.m4 + delta2 * delta2 * na * nb * (na * na - na * nb + nb * nb) / (n * n * n) +
                        6 * delta2 * (na * na * other.m2 + nb * nb * m2) / (n * n) +
                        4 * delta * (na * other.m3 - nb * m3) / n;
  mean += delta * nb / n;
  m2 = m2_new;
  m3 = m3_new;
  m4 = m4_new;
  count += other.count;
  min = std::min(min, other.min);
  max = std::max(max, other.max);
}

double Moments::Variance() const { return count > 1 ? m2 / static_cast<double>(count - 1) : 0.0; }

double Moments::StandardDeviation() const { return std::sqrt(Variance()); }

double Moments::Rms() const {
  return count > 0 ? std::sqrt(mean * mean + m2 / static_cast<double>(count)) : 0.0;
}

double Moments::StandardDeviationStandardError() const {
  if (count < 4 || m2 <= 0) return 0.0;
  const double n = static_cast<double>(count);
  const double variance = Variance();
  const double mu4 = m4 / n;
  const double var_s2 = std::max(0.0, (mu4 - variance * variance * (n - 3) / (n - 1)) / n);
  return std::sqrt(var_s2) / (2 * std::sqrt(variance));
}

}  // namespace vstcal

#include "vstcal/geometry/registration_error.h"

namespace vstcal {

template RegistrationErrorOf<double> RegistrationError(const Vec3<double>&, const Vec3<double>&, const Vec3<double>&);
template bool TriangulateMidpoint(const Vec3<double>&, const Vec3<double>&, const Vec3<double>&, const Vec3<double>&,
                                  Vec3<double>*);

}  // namespace vstcal

// Every enum⇄name table: values and names unique, both directions inverse, and the words the file
// formats and command lines document (docs/formats.md, docs/tools/) spelled as documented.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "vstcal/estimators/dlt.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/calib/tsai.h"
#include "vstcal/capture/detect.h"
#include "vstcal/capture/target.h"
#include "vstcal/core/enum_names.h"
#include "vstcal/estimators/refine_options.h"
#include "vstcal/report/reprojection_report.h"
#include "vstcal/report/stereo_report.h"
#include "vstcal/sensitivity/derivatives.h"
#include "vstcal/sensitivity/unit_points.h"
#include "vstcal/stereo/display_plan.h"
#include "vstcal/stereo/registration.h"

namespace vstcal {
namespace {

template <typename E, size_t N>
void ExpectBijective(const EnumNames<E, N>& table, const std::string& documented) {
  std::set<int> values;
  std::set<std::string_view> names;
  for (const EnumName<E>& entry : table) {
    EXPECT_TRUE(values.insert(static_cast<int>(entry.value)).second) << entry.name;
    EXPECT_TRUE(names.insert(entry.name).second) << entry.name;
    EXPECT_EQ(NameOf(table, entry.value), entry.name);
    EXPECT_EQ(FromName(table, entry.name), entry.value);
  }
  // Enumerators are 0..N−1 in these enums: the table names each of them.
  for (size_t v = 0; v < N; ++v) EXPECT_NE(NameOf(table, static_cast<E>(v)), "?") << documented;
  EXPECT_EQ(FromName(table, "no-such-name"), std::nullopt);
  EXPECT_EQ(JoinedNames(table), documented);
}

TEST(EnumNames, TablesAreCompleteAndSpelledAsDocumented) {
  ExpectBijective(kRegistrationModeNames, "\"left\", \"per-eye\" or \"joint\"");
  ExpectBijective(kViewerNames, "\"none\", \"hmd\" or \"screen\"");
  ExpectBijective(kTargetTypeNames, "\"chessboard\", \"charuco\", \"apriltag-grid\" or \"aprilgrid\"");
  ExpectBijective(kDetectionStatusNames, "\"found\", \"not-found\" or \"rejected\"");
  ExpectBijective(kChessboardFinderNames, "\"classic\", \"sector-based\" or \"classic+sector-based\"");
  ExpectBijective(kCornerRefinerNames, "\"symmetry\", \"cornersubpix\" or \"none\"");
  ExpectBijective(kExclusionNames, "\"none\", \"behind-camera\", \"no-pose\", \"not-measured\" or \"no-ray\"");
  ExpectBijective(kStereoExclusionNames,
                  "\"none\", \"left-only\", \"right-only\", \"no-pose\", \"no-ray\", \"behind\" or \"not-measured\"");
  ExpectBijective(kSamplingMethodNames, "\"pseudo-random\" or \"sobol\"");
  ExpectBijective(kDerivativeMethodNames, "\"autodiff\" or \"central-difference\"");
  ExpectBijective(DltOptions::kSolverNames, "\"normal-equations\" or \"svd\"");
  ExpectBijective(TsaiOptions::kVariantNames, "\"auto\", \"coplanar\" or \"non-coplanar\"");
  ExpectBijective(CalibrationOptions::kPlanePrincipalPointNames, "\"no\", \"yes\" or \"prior\"");
  ExpectBijective(RefineOptions::kLossNames, "\"none\", \"huber\" or \"cauchy\"");
}

TEST(EnumNames, UnknownValueIsQuestionMark) {
  EXPECT_EQ(NameOf(kViewerNames, static_cast<Viewer>(7)), "?");
}

}  // namespace
}  // namespace vstcal

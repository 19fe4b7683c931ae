// err-sim's output tables (errsim/outputs.h) against the layout the file formats document
// (docs/formats.md#err-sim-report, #err-sim-sweep): the names, slots and report keys derived from
// kMeasures, kTotals and kVectorOutputs must be the ones the files have always had.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vstcal/errsim/outputs.h"
#include "vstcal/formats/errsim/report_keys.h"

namespace vstcal {
namespace {

// A test point's output names in slot order, as MeasureOffset places them.
std::vector<std::string> PointNames(OutputSet set, bool surface) {
  std::vector<std::string> names(PointMeasures(set, surface));
  for (const MeasureDecl& d : kMeasures) {
    if (d.needs_surface && !surface) continue;
    for (int e = 0; e < SlotsOf(d.scope); ++e) {
      const int slot = MeasureOffset(set, d.measure, e);
      if (slot < 0) continue;
      EXPECT_TRUE(names.at(slot).empty()) << "two measures in slot " << slot;
      names.at(slot) = MeasureName(d.measure, e);
    }
  }
  return names;
}

TEST(ErrsimOutputs, MeasureSlotsAndNamesAreTheDocumentedLayout) {
  const std::vector<std::string> full = {
      "image.left.pixel_px",      "image.right.pixel_px",  "misregistration.linear",    "misregistration.lateral",
      "misregistration.depth",    "misregistration.depth_abs", "misregistration.angular_deg", "misperception.linear",
      "misperception.lateral",    "misperception.depth",   "misperception.depth_abs",   "misperception.angular_deg",
      "occlusion.left.wrong",     "occlusion.right.wrong"};
  EXPECT_EQ(PointNames(OutputSet::kFull, true), full);
  EXPECT_EQ(PointNames(OutputSet::kFull, false), std::vector<std::string>(full.begin(), full.end() - 2));
  const std::vector<std::string> totals = {"image.left.pixel_px", "image.right.pixel_px", "misregistration.linear",
                                           "misperception.linear", "occlusion.left.wrong", "occlusion.right.wrong"};
  EXPECT_EQ(PointNames(OutputSet::kTotals, true), totals);
  EXPECT_EQ(PointNames(OutputSet::kTotals, false), std::vector<std::string>(totals.begin(), totals.end() - 2));
  EXPECT_EQ(MeasureOffset(OutputSet::kTotals, ErrorMeasure::kMisregistrationLateral), -1);
}

TEST(ErrsimOutputs, ReportKeysAreTheDocumentedOnes) {
  EXPECT_EQ(MeasurePointer(ErrorMeasure::kImagePixel, 1), "image/right/pixel_px");
  EXPECT_EQ(MeasurePointer(ErrorMeasure::kMisregistrationDepthAbs), "misregistration/depth_abs");
  EXPECT_EQ(MeasurePointer(ErrorMeasure::kMisperceptionAngular), "misperception/angular_deg");
  // A decision's rate object {wrong_rate, standard_error} sits at occlusion.<eye>.
  EXPECT_EQ(MeasurePointer(ErrorMeasure::kWrongOcclusion, 0), "occlusion/left");
  EXPECT_EQ(RateKey(ErrorMeasure::kWrongOcclusion), "wrong_rate");
  EXPECT_EQ(TotalKey(Total::kImage), "image_rms_px");
  EXPECT_EQ(TotalKey(Total::kMisperception), "misperception_rms");
  EXPECT_EQ(TotalKey(Total::kWrongOcclusion), "wrong_occlusion_rate");
  EXPECT_EQ(ShareKey(Total::kMisregistration), "share_of_misregistration_ms");
  EXPECT_EQ(BudgetMeasureKey(Total::kImage), "image");
}

TEST(ErrsimOutputs, VectorOutputsAreTheDocumentedLayout) {
  std::vector<std::string> names(kVectorOutputsPerPoint);
  for (const VectorOutputDecl& d : kVectorOutputs) {
    for (int e = 0; e < SlotsOf(d.scope); ++e) {
      for (int c = 0; c < d.size; ++c) names.at(VectorOffset(d.output, e) + c) = VectorOutputName(d.output, e, c);
    }
  }
  const std::vector<std::string> expected = {"left.du_px",          "left.dv_px",          "right.du_px",
                                             "right.dv_px",         "misregistration.dx",  "misregistration.dy",
                                             "misregistration.dz",  "misperception.dx",    "misperception.dy",
                                             "misperception.dz"};
  EXPECT_EQ(names, expected);
}

}  // namespace
}  // namespace vstcal

// A display that is not the camera (docs/math/vst-chain.md#display-fov, issue 21 item 5): the
// chain's display.field_of_view_deg makes the camera's image span the display's own field, a
// nominal magnification M = tan(φ_d/2)/tan(φ_c/2) that is part of the error-free chain. Closed form
// on a parallel pinhole rig with the eyes on the cameras' baseline line, o behind it: the eyes see a
// point P = (X, Y, Z) (hmd frame) at (X, Y·M_y/M_x, Z/M_x − o) — depth scaled by 1/M, lateral
// position kept, whatever the virtual image distance — and err-sim's systematic misperception is
// that, exactly; the misregistration of the error-free chain stays 0. The field's bad values name
// it; a written chain reads back the same.
#include <gtest/gtest.h>

#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/chain_writer.h"
#include "vstcal/json/json_reader.h"

namespace vstcal {
namespace {

constexpr double kFovFocal = 700.0, kFovWidth = 1280, kFovHeight = 720;
const Provenance kFovProvenance{"errsim_display_fov_test", {}, std::nullopt};

OrderedJson FovPose(double tx, double ty, double tz) { return {{"rotvec_deg", {0.0, 0.0, 0.0}}, {"t", {tx, ty, tz}}}; }

// The angle a display must span for magnification m over `half` px of a camera of focal f.
double FieldFor(double m, double half, double f) { return 2 * RadToDeg(std::atan(m * half / f)); }

// The hmd at the world origin, parallel pinhole cameras 63 mm apart on hmd x, the eyes at
// (0, 0, −o) ± 31.5 mm, four test points; `fov` the display's field_of_view_deg (null: none).
OrderedJson FovChain(const OrderedJson& fov, double o, const OrderedJson& image_distance) {
  const OrderedJson camera = {{"image_size", {kFovWidth, kFovHeight}},
                              {"K", {{kFovFocal, 0.0, 639.5}, {0.0, kFovFocal, 359.5}, {0.0, 0.0, 1.0}}},
                              {"distortion", {{"model", "none"}}}};
  OrderedJson c;
  c["format"] = "vstcal/vst-chain@1";
  c["length_unit"] = "mm";
  c["samples"] = 100;
  c["seed"] = 1;
  c["frames"] = {{"tracker_from_world", FovPose(0, 0, 0)},
                 {"hmd_from_tracker", FovPose(0, 0, 0)},
                 {"camera_from_hmd", {{"left", FovPose(31.5, 0, 0)}, {"right", FovPose(-31.5, 0, 0)}}},
                 {"world_from_object", FovPose(0, 0, 0)}};
  c["cameras"] = {{"left", camera}, {"right", camera}};
  c["display"] = {{"ipd", 63.0}, {"eye_centre", {0.0, 0.0, -o}}, {"virtual_image_distance", image_distance}};
  if (!fov.is_null()) c["display"]["field_of_view_deg"] = fov;
  c["test_points"] = {{{"name", "axis"}, {"world", {0.0, 0.0, 1500.0}}},
                      {{"name", "near"}, {"world", {-80.0, 40.0, 500.0}}},
                      {{"name", "aside"}, {"world", {200.0, -100.0, 1200.0}}},
                      {{"name", "far"}, {"world", {300.0, 150.0, 4000.0}}}};
  c["sources"] = OrderedJson::object();
  return c;
}

ChainSpec FovSpec(const OrderedJson& chain) { return ChainSpecFromJson(JsonDocument::Parse(chain.dump(), "chain.json"), "."); }

std::string FovError(const OrderedJson& chain) {
  try {
    BuildChainModel(FovSpec(chain));
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// The error-free chain's misperception against (0, Y(M_y/M_x − 1), Z/M_x − o − Z).
void ExpectSystematic(const OrderedJson& chain, double mx, double my, double o) {
  const ChainModel model = BuildChainModel(FovSpec(chain));
  const ChainEvaluator evaluator(model);
  const std::vector<double> zero(model.parameters.size(), 0.0);
  ChainSample<double> sample(evaluator.num_points());
  evaluator.Evaluate(zero.data(), &sample);
  for (size_t k = 0; k < evaluator.num_points(); ++k) {
    const Eigen::Vector3d p = model.geometry.test_points[k].point_in_world;  // the hmd frame is the world's
    const Eigen::Vector3d expected(0, p.y() * (my / mx - 1), p.z() / mx - o - p.z());
    SCOPED_TRACE(model.geometry.test_points[k].name);
    EXPECT_LT((evaluator.systematic(k).offset - expected).norm(), 1e-9 * p.norm()) << evaluator.systematic(k).offset.transpose();
    // Display-only: the overlay and the video go through the same display, so no misregistration.
    EXPECT_LT((sample.points[k].overlay - sample.points[k].seen).norm(), 1e-9 * p.norm());
  }
}

TEST(DisplayFieldOfView, AMagnifiedDisplayScalesTheDepthByOneOverM) {
  for (const double m : {1.0, 1.25, 0.8, 1.6}) {
    for (const double o : {0.0, 115.0}) {
      for (const OrderedJson& d : {OrderedJson("infinity"), OrderedJson(1500.0)}) {
        SCOPED_TRACE(::testing::Message() << "M " << m << ", o " << o << ", D " << d.dump());
        ExpectSystematic(FovChain(FieldFor(m, kFovWidth / 2, kFovFocal), o, d), m, m, o);
      }
    }
  }
}

// A vertical field of its own magnifies the height by M_y: the eyes see Y·M_y/M_x.
TEST(DisplayFieldOfView, AVerticalFieldOfItsOwnScalesTheHeight) {
  const double mx = 1.2, my = 0.9;
  ExpectSystematic(FovChain({FieldFor(mx, kFovWidth / 2, kFovFocal), FieldFor(my, kFovHeight / 2, kFovFocal)}, 50, "infinity"), mx,
                   my, 50);
  // Per eye: both eyes given the same field are the same chain as one field for both.
  const OrderedJson one = FovChain(90.0, 0, 1500.0), each = FovChain({{"left", 90.0}, {"right", 90.0}}, 0, 1500.0);
  EXPECT_EQ(ChainDigest(BuildChainModel(FovSpec(one))), ChainDigest(BuildChainModel(FovSpec(each))));
  EXPECT_NE(ChainDigest(BuildChainModel(FovSpec(one))), ChainDigest(BuildChainModel(FovSpec(FovChain(nullptr, 0, 1500.0)))));
}

TEST(DisplayFieldOfView, WrittenChainReadsBackTheSame) {
  for (const OrderedJson& fov : {OrderedJson(90.0), OrderedJson({100.0, 60.0}), OrderedJson({{"right", 70.0}})}) {
    const OrderedJson chain = FovChain(fov, 0, 1500.0);
    const OrderedJson written = ChainSpecToJson(FovSpec(chain), kFovProvenance);
    EXPECT_EQ(ChainDigest(BuildChainModel(FovSpec(written))), ChainDigest(BuildChainModel(FovSpec(chain)))) << fov.dump();
    EXPECT_EQ(ChainSpecToJson(FovSpec(written), kFovProvenance).dump(), written.dump()) << fov.dump();
  }
}

TEST(DisplayFieldOfView, BadFieldsNameTheFieldAndTheFix) {
  const std::string fix = "give the angle the camera's image spans on the display, 0 < φ < 180 (e.g. 90), or delete the field to show the camera's own";
  EXPECT_EQ(FovError(FovChain(0.0, 0, 1500.0)),
            "chain.json: display.field_of_view_deg: must lie strictly between 0 and 180 degrees, got 0.0; " + fix);
  EXPECT_EQ(FovError(FovChain(180.0, 0, 1500.0)),
            "chain.json: display.field_of_view_deg: must lie strictly between 0 and 180 degrees, got 180.0; " + fix);
  EXPECT_EQ(FovError(FovChain({90.0, -5.0}, 0, 1500.0)),
            "chain.json: display.field_of_view_deg[1]: must lie strictly between 0 and 180 degrees, got -5.0; " + fix);
  EXPECT_EQ(FovError(FovChain({{"left", 90.0}, {"right", 200.0}}, 0, 1500.0)),
            "chain.json: display.field_of_view_deg.right: must lie strictly between 0 and 180 degrees, got 200.0; " + fix);
  const std::string eye = FovError(FovChain({{"centre", 90.0}}, 0, 1500.0));
  EXPECT_TRUE(eye.starts_with("chain.json: display.field_of_view_deg.centre: ")) << eye;
}

}  // namespace
}  // namespace vstcal

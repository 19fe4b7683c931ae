#include "vstcal/estimators/free_intrinsics.h"

#include <algorithm>
#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/core/suggest.h"

namespace vstcal {
namespace {

bool Named(const std::vector<std::string>& list, std::string_view name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

// Every distortion term any model has, each once, in the order the models first name them.
std::vector<std::string_view> AllDistortionTerms() {
  std::vector<std::string_view> terms;
  ForEachLensModel([&](auto model) {
    for (auto it = decltype(model)::kParamNames.begin() + kNumIntrinsicParams; it != decltype(model)::kParamNames.end(); ++it) {
      if (std::find(terms.begin(), terms.end(), *it) == terms.end()) terms.push_back(*it);
    }
  });
  return terms;
}

}  // namespace

AnyLensModel RefinedModel(const AnyLensModel& given, const RefineOptions& options) {
  AnyLensModel initial = given;
  if (!options.lens_model.empty()) {
    const auto named = LensModelFromName(options.lens_model);
    if (!named) {
      throw InputError("lens_model: unknown lens model \"" + options.lens_model + "\"; use one of " + KnownLensModelNames());
    }
    if (!LensModelExtends(*named, initial)) {
      throw InputError("lens_model: \"" + options.lens_model + "\" does not extend the start's model \"" +
                       std::string(LensModelName(initial)) + "\"; start from a pinhole or from that model");
    }
    initial = *named;
  }
  const std::vector<std::string_view> known = AllDistortionTerms();
  for (const std::string& term : options.free_distortion) {
    if (std::find(known.begin(), known.end(), term) == known.end()) {
      throw InputError("--distortion: unknown term \"" + term + "\"; " + SuggestKey(term, known) +
                       ", or none for no distortion");
    }
  }
  std::optional<AnyLensModel> chosen;
  ForEachLensModel([&](auto model) {
    // Only a model that is the initial one with terms appended: a fisheye stays a fisheye.
    if (chosen || !LensModelExtends(model, initial)) return;
    const auto names = LensModelParamNames(model);
    const bool has_all = std::all_of(options.free_distortion.begin(), options.free_distortion.end(), [&](const std::string& t) {
      return std::find(names.begin() + kNumIntrinsicParams, names.end(), t) != names.end();
    });
    if (has_all) chosen = model;
  });
  if (!chosen) {
    // Only a fisheye gets here: its k's are not the Brown–Conrady ones, and nothing extends it.
    const auto names = LensModelParamNames(initial);
    std::string own;
    for (auto it = names.begin() + kNumIntrinsicParams; it != names.end(); ++it) own += (own.empty() ? "" : ", ") + std::string(*it);
    throw InputError("--distortion: no lens model extends \"" + std::string(LensModelName(initial)) +
                     "\" by the terms named; free only its own terms (" + own + ")");
  }
  return *chosen;
}

std::vector<double> PromotedParams(const Camera& initial, const AnyLensModel& model) {
  // Layouts are prefixes of each other (lens_models.h): a larger model starts with a smaller one.
  std::vector<double> params(LensModelNumParams(model), 0.0);
  VSTCAL_CHECK(LensModelExtends(model, initial.model), "promotion only appends parameters");
  std::copy(initial.params.begin(), initial.params.end(), params.begin());
  return params;
}

std::vector<std::string> FreeIntrinsics::MovedParams(const AnyLensModel& model) const {
  const auto all = LensModelParamNames(model);
  std::vector<std::string> moved;
  for (Eigen::Index i = 0; i < basis.rows(); ++i) {
    if (!basis.row(i).isZero(0)) moved.emplace_back(all[i]);
  }
  return moved;
}

Eigen::MatrixXd FreeIntrinsics::MovedBasis() const {
  std::vector<Eigen::Index> moved;
  for (Eigen::Index i = 0; i < basis.rows(); ++i) {
    if (!basis.row(i).isZero(0)) moved.push_back(i);
  }
  Eigen::MatrixXd B(static_cast<Eigen::Index>(moved.size()), basis.cols());
  for (size_t k = 0; k < moved.size(); ++k) B.row(static_cast<Eigen::Index>(k)) = basis.row(moved[k]);
  return B;
}

FreeIntrinsics MakeFreeIntrinsics(const AnyLensModel& model, const RefineOptions& options) {
  VSTCAL_CHECK(!options.focal_aspect || (options.free_focal && *options.focal_aspect > 0),
               "a held aspect ties two free focal lengths by a positive ratio");
  const auto all = LensModelParamNames(model);
  std::vector<std::pair<std::string, Eigen::VectorXd>> columns;
  auto unit = [&](int i) {
    Eigen::VectorXd c = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(all.size()));
    c(i) = 1;
    return c;
  };
  if (options.free_focal && options.focal_aspect) {
    Eigen::VectorXd c = unit(1);
    c(0) = *options.focal_aspect;
    columns.emplace_back("f", c);
  } else if (options.free_focal) {
    columns.emplace_back("fx", unit(0));
    columns.emplace_back("fy", unit(1));
  }
  if (options.free_principal_point) {
    columns.emplace_back("cx", unit(2));
    columns.emplace_back("cy", unit(3));
  }
  if (options.free_skew) columns.emplace_back("s", unit(4));
  for (size_t i = kNumIntrinsicParams; i < all.size(); ++i) {
    if (Named(options.free_distortion, all[i])) columns.emplace_back(std::string(all[i]), unit(static_cast<int>(i)));
  }
  FreeIntrinsics free;
  free.basis.resize(static_cast<Eigen::Index>(all.size()), static_cast<Eigen::Index>(columns.size()));
  for (size_t k = 0; k < columns.size(); ++k) {
    free.names.push_back(columns[k].first);
    free.basis.col(static_cast<Eigen::Index>(k)) = columns[k].second;
  }
  return free;
}

std::vector<ResolvedPrior> ResolvePriors(const AnyLensModel& model, const FreeIntrinsics& free,
                                         const RefineOptions& options) {
  const auto all = LensModelParamNames(model);
  std::vector<ResolvedPrior> resolved;
  for (size_t k = 0; k < options.priors.size(); ++k) {
    const IntrinsicPrior& prior = options.priors[k];
    const std::string field = "refinement prior on \"" + prior.parameter + "\"";
    const auto it = std::find(all.begin(), all.end(), prior.parameter);
    if (it == all.end()) {
      throw InputError(field + ": the " + std::string(LensModelName(model)) + " model has no such parameter; " +
                       SuggestKey(prior.parameter, all));
    }
    const int index = static_cast<int>(it - all.begin());
    if (free.basis.cols() == 0 || free.basis.row(index).isZero(0)) {
      throw InputError(field + ": the refinement does not estimate " + prior.parameter +
                       " (a prior applies to an estimated parameter); estimate it or drop the prior");
    }
    if (!std::isfinite(prior.value) || !std::isfinite(prior.sigma) || !(prior.sigma > 0)) {
      throw InputError(field + ": needs a finite value and a sigma > 0, got value " + std::to_string(prior.value) +
                       ", sigma " + std::to_string(prior.sigma) + "; give a positive sigma (a hold is a separate choice)");
    }
    for (const ResolvedPrior& r : resolved) {
      if (r.index == index) throw InputError(field + ": given twice; keep one");
    }
    resolved.push_back({index, prior.value, prior.sigma});
  }
  return resolved;
}

std::vector<HeldIntrinsic> HeldIntrinsics(const AnyLensModel& model, const std::vector<double>& params,
                                          const RefineOptions& options) {
  const auto all = LensModelParamNames(model);
  std::vector<HeldIntrinsic> held;
  if (!options.free_focal) {
    held.push_back({"fx", params[intrinsic::kFx], "held by the caller (RefineOptions::free_focal)"});
    held.push_back({"fy", params[intrinsic::kFy], "held by the caller (RefineOptions::free_focal)"});
  } else if (options.focal_aspect) {
    held.push_back({"fx/fy", *options.focal_aspect, options.focal_aspect_held_because});
  }
  if (!options.free_principal_point) {
    held.push_back({"cx", params[intrinsic::kCx], options.principal_point_held_because});
    held.push_back({"cy", params[intrinsic::kCy], options.principal_point_held_because});
  }
  if (!options.free_skew) held.push_back({"s", params[intrinsic::kSkew], "not estimated (--skew frees it)"});
  for (size_t i = kNumIntrinsicParams; i < all.size(); ++i) {
    if (!Named(options.free_distortion, all[i])) {
      held.push_back({std::string(all[i]), params[i], "not named by --distortion"});
    }
  }
  return held;
}

}  // namespace vstcal

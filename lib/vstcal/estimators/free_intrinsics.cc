#include "vstcal/estimators/free_intrinsics.h"

#include <algorithm>
#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/core/suggest.h"
#include "vstcal/core/option_name.h"

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
      throw InputError(VSTCAL_OPT("distortion") ": unknown term \"" + term + "\"; " + SuggestKey(term, known) +
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
    throw InputError(VSTCAL_OPT("distortion") ": no lens model extends \"" + std::string(LensModelName(initial)) +
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

std::vector<std::string> DistortionTermsFromList(const std::string& list) {
  std::vector<std::string> terms;
  if (list == "none") return terms;
  for (size_t start = 0; start <= list.size();) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string term = list.substr(start, comma - start);
    if (term.empty()) throw InputError(VSTCAL_OPT("distortion") ": empty term in \"" + list + "\"; give names like k1,k2,p1,p2 or none");
    if (std::find(terms.begin(), terms.end(), term) != terms.end()) {
      throw InputError(VSTCAL_OPT("distortion") ": \"" + term + "\" is named twice in \"" + list + "\"; name each term once");
    }
    terms.push_back(term);
    start = comma + 1;
  }
  return terms;
}

IntrinsicPrior StatedPrior(std::string parameter, double value, double sigma) {
  return {std::move(parameter), value, sigma, "stated by the user"};
}

void HoldIntrinsics(const std::vector<std::string>& names, RefineOptions* o) {
  const auto held = [&](const char* name) { return std::find(names.begin(), names.end(), name) != names.end(); };
  const std::string because = "held at the start's value, as asked: the sigmas are conditional on it";
  for (const auto& [a, b] : {std::pair{"fx", "fy"}, std::pair{"cx", "cy"}}) {
    if (held(a) != held(b)) {
      throw InputError(VSTCAL_OPT("hold") ": " + std::string(held(a) ? a : b) + " is held only with " + (held(a) ? b : a) +
                       " (the refinement moves them as a pair); hold " + a + "," + b);
    }
  }
  for (const std::string& name : names) {
    if (name == "fx" || name == "fy") {
      o->free_focal = false;
      o->focal_held_because = because;
    } else if (name == "cx" || name == "cy") {
      o->free_principal_point = false;
      o->principal_point_held_because = because;
    } else if (name == "s") {
      if (o->free_skew) throw InputError(VSTCAL_OPT("hold") ": s is held and " VSTCAL_OPT("skew") " frees it; give one of the two");
    } else {
      const auto named = std::find(o->free_distortion.begin(), o->free_distortion.end(), name);
      if (named == o->free_distortion.end()) {
        throw InputError(VSTCAL_OPT("hold") ": \"" + name + "\" is not an estimated lens parameter (fx fy cx cy s, or a "
                         "distortion term being estimated); name one of those");
      }
      o->free_distortion.erase(named);
    }
    for (const IntrinsicPrior& p : o->priors) {
      if (p.parameter == name) {
        throw InputError(VSTCAL_OPT("hold") ": " + name + " is held and also has a " VSTCAL_OPT("prior") "; give one of the two");
      }
    }
  }
}

std::vector<HeldIntrinsic> HeldIntrinsics(const AnyLensModel& model, const std::vector<double>& params,
                                          const RefineOptions& options) {
  const auto all = LensModelParamNames(model);
  std::vector<HeldIntrinsic> held;
  if (!options.free_focal) {
    held.push_back({"fx", params[intrinsic::kFx], options.focal_held_because});
    held.push_back({"fy", params[intrinsic::kFy], options.focal_held_because});
  } else if (options.focal_aspect) {
    held.push_back({"fx/fy", *options.focal_aspect, options.focal_aspect_held_because});
  }
  if (!options.free_principal_point) {
    held.push_back({"cx", params[intrinsic::kCx], options.principal_point_held_because});
    held.push_back({"cy", params[intrinsic::kCy], options.principal_point_held_because});
  }
  if (!options.free_skew) held.push_back({"s", params[intrinsic::kSkew], "not estimated (the skew is estimated only when asked)"});
  for (size_t i = kNumIntrinsicParams; i < all.size(); ++i) {
    if (!Named(options.free_distortion, all[i])) {
      held.push_back({std::string(all[i]), params[i], "not among the distortion terms estimated"});
    }
  }
  return held;
}

}  // namespace vstcal

// The chain as the sensitivity module sees it (lib/vstcal/sensitivity): a parameter space whose
// groups are the seven source keys, and two models over it —
//  - ErrorModel: the error measures of measures.h (magnitudes, angles, occlusion decisions), double
//    only (a norm has no derivative at zero error): Monte Carlo and Sobol indices;
//  - VectorModel: the signed vector errors of ChainEvaluator (px per eye, misregistration and
//    misperception in the hmd frame), templated: linear propagation and sweep slopes by ceres::Jet.
#pragma once

#include "vstcal/errsim/chain_model.h"
#include "vstcal/sensitivity/model.h"
#include "vstcal/sensitivity/parameter_space.h"

namespace vstcal {

// One parameter per θ slot, named as the slot, group = its source key, nominal 0 (an error's
// nominal value: a bias or a non-zero mean then shows as a mean shift in linear propagation).
ParameterSpace MakeParameterSpace(const ChainModel& model);

// Undefined (false) when any test point is undefined.
Model ErrorModel(const ChainModel& model);
Model VectorModel(const ChainModel& model);

// Names of VectorModel's outputs, per test point "<point>." followed by kVectorOutputs' components
// (outputs.h): left.du_px, left.dv_px, right.du_px, right.dv_px, misregistration.{dx,dy,dz},
// misperception.{dx,dy,dz} (hmd frame; the misperception relative to the systematic one).
std::vector<std::string> VectorOutputNames(const ChainModel& model);

}  // namespace vstcal

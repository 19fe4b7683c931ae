#include "vstcal/errsim/models.h"

#include <algorithm>
#include <memory>

#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/measures.h"

namespace vstcal {

ParameterSpace MakeParameterSpace(const ChainModel& model) {
  ParameterSpace space;
  for (const ChainParameter& p : model.parameters) {
    space.Add({p.name(), std::string(SourceKey(p.source)), p.distribution, 0.0});
  }
  return space;
}

Model ErrorModel(const ChainModel& model) {
  auto chain = std::make_shared<const ChainEvaluator>(model);
  auto outputs = std::make_shared<const ErrorOutputs>(model);
  return Model(model.parameters.size(), outputs->names(), [chain, outputs](const double* theta, double* y) {
    // Buffers per thread: the model is called concurrently and must not allocate per sample.
    thread_local ChainSample<double> sample(0);
    thread_local std::unique_ptr<bool[]> defined;
    const size_t points = chain->num_points();
    if (sample.points.size() != points || !defined) {
      sample.points.resize(points);
      defined.reset(new bool[points + 1]);
    }
    chain->Evaluate(theta, &sample);
    outputs->Measure(*chain, sample, theta, y, defined.get());
    return std::all_of(defined.get(), defined.get() + points, [](bool d) { return d; });
  });
}

Model VectorModel(const ChainModel& model) {
  return Model::Templated(model.parameters.size(), VectorOutputNames(model), ChainEvaluator(model));
}

std::vector<std::string> VectorOutputNames(const ChainModel& model) {
  std::vector<std::string> names;
  for (const ChainTestPoint& tp : model.geometry.test_points) {
    for (const VectorOutputDecl& d : kVectorOutputs) {
      for (int e = 0; e < SlotsOf(d.scope); ++e) {
        for (int c = 0; c < d.size; ++c) names.push_back(std::string(tp.name).append(".").append(VectorOutputName(d.output, e, c)));
      }
    }
  }
  return names;
}

}  // namespace vstcal

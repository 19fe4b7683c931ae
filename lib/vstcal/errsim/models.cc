#include "vstcal/errsim/models.h"

#include <memory>

#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/holloway.h"

namespace vstcal::errsim {

sensitivity::ParameterSpace MakeParameterSpace(const ChainModel& model) {
  sensitivity::ParameterSpace space;
  for (const ChainParameter& p : model.parameters) {
    space.Add({p.name, std::string(SourceKey(p.source)), p.distribution, 0.0});
  }
  return space;
}

sensitivity::Model ErrorModel(const ChainModel& model) {
  auto chain = std::make_shared<const ChainEvaluator>(model);
  auto outputs = std::make_shared<const ErrorOutputs>(model);
  return sensitivity::Model(model.parameters.size(), outputs->names(), [chain, outputs](const double* theta, double* y) {
    // One buffer per thread: the model is called concurrently and must not allocate per sample.
    thread_local ChainSample<double> sample(0);
    if (sample.points.size() != chain->num_points()) sample = ChainSample<double>(chain->num_points());
    chain->Evaluate(theta, &sample);
    return outputs->Measure(*chain, sample, theta, y);
  });
}

sensitivity::Model VectorModel(const ChainModel& model) {
  return sensitivity::Model::Templated(model.parameters.size(), VectorOutputNames(model), ChainEvaluator(model));
}

std::vector<std::string> VectorOutputNames(const ChainModel& model) {
  std::vector<std::string> names;
  for (const TestPoint& tp : model.geometry.test_points) {
    for (const char* n : {".left.du_px", ".left.dv_px", ".right.du_px", ".right.dv_px", ".dx", ".dy", ".dz"}) {
      names.push_back(tp.name + n);
    }
  }
  return names;
}

}  // namespace vstcal::errsim

#include "common/scheduler.h"

#include <charconv>
#include <cstring>

#include "vstcal/core/error.h"

namespace vstcal::tools {
namespace {

std::optional<uint64_t> Variable(const std::function<const char*(const char*)>& environment, const char* name) {
  const char* text = environment(name);
  if (!text) return std::nullopt;
  uint64_t v = 0;
  const char* end = text + std::strlen(text);
  const auto [ptr, ec] = std::from_chars(text, end, v);
  if (*text == '\0' || ec != std::errc() || ptr != end) {
    throw InputError(std::string("--shard auto: ") + name + " is \"" + text + "\", not a whole number; check the job's environment");
  }
  return v;
}

}  // namespace

std::pair<uint64_t, uint64_t> ShardFromScheduler(const std::function<const char*(const char*)>& environment,
                                                 std::optional<uint64_t> count, const std::string& count_flag) {
  uint64_t index = 0, shards = 0;
  if (const auto id = Variable(environment, "SLURM_ARRAY_TASK_ID")) {
    const auto task_count = Variable(environment, "SLURM_ARRAY_TASK_COUNT");
    if (!task_count) throw InputError("--shard auto: SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not; run inside an sbatch --array job");
    const uint64_t min = Variable(environment, "SLURM_ARRAY_TASK_MIN").value_or(0);
    const uint64_t step = Variable(environment, "SLURM_ARRAY_TASK_STEP").value_or(1);
    if (*id < min || step == 0 || (*id - min) % step != 0) {
      throw InputError("--shard auto: SLURM_ARRAY_TASK_ID " + std::to_string(*id) + " is not MIN + k·STEP (MIN " + std::to_string(min) +
                       ", STEP " + std::to_string(step) + "); submit the array as --array=MIN-MAX[:STEP]");
    }
    index = (*id - min) / step;
    shards = *task_count;
    if (count && *count != shards) {
      throw InputError(count_flag + ": " + std::to_string(*count) + " disagrees with SLURM_ARRAY_TASK_COUNT " + std::to_string(shards) +
                       "; drop " + count_flag + " under Slurm");
    }
  } else if (const auto completion = Variable(environment, "JOB_COMPLETION_INDEX")) {
    if (!count) {
      throw InputError("--shard auto: JOB_COMPLETION_INDEX is set (a Kubernetes Indexed Job) but the shard count is not; add " +
                       count_flag + " N, the Job's completions");
    }
    index = *completion;
    shards = *count;
  } else {
    throw InputError("--shard auto: neither SLURM_ARRAY_TASK_ID (a Slurm array job) nor JOB_COMPLETION_INDEX (a Kubernetes "
                     "Indexed Job) is set; give --shard i/N instead");
  }
  if (shards == 0 || index >= shards) {
    throw InputError("--shard auto: shard " + std::to_string(index) + " of " + std::to_string(shards) +
                     " is not below the count; check the array range or " + count_flag);
  }
  return {index, shards};
}

}  // namespace vstcal::tools

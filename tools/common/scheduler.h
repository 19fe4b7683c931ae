// `--shard auto`: the shard index and count from the batch scheduler running the process
// (docs/scale.md). A Slurm array job (sbatch --array=MIN-MAX[:STEP]) sets SLURM_ARRAY_TASK_ID,
// SLURM_ARRAY_TASK_COUNT and SLURM_ARRAY_TASK_MIN (and _STEP): shard (ID − MIN)/STEP of COUNT. A
// Kubernetes Indexed Job sets JOB_COMPLETION_INDEX (0 … completions − 1) but not the count, which
// the user gives (--shard-count, the Job's completions).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>

namespace vstcal::tools {

// {i, N}. `environment(name)` returns a variable's value or nullptr (std::getenv in the tools).
// InputError naming the variable or `count_flag` when neither scheduler is detected, a value is not
// a whole number, the index is not below the count, or `count` disagrees with Slurm's.
std::pair<uint64_t, uint64_t> ShardFromScheduler(const std::function<const char*(const char*)>& environment,
                                                 std::optional<uint64_t> count, const std::string& count_flag);

}  // namespace vstcal::tools

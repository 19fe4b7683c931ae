// Tests that repeat one computation many times to measure a statistic (a Monte Carlo spread, an
// accuracy over dozens of rendered views) run in the Release suite only. Under ASan+UBSan each
// such test cost 20–200 CPU-seconds, a third of the sanitizer suite, while every code path it
// takes is run under the sanitizers by smaller tests (docs/reliability.md#ci-time names them).
// The test is reported as skipped, with the reason, so the sanitizer run says what it left out.
#pragma once

#include <gtest/gtest.h>

#if defined(__SANITIZE_ADDRESS__)
#define VSTCAL_STATISTICAL_TEST_RELEASE_ONLY() \
  GTEST_SKIP() << "statistical repetition: run in the Release suite (tests/support/sanitizers.h)"
#else
#define VSTCAL_STATISTICAL_TEST_RELEASE_ONLY() static_cast<void>(0)
#endif

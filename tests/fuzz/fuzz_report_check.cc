// vstcal/err-sim-report@3 (and @2) as err-sim check reads it (docs/formats.md#err-sim-report): the run and
// the metrics with their Monte Carlo standard errors. The reader has no writer, so there is no
// fixed point: every input is either read or refused with an InputError.
#include "harness.h"
#include "vstcal/formats/errsim/report_reader.h"

VSTCAL_FUZZ_TARGET(report_check, text) {
  (void)vstcal::ReadReportForCheck(vstcal::JsonDocument::Parse(text, "fuzz.json"));
}

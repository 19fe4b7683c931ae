// JUnit XML, the test-report format CI systems read (GitLab's `artifacts:reports:junit`, GitHub
// actions that publish test results, Jenkins): one <testsuite> of one <testcase> per check, a
// <failure> for a failed one, the verdict and its numbers in <system-out> for every one
// (docs/formats.md#junit). Text is escaped for XML 1.0; a byte XML cannot carry (a control
// character, invalid UTF-8) is written as the four characters \xNN.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "vstcal/core/check.h"

namespace vstcal {

// `suite` names the testsuite and every testcase's classname ("calib-compare", "err-sim check").
std::string JUnitXml(std::string_view suite, std::span<const CheckResult> results);

// Text as XML character data or an attribute value: & < > " ' escaped, and what XML 1.0 cannot
// hold (control characters other than tab, newline and return; bytes that are not UTF-8) as \xNN.
std::string XmlEscape(std::string_view text);

}  // namespace vstcal

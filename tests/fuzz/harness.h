// What every fuzz harness shares (docs/reliability.md#fuzzing). A harness is one file
// tests/fuzz/fuzz_<name>.cc holding
//
//   #include "harness.h"
//   VSTCAL_FUZZ_TARGET(name, text) {
//     const Thing t = vstcal::ThingFromJson(vstcal::JsonDocument::Parse(text, "fuzz.json"));
//     vstcal::fuzz::RequireFixedPoint(text, [](const std::string& s) { return Write(Read(s)); });
//   }
//
// and its seed corpus in tests/fuzz/corpus/<name>/ (a few small valid files): tests/fuzz/
// CMakeLists.txt finds it, ctest replays the corpus (fuzz_replay.<name>) and scripts/fuzz runs it
// under libFuzzer. For the replays every harness is compiled into one program (`fuzz_replay NAME
// CORPUS...`, one translation unit: the readers' headers are parsed once, and the CI's sanitizer
// pass links one program instead of twenty), so a harness's file-local names must differ from the
// other harnesses' (the build says so when two collide); under libFuzzer each harness is its own
// program. The body receives the input as text; InputError and DegenerateError are the
// documented answers to bad input, so they end the input quietly; any other exception (an
// InternalError, a non-finite number on its way to a file, a round trip that is no fixed point)
// aborts, which libFuzzer reports as a crash with the input that caused it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "vstcal/json/provenance.h"

namespace vstcal::fuzz {

// The provenance written by harnesses (fixed, so that written texts can be compared).
extern const Provenance kProvenance;

// Runs `body` on the input as described above.
void RunOne(const uint8_t* data, size_t size, void (*body)(const std::string&));

using Body = void (*)(const std::string&);

// Makes `body` the harness `name` of the replay program (VSTCAL_FUZZ_TARGET's static
// initialiser); aborts when the name is taken. Returns true.
bool Register(const char* name, Body body);

// The harness registered as `name`, or nullptr.
Body Find(const std::string& name);

// The registered names, sorted.
std::vector<std::string> Names();

// Aborts with `what` on stderr unless `ok`.
void Require(bool ok, const char* what);

// pass(text) is a read and a write. Aborts unless pass(pass(text)) == pass(text): a file read and
// written again is the same bytes on the second pass (docs/reliability.md#round-trips).
void RequireFixedPoint(const std::string& text, const std::function<std::string(const std::string&)>& pass);

}  // namespace vstcal::fuzz

#ifdef VSTCAL_FUZZ_LIBFUZZER
#define VSTCAL_FUZZ_TARGET(name, text)                                            \
  static void VstcalFuzzBody_##name(const std::string& text);                     \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {      \
    ::vstcal::fuzz::RunOne(data, size, &VstcalFuzzBody_##name);                   \
    return 0;                                                                     \
  }                                                                               \
  static void VstcalFuzzBody_##name(const std::string& text)
#else
#define VSTCAL_FUZZ_TARGET(name, text)                                            \
  static void VstcalFuzzBody_##name(const std::string& text);                     \
  static const bool kVstcalFuzzRegistered_##name =                               \
      ::vstcal::fuzz::Register(#name, &VstcalFuzzBody_##name);                    \
  static void VstcalFuzzBody_##name(const std::string& text)
#endif

#include "harness.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>

#include "vstcal/core/error.h"

namespace vstcal::fuzz {

const Provenance kProvenance{"fuzz", {"--fuzz"}, std::nullopt};

void RunOne(const uint8_t* data, size_t size, void (*body)(const std::string&)) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    body(text);
  } catch (const InputError&) {
    // The documented answer to bad input (exit code 2).
  } catch (const DegenerateError&) {
    // The documented answer to degenerate data (exit code 3).
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: unexpected exception (a bug): %s\n", e.what());
    std::abort();
  }
}

namespace {

std::map<std::string, Body>& Registry() {
  static std::map<std::string, Body> registry;  // built during static initialisation
  return registry;
}

}  // namespace

bool Register(const char* name, Body body) {
  if (!Registry().emplace(name, body).second) {
    std::fprintf(stderr, "fuzz: two harnesses are named %s\n", name);
    std::abort();
  }
  return true;
}

Body Find(const std::string& name) {
  const auto it = Registry().find(name);
  return it == Registry().end() ? nullptr : it->second;
}

std::vector<std::string> Names() {
  std::vector<std::string> names;
  for (const auto& [name, body] : Registry()) names.push_back(name);
  return names;
}

void Require(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz: %s\n", what);
  std::abort();
}

void RequireFixedPoint(const std::string& text, const std::function<std::string(const std::string&)>& pass) {
  const std::string once = pass(text);
  Require(pass(once) == once, "a file read and written again changed on the second pass");
}

}  // namespace vstcal::fuzz
